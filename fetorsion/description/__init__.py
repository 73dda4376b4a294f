"""Stage 1, the description: what the user wrote, read into frozen dataclasses in SI units.

Owns the crank, chain and network data types (:mod:`.model`), one reader per kind of file
(:mod:`.files` says which kind a file is; :mod:`.crank`, :mod:`.chain`, :mod:`.network`) over the
tables they share (:mod:`.tables`), the file reader that collects every problem
(:class:`.reader.Table`, :func:`.reader.read_toml`), length units, the defaults every later stage
uses (:mod:`.defaults`), and the short-bearing oil-film formulas (:mod:`.oilfilm`) that turn an
oil film in ``[bearings]`` into the bearing stiffness and damping every later stage reads. Hands a
:class:`~.model.Crank`, :class:`~.chain_model.Chain` or :class:`~.chain_model.Network` to every other stage;
imports no other stage.
"""
