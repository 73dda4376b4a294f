"""Stage 4, excitation: slider-crank kinematics, the cylinder pressure cycle and torque
harmonics (:mod:`.torque`), and the Campbell diagram with order severity (:mod:`.campbell`).

Takes a crank with ``[excitation]`` and :class:`~fetorsion.modes.TorsionalModes`; hands
order harmonics and crossings to the response stage and the report.
"""
