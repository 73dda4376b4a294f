"""A chain file: inertias and springs given directly (``[chain]``), with the tables a crank
description shares (:mod:`.tables`)."""

from __future__ import annotations

from pathlib import Path

from ..errors import DescriptionError, Problem
from .chain_fields import CHAIN_SCHEMA
from .chain_model import Chain
from .reader import Table, read_length_unit
from .excitation_table import read_chain_excitation, stated_damping_excitation
from .tables import (per_spring, read_engine, read_dampers, read_limits, read_variations, unique_problems,
                     uncertainty_bound_problems)


def parse_chain(data: dict, source: str = "<chain>", check_uncertainty: bool = True) -> Chain:
    """Build a :class:`Chain` from a parsed TOML mapping with a ``[chain]`` table.

    A chain may carry ``[engine]`` and ``[excitation]`` (read exactly as for a crank
    description, lengths in ``[units] length``) with ``chain.cylinder_stations`` saying which
    station (1-based) carries each cylinder.
    """
    problems: list[Problem] = []
    root = Table(data, "", problems, schema=CHAIN_SCHEMA)
    unit = read_length_unit(root, source) if ("engine" in data or "units" in data) else "m"
    t = root.table("chain")
    root.used.add("meta")  # free-form notes, not checked
    name = t.text("name", default=Path(source).stem)
    inertias = t.numbers("inertias_kgm2")
    stiffnesses = t.numbers("stiffnesses_nm_per_rad")
    labels = t.get("labels", [])
    absolute = t.numbers("absolute_damping_nms_per_rad", required=False)
    relative = t.numbers("relative_damping_nms_per_rad", required=False)
    loss = per_spring(t, "loss_factors", len(stiffnesses))
    stations = t.get("cylinder_stations", [])
    t.finish()
    n = len(inertias)
    labels = _check_lists(inertias, stiffnesses, absolute, relative, loss, labels, problems)

    engine = read_engine(root) if "engine" in data else None
    stations = _check_cylinder_stations(stations, n, engine, problems)
    dampers = read_dampers(root)
    limits = read_limits(root, torque_only=True)
    excitation, ex_table = read_chain_excitation(root, data, source, engine, problems)
    if excitation is not None:
        has_dampers = any(v > 0 for v in (*absolute, *relative, *loss))
        excitation = stated_damping_excitation(excitation, ex_table, has_dampers, "chain", problems)
    uncertainty, distributions = read_variations(root, data, problems)
    root.finish()
    if problems:
        raise DescriptionError(source, unique_problems(problems))
    labels = tuple(labels) if labels else tuple(f"inertia {i + 1}" for i in range(n))
    chain = Chain(name, inertias, stiffnesses, labels, absolute, relative, source, loss,
                  tuple(c - 1 for c in stations), engine, excitation, unit, data, dampers, limits,
                  uncertainty, distributions)
    if check_uncertainty:
        bounds = uncertainty_bound_problems(chain, parse_chain)
        if bounds:
            raise DescriptionError(source, bounds)
    return chain


def _check_lists(inertias, stiffnesses, absolute, relative, loss, labels, problems: list[Problem]) -> list:
    """Every rule of ``[chain]``'s lists (inertias, springs, dampers, labels) in turn, recorded in
    ``problems``; the labels, or [] where they were refused."""
    n = len(inertias)
    if inertias and n < 2:
        problems.append(Problem("chain.inertias_kgm2", list(inertias), "needs at least 2 inertias"))
    for i, v in enumerate(inertias):
        if not v > 0:
            problems.append(Problem(f"chain.inertias_kgm2[{i + 1}]", v, "must be > 0"))
    for i, v in enumerate(stiffnesses):
        if not v > 0:
            problems.append(Problem(f"chain.stiffnesses_nm_per_rad[{i + 1}]", v, "must be > 0"))
    if inertias and len(stiffnesses) != n - 1:
        problems.append(Problem("chain.stiffnesses_nm_per_rad", list(stiffnesses),
                                f"must have one spring fewer than inertias ({n - 1})"))
    if absolute and len(absolute) != n:
        problems.append(Problem("chain.absolute_damping_nms_per_rad", list(absolute),
                                f"must have one value per inertia ({n})"))
    if relative and len(relative) != n - 1:
        problems.append(Problem("chain.relative_damping_nms_per_rad", list(relative),
                                f"must have one value per spring ({n - 1})"))
    for key, values in (("absolute_damping_nms_per_rad", absolute), ("relative_damping_nms_per_rad", relative),
                        ("loss_factors", loss)):
        for i, v in enumerate(values):
            if v < 0:
                problems.append(Problem(f"chain.{key}[{i + 1}]", v, "must be >= 0"))
    if not isinstance(labels, list) or not all(isinstance(s, str) for s in labels) or (
        labels and len(labels) != n
    ):
        problems.append(Problem("chain.labels", labels, f"must be a list of {n} strings"))
        labels = []
    return labels


def _check_cylinder_stations(stations, n: int, engine, problems: list[Problem]) -> list:
    """``chain.cylinder_stations`` checked against ``n`` stations and the ``engine``; [] where refused."""
    cylinders = engine.cylinders if engine else 0
    if not (isinstance(stations, list) and all(isinstance(c, int) and not isinstance(c, bool) and 1 <= c <= max(n, 1)
                                              for c in stations)):
        problems.append(Problem("chain.cylinder_stations", stations,
                                f"must be a list of station numbers 1..{n}, one per cylinder"))
        stations = []
    elif engine is not None and cylinders and len(stations) != cylinders:
        problems.append(Problem("chain.cylinder_stations", stations,
                                f"must name one station (1..{n}) per cylinder ({cylinders})"))
    elif engine is None and stations:
        problems.append(Problem("chain.cylinder_stations", stations, "needs an [engine] table"))
    return stations
