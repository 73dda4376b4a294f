"""Stage 1, the description: what the user wrote, read into frozen dataclasses in SI units.

Owns the crank and chain data types (:mod:`.crank`), the file reader that collects every
problem (:class:`.reader.Table`, :func:`.reader.read_toml`), length units and the defaults
every later stage uses (:mod:`.defaults`). Hands a :class:`~.model.Crank` or
:class:`~.model.Chain` to every other stage; imports no other stage.
"""
