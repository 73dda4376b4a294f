"""Stage 1, the description: what the user wrote, read into frozen dataclasses in SI units.

Owns the crank and chain data types (:mod:`.crank`), the file reader that collects every
problem (:class:`.reader.Table`, :func:`.reader.read_toml`), length units and the defaults
every later stage uses (:mod:`.defaults`). Hands a :class:`~.model.Crank` or
:class:`~.model.Chain` to every other stage; imports no other stage, but for the oil-film
formulas (:mod:`fetorsion.fe.oilfilm`, a leaf of numpy and scipy) that turn an oil film in
``[bearings]`` into the bearing stiffness and damping every later stage reads.
"""
