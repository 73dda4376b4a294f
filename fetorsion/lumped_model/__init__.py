"""Stage 3b, the lumped torsional chain: crank parts with equivalent lengths and inertias
(:mod:`.parts`) and the 5/6/17/19/21-DOF partitions (:mod:`.lumped`).

Takes a :class:`~fetorsion.description.model.Crank` (or a chain file); hands a
:class:`~fetorsion.lumped_model.lumped.LumpedResult`, which carries its stations and its pin
weights, and :class:`~fetorsion.modes.TorsionalModes` to the excitation stage.
"""
