"""Stage 4, excitation: slider-crank kinematics, the cylinder pressure cycle and torque
harmonics (:mod:`.torque`), every cylinder's load as the consumers read it (:mod:`.loads`: the
one load seam), and the Campbell diagram with order severity (:mod:`.campbell`).

Takes a crank with ``[excitation]`` and :class:`~fetorsion.modes.TorsionalModes`; hands
order harmonics and crossings to the response stage and the report.
"""
