"""The crank description: one TOML file, parsed into frozen dataclasses in SI units.

Every later step (Gmsh solid, FE modal, lumped models, Campbell) reads a :class:`Crank`.
The file format is documented in ``docs/description-format.md``; ``geometry/*.toml`` are
examples. Lengths are in the unit the file names in ``[units] length``; every other
quantity carries its SI unit in its key name (``density_kgm3``, ``polar_inertia_kgm2``).

Validation collects every violated rule (field, value, rule) and raises one
:class:`~fetorsion.errors.DescriptionError` before any work starts.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

from ..errors import DescriptionError, Problem
from .defaults import (DEFAULT_DAMPING_BAND, DEFAULT_DAMPING_BAND_SOURCE, DEFAULT_DAMPING_RATIO, DEFAULT_OVERSPEED,
                       DEFAULT_PARTITION, DEFAULT_WEB_METHOD)
from .fields import CHAIN_SCHEMA, CRANK_SCHEMA
from .model import (ATTACH_POINTS, table_at_temperature, DAMPER_STATIONS, DAMPER_TYPES, Attachment, AttachPoint, Bearings, Chain, Crank,
                    CRANK_END_ALIASES, GROUND, PARTITIONS, WEB_METHOD_NAMES, GearPair, Network, NetworkCrank,
                    NonlinearSpring, Shaft,
                    Cylinder, Damper, Engine, Excitation, Fillets, Limits, Material, OilFilm, OilHoles, PROCESSES,
                    SURFACES, Web)
from .reader import MAX_DESCRIPTION_BYTES, Table, finite_number, read_length_unit, read_toml, resolve_field

# Tables of the crank-train mechanics file (fetorsion.mechanics.input), which has no [engine].
MECHANICS_TABLES = {"slider_crank", "masses", "balance", "flywheel", "planetary"}


def load(path) -> Crank | Chain | Network:
    """Read a crank description or a chain file (``[chain]`` table) from TOML; a chain file
    with ``[[chain.stations]]`` is a :class:`Network` (shafts and gear pairs between named stations).

    Parameters
    ----------
    path : str or Path
        The ``.toml`` file.

    Returns
    -------
    Crank or Chain
        In SI units.

    Raises
    ------
    DescriptionError
        Listing every violated rule with its field, value and rule.

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")
    >>> crank.engine.cylinders
    4
    """
    path = Path(path)
    data = read_toml(path)
    if "extends" in data:
        data = extended(path, data)
    if "engine" not in data and "chain" not in data and MECHANICS_TABLES & set(data):
        raise DescriptionError(str(path), [Problem("file", str(path), (
            "is a mechanics file (for 'fetorsion kinematics | balance | flywheel'), not a crank description "
            "or chain file"))])
    return parse_description(data, str(path))


def parse_description(data: dict, source: str = "<description>") -> Crank | Chain | Network:
    """A parsed TOML mapping as the description it is: a network (``[chain]`` with stations or
    cranks), a chain (``[chain]``) or a crank description."""
    if "chain" in data:
        if isinstance(data["chain"], dict) and ("stations" in data["chain"] or "cranks" in data["chain"]):
            return parse_network(data, source=source)
        return parse_chain(data, source=source)
    return parse_crank(data, source=source)


def field_keys(parent, key: str) -> list:
    """The keys of ``parent`` a path's last part names: a table's key (set even where the table
    lacks it), or a list's 1-based index (``*``: every index), as
    :func:`~fetorsion.description.reader.resolve_field` reads them."""
    if isinstance(parent, list):
        if key == "*":
            return list(range(len(parent)))
        return [int(key) - 1] if key.isdigit() and 1 <= int(key) <= len(parent) else []
    return [key]


#: How many descriptions deep ``extends`` may go (a variant of a variant of ...): far beyond any real
#: use, low enough that a mistake is named rather than followed.
MAX_EXTENDS_DEPTH = 8


def extended(path: Path, data: dict, seen: tuple[Path, ...] = ()) -> dict:
    """A description that names another in ``extends`` read on top of it: its own top-level
    tables replace the base's tables of the same name whole (a table is never merged key by key,
    so what a variant states is all there is of that table); the base's other tables are kept.

    One design in two assemblies (the crank alone on a modal test, the same crank in its engine)
    is then one geometry file and a short variant, and the two cannot drift apart.

    Parameters
    ----------
    path : Path
        The file ``data`` was read from; ``extends`` is relative to its folder.
    data : dict
        Its parsed TOML, with an ``extends`` key.
    seen : tuple of Path
        The files already on this chain of ``extends`` (a cycle is refused).

    Returns
    -------
    dict
        The merged mapping, without ``extends``.
    """
    base_name = data["extends"]
    here = path.resolve()
    if not isinstance(base_name, str) or not base_name.strip():
        raise DescriptionError(str(path), [Problem("extends", base_name, (
            "the file name of the crank description this one is a variant of, relative to this file's folder"))])
    base_path = (path.parent / base_name).resolve()
    chain = seen + (here,)
    if base_path in chain:
        names = " -> ".join(p.name for p in chain + (base_path,))
        raise DescriptionError(str(path), [Problem("extends", base_name, f"the descriptions extend each other in a cycle ({names})")])
    if len(chain) > MAX_EXTENDS_DEPTH:
        raise DescriptionError(str(path), [Problem("extends", base_name, (
            f"more than {MAX_EXTENDS_DEPTH} descriptions deep; is the chain of extends a mistake?"))])
    base = read_toml(base_path)
    if "extends" in base:
        base = extended(base_path, base, chain)
    if "chain" in base or "chain" in data or "engine" not in base:
        raise DescriptionError(str(path), [Problem("extends", base_name, (
            "must name a crank description (with [engine]), and be named by one: chain files do not extend"))])
    merged = dict(base)
    merged.update({k: v for k, v in data.items() if k != "extends"})
    return merged


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
    loss = _per_spring(t, "loss_factors", len(stiffnesses))
    stations = t.get("cylinder_stations", [])
    t.finish()
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

    engine = read_engine(root) if "engine" in data else None
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
    dampers = read_dampers(root)
    limits = read_limits(root, torque_only=True)
    excitation = None
    if "excitation" in data:
        if engine is None:
            problems.append(Problem("excitation", "[excitation]", "needs an [engine] table (and chain.cylinder_stations)"))
        ex_table = data["excitation"] if isinstance(data["excitation"], dict) else {}
        excitation = _excitation(root.table("excitation"), Path(source).parent, engine, zero_damping_ok=True)
        has_dampers = any(v > 0 for v in (*absolute, *relative, *loss))
        if "modal_damping_ratio" not in ex_table and has_dampers:
            # The chain states its damping; a default modal ratio on top would count it twice.
            excitation = replace(excitation, modal_damping_ratio=0.0)
        elif not excitation.modal_damping_ratio > 0 and not has_dampers:
            problems.append(Problem("excitation.modal_damping_ratio", excitation.modal_damping_ratio,
                                    "must be > 0 when the chain states no absolute, relative or hysteretic damping "
                                    "(an undamped resonance has no finite response)"))
    uncertainty = _uncertainty(root.table("uncertainty", required=False), data, problems)
    distributions = _distributions(root.table("distributions", required=False), uncertainty, data, problems)
    root.finish()
    if problems:
        raise DescriptionError(source, _unique(problems))
    labels = tuple(labels) if labels else tuple(f"inertia {i + 1}" for i in range(n))
    chain = Chain(name, inertias, stiffnesses, labels, absolute, relative, source, loss,
                  tuple(c - 1 for c in stations), engine, excitation, unit, data, dampers, limits,
                  uncertainty, distributions)
    if check_uncertainty:
        bounds = _uncertainty_bound_problems(chain, parse_chain)
        if bounds:
            raise DescriptionError(source, bounds)
    return chain


def parse_network(data: dict, source: str = "<network>", check_uncertainty: bool = True) -> Network:
    """Build a :class:`Network` from a parsed TOML mapping whose ``[chain]`` table has
    ``[[chain.stations]]`` (names and inertias), ``[[chain.shafts]]`` (springs between two named
    stations, or a station and ``"ground"``) and optional ``[[chain.gears]]`` (rigid meshes with
    a speed ratio). ``[engine]``, ``[excitation]`` and ``[limits]`` are read as for a chain;
    ``chain.cylinder_stations`` names a station per cylinder (names or 1-based numbers).
    """
    problems: list[Problem] = []
    root = Table(data, "", problems, schema=CHAIN_SCHEMA)
    unit = read_length_unit(root, source) if ("engine" in data or "units" in data) else "m"
    t = root.table("chain")
    root.used.add("meta")
    name = t.text("name", default=Path(source).stem)
    for key in ("inertias_kgm2", "stiffnesses_nm_per_rad", "labels", "absolute_damping_nms_per_rad",
                "relative_damping_nms_per_rad", "loss_factors"):
        if key in t.data:
            t.used.add(key)
            problems.append(Problem(f"chain.{key}", t.data[key], "a network ([[chain.stations]]) states this per "
                                    "station or shaft, not as a list"))
    cranks = _network_cranks(t, Path(source).parent, problems)
    labels, inertias, absolute = [], [], []
    index = {}
    for k, c in enumerate(cranks):  # the crank's stations first: its pulley is station 1, the reference speed
        first = len(labels)
        cranks[k] = replace(c, first=first)
        labels += c.labels
        inertias += [math.nan] * len(c.labels)  # the lumped model's, when resolved
        absolute += [0.0] * len(c.labels)
        index.update({f"{c.name}.{CRANK_END_ALIASES[0]}": first, f"{c.name}.{CRANK_END_ALIASES[1]}": len(labels) - 1})
    for st in t.tables("stations", required=not cranks):
        label = st.text("name")
        if label in labels or label == GROUND:
            problems.append(Problem(f"{st.path}.name", label, "must be unique and not 'ground'"))
        labels.append(label)
        inertias.append(st.number("inertia_kgm2", positive=True))
        absolute.append(st.number("damping_nms_per_rad", 0.0, nonnegative=True))
        st.finish()
    index.update({s: i for i, s in enumerate(labels)})

    def ends(tt: Table, ground: bool):
        raw = tt.raw("between")
        ok = (isinstance(raw, list) and len(raw) == 2 and all(isinstance(s, str) for s in raw)
              and all(s in index or (ground and s == GROUND) for s in raw) and raw[0] != raw[1])
        unknown = [s for s in (raw if isinstance(raw, list) else []) if isinstance(s, str) and s not in index
                   and any(s.startswith(f"{c.name}.") for c in cranks)]
        if unknown:
            c = next(c for c in cranks if unknown[0].startswith(f"{c.name}."))
            problems.append(Problem(f"{tt.path}.between", raw, f"'{unknown[0]}' is not a station of the crank "
                                    f"'{c.name}': its stations are {c.name}.pulley, {c.name}.flywheel and "
                                    + ", ".join(c.labels)))
        elif raw is not None and not ok:
            problems.append(Problem(f"{tt.path}.between", raw, "must name two different stations"
                                    + (" (or a station and 'ground')" if ground else "")))
        if not ok:
            return None
        a, b = raw if raw[0] != GROUND else raw[::-1]
        return index[a], index.get(b, -1)

    shafts = []
    for sh in t.tables("shafts", required=not cranks):
        pair = ends(sh, ground=True)
        k = sh.number("stiffness_nm_per_rad", positive=True)
        c = sh.number("damping_nms_per_rad", 0.0, nonnegative=True)
        eta = sh.number("loss_factor", 0.0, nonnegative=True)
        sh.finish()
        if pair:
            shafts.append(Shaft(pair[0], pair[1], k, c, eta))
    gears = []
    for g in t.tables("gears", required=False):
        pair = ends(g, ground=False)
        ratio = g.number("ratio", positive=True)
        g.finish()
        if pair:
            gears.append(GearPair(pair[0], pair[1], ratio))
    nonlinear = [e for e in (_nonlinear_spring(nl, ends(nl, ground=True), problems)
                             for nl in t.tables("nonlinear", required=False)) if e is not None]
    stations = t.get("cylinder_stations", [])
    t.finish()
    if not problems:
        inside = [Shaft(c.first + s, c.first + s + 1, 1.0) for c in cranks for s in range(len(c.labels) - 1)]
        problems += _network_topology(labels, inside + shafts + [Shaft(e.i, e.j, 1.0) for e in nonlinear], gears)
    engine = read_engine(root) if "engine" in data else None
    driver = cranks[0] if cranks and engine is None else None  # the crank's own engine drives its pins
    if driver is not None:
        engine = driver.crank.engine
        if stations:
            problems.append(Problem("chain.cylinder_stations", stations, "the crank's pins carry its cylinders "
                                    "when the chain file gives no [engine]; give [engine] to place them yourself"))
            stations = []
    cranks = [replace(c, drives=c is driver) for c in cranks]
    picked = []
    if not isinstance(stations, list) or not all(
            (isinstance(c, str) and c in index) or (isinstance(c, int) and not isinstance(c, bool)
                                                    and 1 <= c <= len(labels)) for c in stations):
        problems.append(Problem("chain.cylinder_stations", stations, "must name a station (its name or 1-based "
                                "number) per cylinder"))
    else:
        picked = [index[c] if isinstance(c, str) else c - 1 for c in stations]
        if driver is None and engine is not None and engine.cylinders and len(picked) != engine.cylinders:
            problems.append(Problem("chain.cylinder_stations", stations,
                                    f"must name one station per cylinder ({engine.cylinders})"))
        elif "engine" not in data and picked:
            problems.append(Problem("chain.cylinder_stations", stations, "needs an [engine] table"))
    if "dampers" in data:
        root.used.add("dampers")
        problems.append(Problem("dampers", "[[dampers]]", "is not read for a network yet: join the damper's ring "
                                "as a station with a shaft (tuned) or an absolute/relative damper"))
    limits = read_limits(root, torque_only=True)
    excitation = None
    has_dampers = any(v > 0 for v in absolute) or any(s.damping > 0 or s.loss_factor > 0 for s in shafts)
    ex_table = None
    if "excitation" in data:
        if engine is None:
            problems.append(Problem("excitation", "[excitation]", "needs an [engine] table (and chain.cylinder_stations)"))
        ex_table = data["excitation"] if isinstance(data["excitation"], dict) else {}
        excitation = _excitation(root.table("excitation"), Path(source).parent, engine, zero_damping_ok=True)
    elif cranks and cranks[0].crank.excitation is not None and engine is cranks[0].crank.engine:
        # the crank's own [excitation] (its pressure file already read relative to the crank's folder)
        excitation, ex_table = cranks[0].crank.excitation, cranks[0].crank.raw.get("excitation", {})
    if excitation is not None:
        if "modal_damping_ratio" not in ex_table and has_dampers:
            excitation = replace(excitation, modal_damping_ratio=0.0)  # stated damping, not counted twice
        elif not excitation.modal_damping_ratio > 0 and not has_dampers:
            problems.append(Problem("excitation.modal_damping_ratio", excitation.modal_damping_ratio,
                                    "must be > 0 when the network states no absolute, relative or hysteretic "
                                    "damping (an undamped resonance has no finite response)"))
    uncertainty = _uncertainty(root.table("uncertainty", required=False), data, problems)
    distributions = _distributions(root.table("distributions", required=False), uncertainty, data, problems)
    root.finish()
    if problems:
        raise DescriptionError(source, _unique(problems))
    network = Network(name, tuple(labels), tuple(inertias), tuple(shafts), tuple(gears), tuple(absolute), source,
                      tuple(picked), engine, excitation, unit, data, limits, nonlinear=tuple(nonlinear),
                      cranks=tuple(cranks), uncertainty=uncertainty, distributions=distributions)
    if check_uncertainty:
        bounds = _uncertainty_bound_problems(network, parse_network)
        if bounds:
            raise DescriptionError(source, bounds)
    return network


def _network_cranks(t: Table, folder: Path, problems: list[Problem]) -> list[NetworkCrank]:
    """The ``[[chain.cranks]]`` of a network: each crank description read (every rule of its own
    checked) and placed at the front of the station list; its lumped model is built later
    (:func:`fetorsion.lumped_model.network.resolved`), which the description stage cannot import."""
    out = []
    tables = t.tables("cranks", required=False)
    if len(tables) > 1:
        problems.append(Problem("chain.cranks", f"{len(tables)} cranks", "at most one crank per network (two "
                                "engines on one gearbox need an excitation each: not yet)"))
    for ct in tables[:1]:
        name = ct.text("name", "crank")
        file = ct.text("file")
        dof = ct.choice("dof", PARTITIONS, DEFAULT_PARTITION)
        method = ct.text("stiffness", DEFAULT_WEB_METHOD, choices=WEB_METHOD_NAMES)
        ct.finish()
        if not name or name == GROUND or "." in name:
            problems.append(Problem(f"{ct.path}.name", name, "must be a name without '.', not 'ground'"))
        if not file:
            continue
        path = folder / file
        if not path.is_file():
            problems.append(Problem(f"{ct.path}.file", file, f"no such file ({path}); give the crank description's "
                                    "path relative to this chain file's folder"))
            continue
        try:
            crank = load(path)
        except DescriptionError as exc:
            problems.append(Problem(f"{ct.path}.file", file, f"is not a valid crank description: {exc}"))
            continue
        if not isinstance(crank, Crank):
            problems.append(Problem(f"{ct.path}.file", file, "must name a crank description (journals, pins, webs "
                                    "and [engine]), not a chain file"))
            continue
        if crank.dampers:
            problems.append(Problem(f"{ct.path}.file", file, "its [[dampers]] are not read in a network yet: join "
                                    "the damper's ring as a station with a shaft, and leave [[dampers]] out"))
            continue
        out.append(NetworkCrank(name, crank, dof, method))
    return out


def _nonlinear_spring(t: Table, pair, problems: list[Problem]) -> NonlinearSpring | None:
    """One ``[[chain.nonlinear]]`` element (a clutch damper's or a DMF's springs with friction):
    every field checked here, by name, before any analysis."""
    name = t.text("name")
    k = t.numbers("stiffnesses_nm_per_rad")
    angles = t.numbers("stage_angles_deg", required=False)
    friction = t.number("friction_torque_nm", 0.0, nonnegative=True)
    stick = t.number("stick_stiffness_nm_per_rad", 0.0, nonnegative=True)
    preload = t.number("preload_nm", 0.0)
    source = t.text("source")
    t.finish()
    before = len(problems)
    if not k or not all(v > 0 for v in k):
        problems.append(Problem(f"{t.path}.stiffnesses_nm_per_rad", list(k), "must be a list of stiffnesses, each > 0"))
    if len(angles) != max(len(k) - 1, 0) or not all(a > 0 for a in angles) or list(angles) != sorted(set(angles)):
        problems.append(Problem(f"{t.path}.stage_angles_deg", list(angles), "must give where each stage after the "
                                "first begins: one fewer than the stiffnesses, each > 0, ascending"))
    if stick and stick <= max(k, default=0.0):
        problems.append(Problem(f"{t.path}.stick_stiffness_nm_per_rad", stick, "must exceed the stiffest stage "
                                "(the friction sticks through it)"))
    if len(problems) > before or pair is None:
        return None
    return NonlinearSpring(pair[0], pair[1], k, tuple(math.radians(a) for a in angles), friction,
                           stick, preload, name, source)


def _network_topology(labels, shafts, gears) -> list[Problem]:
    """A network must hang together (one piece through shafts and gears), and its gears must not
    close a loop (a loop of rigid meshes over-constrains the angles)."""
    n = len(labels)
    if n < 2:
        return [Problem("chain.stations", list(labels), "needs at least 2 stations")]
    parent = list(range(n))

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    out = []
    for g in gears:
        a, b = root(g.i), root(g.j)
        if a == b:
            out.append(Problem("chain.gears", [labels[g.i], labels[g.j]], "closes a loop of gears"))
        parent[a] = b
    for s in shafts:
        if s.j >= 0:
            parent[root(s.i)] = root(s.j)
    apart = sorted({labels[i] for i in range(n) if root(i) != root(0)})
    if apart:
        out.append(Problem("chain.stations", apart, f"are not joined to '{labels[0]}' by any shaft or gear"))
    return out


def _per_spring(t: Table, key: str, springs: int) -> tuple[float, ...]:
    """One value per spring: a list, or one number for every spring."""
    raw = t.get(key, None)
    if raw is None:
        return ()
    if finite_number(raw):
        return (float(raw),) * springs
    values = t.numbers(key)
    if values and len(values) != springs:
        t.problems.append(Problem(f"{t.path}.{key}", list(values), f"must be one number or one per spring ({springs})"))
        return ()
    return values


def _attach_point(text: str) -> AttachPoint:
    # A bad value is already recorded as a problem; any member stands in until it is raised.
    return AttachPoint(text) if text in ATTACH_POINTS else AttachPoint.FRONT


RIGID = "rigid"


def _per_journal(t: Table, key: str, n: int, default: float, *, rigid: bool = False, length: bool = False,
                 positive: bool = False) -> tuple[float, ...]:
    """One value or one per journal; ``"rigid"`` (→ inf) where allowed."""
    raw = t.get(key, None)
    if raw is None:
        return (default,) * n
    values = raw if isinstance(raw, list) else [raw]
    if isinstance(raw, list) and len(raw) != n:
        t.problems.append(Problem(f"{t.path}.{key}", raw, f"must be one value or one per main journal ({n})"))
        return (default,) * n
    out = []
    for v in values:
        if rigid and v == RIGID:
            out.append(math.inf)
        elif finite_number(v) and (v > 0 if positive else v >= 0):
            out.append(float(v) * (t.scale if length else 1.0))
        else:
            what = "a finite number" + (" > 0" if positive else " >= 0") + (' or "rigid"' if rigid else "")
            t.problems.append(Problem(f"{t.path}.{key}", raw, f"must be {what}" + (", or a list of them" if n > 1 else "")))
            return (default,) * n
    return tuple(out) * (n if len(out) == 1 else 1)


# The oil-film group of [bearings]: given instead of radial_stiffness_n_per_m (speed_rpm may be left
# to default to the top of [excitation] speed_range_rpm).
OIL_FILM_KEYS = ("clearance", "oil_viscosity_pa_s", "load_n", "speed_rpm")


def _bearings(t: Table, journals, speed_range=None) -> Bearings:
    """``[bearings]``: radial stiffness (N/m or "rigid") and damping (N·s/m) per journal, or an
    oil film (:func:`_oil_film`); widths, a thrust journal with its axial stiffness.
    ``speed_range`` is the raw ``[excitation] speed_range_rpm`` (the oil film's default speed)."""
    n = len(journals)
    width = _per_journal(t, "width", n, math.nan, length=True, positive=True)
    width = tuple(j.length if math.isnan(w) else w for w, j in zip(width, journals))
    for i, (w, j) in enumerate(zip(width, journals)):
        if w > j.length * (1 + 1e-9):
            t.problems.append(Problem(f"{t.path}.width", w / t.scale,
                                      f"must not exceed journal {i + 1}'s length ({j.length / t.scale:g})"))
    film = None
    if any(k in t.data for k in OIL_FILM_KEYS):
        for key in ("radial_stiffness_n_per_m", "radial_damping_ns_per_m"):
            if key in t.data:
                t.problems.append(Problem(f"{t.path}.{key}", t.get(key), (
                    "cannot be given with an oil film (clearance, oil_viscosity_pa_s, load_n, speed_rpm): "
                    "the film gives the radial stiffness and damping; give one or the other")))
        radial, damping, film = _oil_film(t, journals, width, speed_range)
    else:
        radial = _per_journal(t, "radial_stiffness_n_per_m", n, math.inf, rigid=True, positive=True)
        damping = _per_journal(t, "radial_damping_ns_per_m", n, 0.0)
    axial_raw = t.get("axial_stiffness_n_per_m", 0.0)
    if axial_raw == RIGID:
        axial = math.inf
    elif finite_number(axial_raw) and axial_raw >= 0:
        axial = float(axial_raw)
    else:
        t.problems.append(Problem(f"{t.path}.axial_stiffness_n_per_m", axial_raw, 'must be a finite number >= 0 or "rigid"'))
        axial = 0.0
    thrust = 1
    if "thrust_journal" in t.data:
        thrust = t.integer("thrust_journal")
        if thrust > n:
            t.problems.append(Problem(f"{t.path}.thrust_journal", thrust, f"must be a main journal number (1 to {n})"))
            thrust = 1
    elif axial > 0:
        t.problems.append(Problem(f"{t.path}.thrust_journal", None, "is required with axial_stiffness_n_per_m"))
    t.used.add("source")
    t.finish()
    return Bearings(radial, damping, width, axial, max(thrust, 1) - 1, oil_film=film)


def _oil_film(t: Table, journals, width: tuple[float, ...], speed_range) -> tuple:
    """The oil-film group of ``[bearings]``: plain journal bearings at one operating point.

    ``clearance`` (radial, file length unit) and ``load_n`` (static load, N) one value or one per
    journal, ``oil_viscosity_pa_s`` one value, ``speed_rpm`` one value (default: the top of
    ``speed_range``). Returns (radial stiffness N/m, radial damping N·s/m, :class:`OilFilm`):
    the short-bearing film's isotropic equivalents per journal (:mod:`fetorsion.fe.oilfilm`),
    NaN where a value was refused (the problem is recorded). Without ``load_n`` the loads are
    each journal's mean load from the crank's own gas and inertia forces, found once the crank
    is condensed (:func:`fetorsion.response.coupled.with_film_bearings`): until then the film's
    ``load`` is None and the stiffness placeholders are rigid.
    """
    from ..fe.oilfilm import film_coefficients, isotropic_equivalent

    n = len(journals)
    if "clearance" not in t.data:  # per journal: _per_journal has no "required"
        t.problems.append(Problem(f"{t.path}.clearance", None, "is required with an oil film"))
    clearance = _per_journal(t, "clearance", n, math.nan, length=True, positive=True)
    load = _per_journal(t, "load_n", n, math.nan, positive=True) if "load_n" in t.data else None
    if load is None and speed_range is None:
        t.problems.append(Problem(f"{t.path}.load_n", None, (
            "is required with an oil film when the description has no [excitation] to derive the journals' "
            "mean loads from")))
    viscosity = t.number("oil_viscosity_pa_s", positive=True)
    if "speed_rpm" in t.data:
        speed_rpm = t.number("speed_rpm", positive=True)
    elif speed_range is None:
        t.problems.append(Problem(f"{t.path}.speed_rpm", None, (
            "is required with an oil film when [excitation] gives no speed_range_rpm to take its top")))
        speed_rpm = math.nan
    else:  # a bad range is the excitation's problem: no film then, and no second problem here
        top = speed_range[-1] if isinstance(speed_range, list) and speed_range else None
        speed_rpm = float(top) if finite_number(top) and top > 0 else math.nan
    for i, (c, j) in enumerate(zip(clearance, journals)):
        if c >= 0.5 * j.diameter:
            t.problems.append(Problem(f"{t.path}.clearance", c / t.scale,
                                      f"must be smaller than journal {i + 1}'s radius ({0.5 * j.diameter / t.scale:g})"))
            clearance = (math.nan,) * n
            break
    speed = speed_rpm * math.pi / 30.0  # rad/s
    if load is None:  # from the crank's own forces, later
        return (math.inf,) * n, (0.0,) * n, OilFilm(clearance, viscosity, None, speed, (), ())
    stiffness, damping, eccentricity, attitude = [], [], [], []
    for c, w, j, lw in zip(clearance, load, journals, width):
        if all(math.isfinite(v) for v in (c, w, lw, j.diameter, viscosity, speed)):
            f = film_coefficients(w, speed, j.diameter, lw, c, viscosity)
            k, d = isotropic_equivalent(f.stiffness, f.damping)
            stiffness.append(k), damping.append(d), eccentricity.append(f.eccentricity), attitude.append(f.attitude)
        else:
            stiffness.append(math.nan), damping.append(math.nan), eccentricity.append(math.nan), attitude.append(math.nan)
    film = OilFilm(clearance, viscosity, load, speed, tuple(eccentricity), tuple(attitude))
    return tuple(stiffness), tuple(damping), film


def _cylinder(t: Table) -> Cylinder:
    d = t.number("diameter", length=True, positive=True)
    length = t.number("length", length=True, positive=True)
    bore = t.number("bore", 0.0, length=True, nonnegative=True)
    t.finish()
    if d > 0 and bore >= d:
        t.problems.append(Problem(f"{t.path}.bore", bore / t.scale, f"must be smaller than diameter ({d / t.scale:g})"))
    return Cylinder(d, length, bore)


def _web(t: Table) -> Web:
    h = t.number("thickness", length=True, positive=True)
    b_max = t.number("width_journal", length=True, positive=True)
    b_min = t.number("width_pin", length=True, positive=True)
    r_cw = t.number("counterweight_radius", 0.0, length=True, nonnegative=True)
    a_cw = t.number("counterweight_angle_deg", 0.0, nonnegative=True)
    t.finish()
    if a_cw > 360:
        t.problems.append(Problem(f"{t.path}.counterweight_angle_deg", a_cw, "must be <= 360"))
    if (r_cw > 0) != (a_cw > 0):
        t.problems.append(Problem(f"{t.path}.counterweight_radius", r_cw / t.scale,
                                  "counterweight needs both counterweight_radius and counterweight_angle_deg > 0"))
    return Web(h, b_max, b_min, r_cw, math.radians(a_cw))



def read_engine(root: Table) -> Engine:
    """The ``[engine]`` table (cylinders, cycle, stroke, rod, bore, crank angles, firing order), lengths
    in the file's unit converted to m; shared by crank descriptions and chain files."""
    problems = root.problems
    et = root.table("engine")
    n = et.integer("cylinders")
    strokes = et.choice("cycle_strokes", (2, 4), 4)
    stroke = et.number("stroke", length=True, positive=True)
    rod = et.number("rod_length", length=True, positive=True)
    bore = et.number("bore", 0.0, length=True, nonnegative=True)
    angles = et.numbers("crank_angles_deg")
    firing = et.raw("firing_order")
    et.finish()
    if firing is None:
        firing = []
    elif not (isinstance(firing, list) and all(isinstance(c, int) and not isinstance(c, bool) for c in firing)
              and (not n or sorted(firing) == list(range(1, n + 1)))):
        problems.append(Problem("engine.firing_order", firing,
                                f"must be a permutation of the cylinder numbers 1..{n or 'N'}"))
        firing = []
    if n and angles and len(angles) != n:
        problems.append(Problem("engine.crank_angles_deg", list(angles), f"must list one angle per cylinder ({n})"))
    if rod <= 0.5 * stroke:
        problems.append(Problem("engine.rod_length", rod / root.scale,
                                f"must be longer than the crank radius ({0.5 * stroke / root.scale:g})"))
    engine = Engine(n, strokes, stroke, rod,
                    tuple(math.radians(a) for a in angles), tuple(firing), bore)
    if n and firing and angles and len(angles) == n:
        try:
            engine.firing_angles()
        except ValueError as exc:
            problems.append(Problem("engine.firing_order", list(firing),
                                    f"cannot be fired by crank_angles_deg {list(angles)}: {exc}"))
    return engine


def parse_crank(data: dict, source: str = "<crank>", check_uncertainty: bool = True) -> Crank:
    """Build a :class:`Crank` from a parsed TOML mapping; see :func:`load`.

    With ``check_uncertainty`` every bound of the ``[uncertainty]`` table is checked too:
    the description with that input at that bound must obey every rule.
    """
    problems: list[Problem] = []
    root = Table(data, "", problems, schema=CRANK_SCHEMA)
    unit = read_length_unit(root, source)

    meta = root.table("meta", required=False)
    name = meta.text("name", default=Path(source).stem)
    notes = {k: v for k, v in meta.data.items() if k != "name"}
    meta.used.update(meta.data)

    mt = root.table("material")
    material = Material(
        youngs_modulus=mt.number("youngs_modulus_pa", positive=True),
        poisson_ratio=mt.number("poisson_ratio", above=0.0, below=0.5),
        density=mt.number("density_kgm3", positive=True),
        name=mt.text("name"),
        **_strength(mt),
    )
    mt.used.add("source")
    mt.finish()

    engine = read_engine(root)
    n = engine.cylinders

    journals = tuple(_cylinder(t) for t in root.tables("journals"))
    pins = tuple(_cylinder(t) for t in root.tables("pins"))
    webs = tuple(_web(t) for t in root.tables("webs"))
    front = tuple(_cylinder(t) for t in root.tables("front", required=False))
    rear = tuple(_cylinder(t) for t in root.tables("rear", required=False))
    for key, items, want in (("journals", journals, n + 1), ("pins", pins, n), ("webs", webs, 2 * n)):
        if n and len(items) != want:
            problems.append(Problem(key, f"{len(items)} entries", f"a {n}-cylinder crank needs {want} [[{key}]]"))

    ft = root.table("fillets", required=False)
    fillets = Fillets(ft.number("journal", 0.0, length=True, nonnegative=True),
                      ft.number("pin", 0.0, length=True, nonnegative=True))
    ft.finish()
    ot = root.table("oil_holes", required=False)
    oil = OilHoles(ot.number("diameter", 0.0, length=True, nonnegative=True),
                   ot.flag("in_journals"), ot.flag("in_pins"))
    ot.finish()

    attachments = []
    for t in root.tables("attachments", required=False):
        attachments.append(Attachment(
            name=t.text("name", default=""),
            at=_attach_point(t.text("at", choices=ATTACH_POINTS)),
            polar_inertia=t.number("polar_inertia_kgm2", positive=True),
            mass=t.number("mass_kg", 0.0, nonnegative=True),
            diametral_inertia=t.number("diametral_inertia_kgm2", 0.0, nonnegative=True),
            offset=t.number("offset", 0.0, length=True),
        ))
        t.used.add("source")
        t.finish()
    ex = data.get("excitation")
    bearings = (_bearings(root.table("bearings"), journals, ex.get("speed_range_rpm") if isinstance(ex, dict) else None)
                if "bearings" in data else None)
    uncertainty = _uncertainty(root.table("uncertainty", required=False), data, problems)
    distributions = _distributions(root.table("distributions", required=False), uncertainty, data, problems)
    dampers = read_dampers(root)
    limits = read_limits(root)
    excitation = None
    if "excitation" in data:
        excitation = _excitation(root.table("excitation"), Path(source).parent, engine)
    root.finish()

    crank = Crank(name, material, engine, journals, pins, webs, front, rear, fillets, oil,
                  tuple(attachments), unit, source, notes, uncertainty, excitation, data, bearings=bearings,
                  distributions=distributions, dampers=dampers, limits=limits)
    problems.extend(_geometry_problems(crank, root.scale))
    if check_uncertainty and not problems:
        problems.extend(_uncertainty_bound_problems(crank))
    if problems:
        raise DescriptionError(source, _unique(problems))
    return crank


def _strength(mt: Table) -> dict:
    """The optional strength fields of ``[material]`` (absent: None); a yield strength must lie
    below the tensile strength."""
    out = {"tensile_strength": None, "yield_strength": None, "surface": None, "process": None}
    for field, key in (("tensile_strength", "tensile_strength_pa"), ("yield_strength", "yield_strength_pa")):
        if key in mt.data:
            value = mt.number(key, positive=True)
            out[field] = None if math.isnan(value) else value
    for field, choices in (("surface", SURFACES), ("process", PROCESSES)):
        if field in mt.data:
            value = mt.text(field, choices=choices)
            out[field] = value if value in choices else None
    if out["tensile_strength"] and out["yield_strength"] and out["yield_strength"] > out["tensile_strength"]:
        mt.problems.append(Problem("material.yield_strength_pa", mt.data["yield_strength_pa"],
                                   f"must not exceed tensile_strength_pa ({mt.data['tensile_strength_pa']})"))
    return out


# The inertia key of each damper type: a viscous damper's housing, a rubber or tuned damper's hub.
_HUB_KEY = {"viscous": "housing_inertia_kgm2", "rubber": "hub_inertia_kgm2", "tuned": "hub_inertia_kgm2"}


def read_dampers(root: Table) -> tuple[Damper, ...]:
    """The ``[[dampers]]`` tables (crank descriptions and chain files): one problem per bad field.

    Every type needs ``ring_inertia_kgm2`` > 0; ``viscous`` needs ``damping_nms_per_rad`` > 0 and
    takes ``housing_inertia_kgm2``; ``rubber`` needs ``stiffness_nm_per_rad`` and ``loss_factor``
    (or a ``dynamic_table`` of [frequency Hz, stiffness N m/rad, loss factor] rows, frequency
    ascending) and takes ``hub_inertia_kgm2``; ``tuned`` needs ``stiffness_nm_per_rad`` and takes
    ``hub_inertia_kgm2`` and ``damping_nms_per_rad``. ``at``: ``front`` (pulley end, default) or
    ``rear`` (flywheel side). ``allowed_power_w`` (optional, > 0): the heat it may dissipate
    continuously, its maker's rating, which the verdict checks.
    """
    out = []
    for t in root.tables("dampers", required=False):
        kind = t.text("type", choices=DAMPER_TYPES)
        at = t.text("at", "front", choices=DAMPER_STATIONS)
        ring = t.number("ring_inertia_kgm2", positive=True)
        hub_key = _HUB_KEY.get(kind)
        hub = t.number(hub_key, 0.0, nonnegative=True) if hub_key else 0.0
        k = eta = c = 0.0
        table: tuple = ()
        heat: dict = {}
        if kind == "viscous":
            c = t.number("damping_nms_per_rad", positive=True)
        elif kind == "rubber":
            if "dynamic_table" in t.data:
                table, heat = _dynamic_table(t)
                k, eta = (table[0][1], table[0][2]) if table else (math.nan, math.nan)
            else:
                k = t.number("stiffness_nm_per_rad", positive=True)
                eta = t.number("loss_factor", positive=True)
        elif kind == "tuned":
            k = t.number("stiffness_nm_per_rad", positive=True)
            c = t.number("damping_nms_per_rad", 0.0, nonnegative=True)
        name = t.text("name", default=kind)
        allowed = t.number("allowed_power_w", 0.0, positive=True) if "allowed_power_w" in t.data else 0.0
        t.used.add("source")
        t.finish()
        if kind in DAMPER_TYPES and at in DAMPER_STATIONS:
            out.append(Damper(kind, at, hub, ring, k, c, eta, table, name, str(t.data.get("source", "")), allowed,
                              **heat))
    return tuple(out)


def _dynamic_table(t: Table) -> tuple[tuple, dict]:
    """``dynamic_table`` rows [frequency Hz, stiffness N m/rad, loss factor], or [temperature °C,
    frequency Hz, stiffness, loss factor] read either at the stated operating ``temperature_c``
    or, with ``ambient_c`` and ``thermal_conductance_w_per_k`` (W/K, the rubber's heat path to the
    air), at the temperature its own dissipation holds (found by the response). Returns the
    frequency table (at ``temperature_c``, or at ``ambient_c`` to start from) and the
    :class:`Damper`'s temperature fields."""
    raw = t.get("dynamic_table")
    temperature = t.get("temperature_c", None)
    heat_keys = [k for k in ("ambient_c", "thermal_conductance_w_per_k") if k in t.data]
    width = len(raw[0]) if isinstance(raw, list) and raw and isinstance(raw[0], list) else 0
    rule = ("must be >= 2 rows [frequency_hz > 0, stiffness_nm_per_rad > 0, loss_factor >= 0] with frequency "
            "ascending, or rows [temperature_c, frequency_hz, stiffness_nm_per_rad, loss_factor] with frequency "
            "ascending within each temperature (>= 2 per temperature) and temperature_c (or ambient_c and "
            "thermal_conductance_w_per_k) given")
    rows = raw if isinstance(raw, list) else []
    ok = (width in (3, 4) and len(rows) >= 2
          and all(isinstance(r, list) and len(r) == width and all(finite_number(v) for v in r) for r in rows))
    if ok:
        body = [r[-3:] for r in rows]
        ok = all(f > 0 and k > 0 and e >= 0 for f, k, e in body)
    groups: dict = {}
    if ok:
        for r in rows:
            groups.setdefault(r[0] if width == 4 else None, []).append(r[-3:])
        ok = all(len(g) >= 2 and all(a[0] < b[0] for a, b in zip(g, g[1:])) for g in groups.values())
    if not ok:
        t.used.update(heat_keys)
        t.problems.append(Problem(f"{t.path}.dynamic_table", raw, rule))
        return (), {}
    if width == 3:
        for key, value in [("temperature_c", temperature)] * (temperature is not None) + [(k, t.data[k]) for k in heat_keys]:
            t.used.add(key)
            t.problems.append(Problem(f"{t.path}.{key}", value,
                                      "needs dynamic_table rows with a temperature column [temperature_c, frequency_hz, "
                                      "stiffness_nm_per_rad, loss_factor]"))
        return tuple((float(f), float(k), float(e)) for f, k, e in rows), {}
    rows4 = tuple((float(T), float(f), float(k), float(e)) for T, f, k, e in rows)
    if heat_keys:
        ambient = t.number("ambient_c")
        conductance = t.number("thermal_conductance_w_per_k", positive=True)
        if temperature is not None:
            t.problems.append(Problem(f"{t.path}.temperature_c", temperature,
                                      "give either temperature_c (a stated operating temperature) or ambient_c and "
                                      "thermal_conductance_w_per_k (the damper's own heat sets it), not both"))
        if not (finite_number(ambient) and conductance > 0):
            return (), {}
        return table_at_temperature(groups, ambient), {"temperature_table": rows4, "temperature_c": ambient,
                                                       "ambient_c": ambient, "thermal_conductance": conductance}
    if not finite_number(temperature):
        t.problems.append(Problem(f"{t.path}.temperature_c", temperature,
                                  "a dynamic_table with a temperature column needs the operating temperature_c "
                                  "(a finite number, °C), or ambient_c and thermal_conductance_w_per_k"))
        return (), {}
    return table_at_temperature(groups, float(temperature)), {"temperature_table": rows4,
                                                              "temperature_c": float(temperature)}


#: ``[limits]`` keys of the fatigue assessment's own strength and margin (opt-in overrides).
FATIGUE_LIMIT_KEYS = ("fatigue_strength_bending_pa", "fatigue_required_safety", "additional_bending_pa")


#: ``[limits]`` keys of earlier versions' shear-stress verdict, refused in a crank description.
SHEAR_LIMIT_KEYS = ("continuous_shear_pa", "fatigue_strength_shear_pa", "safety_factor", "transient_shear_pa")
FATIGUE_METHOD_NAMES = ("iacs-m53", "fe")


def read_limits(root: Table, torque_only: bool = False) -> Limits | None:
    """The ``[limits]`` table. A chain or network file (``torque_only``): the permissible
    vibratory section torque for continuous running (``continuous_torque_nm``) and passing through
    (``transient_torque_nm``). A crank description: the fatigue verdict's overrides only
    (:data:`FATIGUE_LIMIT_KEYS`, ``fatigue_method``); the shear limits of earlier versions are
    refused with the fields that replace them. ``source`` (required) says where the numbers come from."""
    if "limits" not in root.data:
        return None
    t = root.table("limits")
    source = t.text("source")
    if not source.strip():
        t.problems.append(Problem(f"{t.path}.source", t.data.get("source"), "must say where the limits come from"))
    if torque_only:
        bad = [k for k in (*SHEAR_LIMIT_KEYS, *FATIGUE_LIMIT_KEYS, "fatigue_method") if k in t.data]
        if bad or "continuous_torque_nm" not in t.data:
            t.problems.append(Problem(t.path, sorted(t.data), "a chain file has no shaft sections: give "
                                                             "continuous_torque_nm (and transient_torque_nm)"))
            t.used.update((*SHEAR_LIMIT_KEYS, *FATIGUE_LIMIT_KEYS, "fatigue_method", "continuous_torque_nm",
                           "transient_torque_nm"))
            t.finish()
            return None
        lim = Limits(continuous_torque=t.number("continuous_torque_nm", positive=True),
                     transient_torque=t.number("transient_torque_nm", 0.0, nonnegative=True), source=source)
        t.finish()
        if lim.transient and lim.transient < lim.continuous:
            t.problems.append(Problem(f"{t.path}.transient_torque_nm", lim.transient,
                                      f"must be >= the continuous limit ({lim.continuous:g}): passing through a "
                                      "resonance is allowed more, not less"))
        return lim
    old = [k for k in (*SHEAR_LIMIT_KEYS, "continuous_torque_nm", "transient_torque_nm") if k in t.data]
    if old:
        t.problems.append(Problem(t.path, old, "a crank's verdict is its fatigue assessment, not a second shear or "
                                               "torque limit: state the strength as [material] tensile_strength_pa "
                                               "(and yield_strength_pa), or the crank's own as [limits] "
                                               "fatigue_strength_bending_pa, the margin as fatigue_required_safety"))
        t.used.update(old)
    method = t.text("fatigue_method", "")
    if method and method not in FATIGUE_METHOD_NAMES:
        t.problems.append(Problem(f"{t.path}.fatigue_method", method, f"must be one of {', '.join(FATIGUE_METHOD_NAMES)}"))
    lim = Limits(source=source, fatigue_method=method,
                 fatigue_strength_bending=t.number("fatigue_strength_bending_pa", 0.0, nonnegative=True),
                 fatigue_required_safety=t.number("fatigue_required_safety", 0.0, nonnegative=True),
                 additional_bending=t.number("additional_bending_pa", 0.0, nonnegative=True))
    if 0 < lim.fatigue_required_safety < 1.0:
        t.problems.append(Problem(f"{t.path}.fatigue_required_safety", lim.fatigue_required_safety,
                                  "must be >= 1 (a safety factor)"))
    t.finish()
    return lim


EXCITATION_SOURCES = ("imep_pa", "peak_pressure_pa", "pressure_csv")


def _excitation(t: Table, folder: Path, engine: Engine | None, zero_damping_ok: bool = False) -> Excitation:
    """The ``[excitation]`` table; a pressure CSV path is relative to the description file. A chain
    that states its own dampers may set ``modal_damping_ratio = 0`` (``zero_damping_ok``).
    The synthetic cycle is checked against the ``engine`` it drives (a bore, four strokes, a
    peak pressure above the motored one)."""
    strokes = engine.strokes_per_cycle if engine else 4
    mass = t.number("reciprocating_mass_kg", nonnegative=True)
    rotating = t.number("rotating_mass_kg", 0.0, nonnegative=True)
    speeds = t.numbers("speed_range_rpm")
    if speeds and not (len(speeds) == 2 and 0 < speeds[0] < speeds[1]):
        t.problems.append(Problem(f"{t.path}.speed_range_rpm", list(speeds), "must be [low, high] rpm with 0 < low < high"))
        speeds = (1.0, 2.0)
    zeta = t.number("modal_damping_ratio", DEFAULT_DAMPING_RATIO, positive=not zero_damping_ok,
                    nonnegative=zero_damping_ok, below=1.0)
    overspeed = t.number("overspeed_factor", DEFAULT_OVERSPEED, above=0.0)
    if overspeed < 1.0:
        t.problems.append(Problem(f"{t.path}.overspeed_factor", overspeed, "must be >= 1 (a multiple of the top speed)"))
    band = tuple(t.numbers("modal_damping_band", required=False) or DEFAULT_DAMPING_BAND)
    if not (len(band) == 2 and 0 < band[0] <= band[1] < 1):
        t.problems.append(Problem(f"{t.path}.modal_damping_band", list(band), "must be [low, high] with 0 < low <= high < 1"))
        band = DEFAULT_DAMPING_BAND
    source = t.text("modal_damping_source", "")
    if "modal_damping_band" in t.data and not source.strip():
        t.problems.append(Problem(f"{t.path}.modal_damping_source", source,
                                  "is required with modal_damping_band: say where the band comes from"))
    common = dict(reciprocating_mass=mass, rotating_mass=rotating, speed_range=tuple(speeds), modal_damping_ratio=zeta, overspeed=overspeed,
                  damping_band=(float(band[0]), float(band[1])),
                  damping_source=source.strip() if "modal_damping_band" in t.data else DEFAULT_DAMPING_BAND_SOURCE,
                  modal_damping_ratio_source=t.text("modal_damping_ratio_source", "").strip())
    given = [k for k in EXCITATION_SOURCES if k in t.data]
    if len(given) != 1:
        t.problems.append(Problem(t.path, given or None, f"give exactly one of {', '.join(EXCITATION_SOURCES)}"))
        t.used.update(EXCITATION_SOURCES)
        t.used.update(_SYNTHETIC_CYCLE_KEYS)
        t.finish()
        return Excitation(**common)
    if given[0] == "pressure_csv":
        csv = t.text("pressure_csv")
        t.finish()
        curve = _pressure_csv(folder / csv, f"{t.path}.pressure_csv", t.problems, 180.0 * strokes) if csv else None
        return Excitation(pressure_curve=curve, **common)
    raw = t.get(given[0])
    pairs = [(1.0, raw)] if finite_number(raw) else raw
    if not (isinstance(pairs, list) and pairs and all(
            isinstance(p, (list, tuple)) and len(p) == 2 and all(finite_number(v) for v in p) and p[1] > 0
            for p in pairs) and all(a[0] < b[0] for a, b in zip(pairs, pairs[1:]))):
        t.problems.append(Problem(f"{t.path}.{given[0]}", raw,
                                  "must be a finite pressure > 0 (Pa) or a list of [rpm, Pa] pairs with rpm ascending"))
        pairs = [(1.0, 1.0)]
    ex = Excitation(
        compression_ratio=t.number("compression_ratio", above=1.0),
        load_kind="imep" if given[0] == "imep_pa" else "peak",
        load=tuple((float(a), float(b)) for a, b in pairs),
        intake_pressure=t.number("intake_pressure_pa", 1.0e5, positive=True),
        polytropic_exponent=t.number("polytropic_exponent", 1.3, above=1.0, below=1.67),
        combustion_start=math.radians(t.number("combustion_start_deg", -15.0, above=-90.0, below=90.0)),
        combustion_duration=math.radians(t.number("combustion_duration_deg", 50.0, positive=True, below=180.0)),
        wiebe_a=t.number("wiebe_a", 5.0, positive=True),
        wiebe_m=t.number("wiebe_m", 2.0, nonnegative=True),
        **common,
    )
    t.finish()
    if engine is not None and engine.strokes_per_cycle != 4:
        t.problems.append(Problem(f"{t.path}.{given[0]}", raw, "the synthetic cycle is a 4-stroke cycle; give "
                                  "pressure_csv for a 2-stroke engine"))
    if engine is not None and not engine.bore > 0:
        t.problems.append(Problem("engine.bore", engine.bore, f"must be > 0 for the gas force of {t.path}.{given[0]}"))
    motored_peak = ex.intake_pressure * ex.compression_ratio ** ex.polytropic_exponent
    if ex.load_kind == "peak" and ex.compression_ratio > 1 and min(p for _, p in ex.load) <= motored_peak:
        # Polytropic compression from BDC at the intake pressure: the motored pressure at TDC.
        t.problems.append(Problem(f"{t.path}.peak_pressure_pa", raw, f"must be above the motored peak "
                                  f"p_intake·CR^n = {motored_peak:.4g} Pa at every speed"))
    return ex


_SYNTHETIC_CYCLE_KEYS = ("compression_ratio", "intake_pressure_pa", "polytropic_exponent", "combustion_start_deg",
                         "combustion_duration_deg", "wiebe_a", "wiebe_m")


def _pressure_csv(path: Path, field_name: str, problems: list[Problem], cycle_deg: float):
    """(angles rad, pressures Pa) from a CSV of crank angle (deg, 0 = firing TDC) and pressure (Pa)
    that covers one whole cycle (``cycle_deg``: 720 for a 4-stroke, 360 for a 2-stroke)."""
    import numpy as np

    rows = "rows of 'angle_deg, pressure_pa'"
    if not path.is_file():
        problems.append(Problem(field_name, str(path), "is not a file"))
        return None
    if path.stat().st_size > MAX_DESCRIPTION_BYTES:
        problems.append(Problem(field_name, str(path), f"is larger than {MAX_DESCRIPTION_BYTES >> 20} MiB"))
        return None
    try:
        table = np.loadtxt(path, delimiter=",", comments="#", ndmin=2, encoding="utf-8")
    except (OSError, ValueError) as exc:
        problems.append(Problem(field_name, str(path), f"could not be read as {rows} ({exc})"))
        return None
    if table.ndim != 2 or table.shape[1] != 2 or len(table) < 8:
        problems.append(Problem(field_name, str(path), f"needs >= 8 {rows}"))
        return None
    angle, pressure = table[:, 0], table[:, 1]
    if not np.all(np.isfinite(table)):
        bad = int(np.flatnonzero(~np.isfinite(table).all(axis=1))[0])
        problems.append(Problem(field_name, str(path), f"row {bad + 1} holds a non-finite number"))
    elif np.any(np.diff(angle) <= 0) or np.any(pressure <= 0):
        problems.append(Problem(field_name, str(path), f"needs {rows} with angles ascending and pressures > 0"))
    else:
        span, step = angle[-1] - angle[0], np.diff(angle).max()
        if not cycle_deg - step - 1e-9 <= span <= cycle_deg + 1e-9:
            problems.append(Problem(field_name, str(path),
                                    f"covers {angle[0]:g}..{angle[-1]:g} deg; it must cover one whole cycle "
                                    f"({cycle_deg:g} deg, one step short at most)"))
        else:
            return tuple(np.radians(angle)), tuple(pressure)
    return None


def _uncertainty(t: Table, data: dict, problems: list[Problem]):
    """Ranges of reconstructed inputs: ``"path" = [low, high]``, or a named group
    ``name = {"path" = [low, high], ...}`` whose members move together (low with low),
    e.g. a material's E and density. Each range must contain its nominal value."""
    out = []
    for name, spec in t.data.items():
        t.used.add(name)
        members = spec.items() if isinstance(spec, dict) else [(name, spec)]
        group = []
        for path, rng in members:
            where_name = f"uncertainty.{name}" + (f".{path}" if isinstance(spec, dict) else "")
            if not (isinstance(rng, list) and len(rng) == 2 and all(finite_number(v) for v in rng)
                    and rng[0] < rng[1]):
                problems.append(Problem(where_name, rng, "must be [low, high], finite numbers with low < high"))
                continue
            targets = resolve_field(data, path)
            if not targets or any(isinstance(v, bool) or not isinstance(v, (int, float)) for _, v in targets):
                problems.append(Problem(where_name, rng, f"'{path}' does not name a numeric field of this description"))
                continue
            refused = {p.field for p in problems}  # a nominal value already refused is reported once
            for where, v in targets:
                if where not in refused and not rng[0] <= v <= rng[1]:
                    problems.append(Problem(where_name, rng, f"must contain the nominal value {where} = {v}"))
            group.append((path, float(rng[0]), float(rng[1])))
        out.append((name, tuple(group)))
    return tuple(out)


#: Distributions an ``[uncertainty]`` input may have (``fetorsion study`` samples them; the
#: one-at-a-time sensitivity and the grid use the range alone).
DISTRIBUTIONS = ("uniform", "triangular", "normal")


def _distributions(t: Table, uncertainty, data: dict, problems: list[Problem]):
    """``[distributions]``: ``name = "uniform" | "triangular"`` or ``name = { kind = "normal",
    sd = S }`` for an ``[uncertainty]`` entry (a group: its first member). Triangular peaks
    at the nominal value, which must lie below the high bound; normal is centred on the
    nominal value with standard deviation S (the member's file units), truncated to the range."""
    entries = dict(uncertainty)
    out = []
    for name, spec in t.data.items():
        t.used.add(name)
        where = f"distributions.{name}"
        if name not in entries:
            problems.append(Problem(where, spec, "names no [uncertainty] entry"
                                    + (f" (entries: {', '.join(entries)})" if entries else "")))
            continue
        kind, sd = (spec, None) if isinstance(spec, str) else (
            (spec.get("kind"), spec.get("sd")) if isinstance(spec, dict) else (None, None))
        extra = sorted(set(spec) - {"kind", "sd"}) if isinstance(spec, dict) else []
        if kind not in DISTRIBUTIONS or extra:
            problems.append(Problem(where, spec, f"must be one of {', '.join(DISTRIBUTIONS)}, or "
                                                 "{ kind = \"normal\", sd = S }" + (f"; unknown key {extra[0]}" if extra else "")))
            continue
        if not entries[name]:  # the range itself was refused
            continue
        path, low, high = entries[name][0]
        values = [v for _, v in resolve_field(data, path)]
        nominal = sum(values) / len(values)
        if kind == "normal" and not (finite_number(sd) and sd > 0):
            problems.append(Problem(f"{where}.sd", sd, "a normal distribution needs sd > 0 (file units of "
                                                         f"{path})"))
            continue
        if kind != "normal" and sd is not None:
            problems.append(Problem(f"{where}.sd", sd, f"only a normal distribution takes sd, not {kind}"))
            continue
        if kind == "triangular" and not low <= nominal < high:
            problems.append(Problem(where, spec, f"a triangular distribution peaks at the nominal {path} = "
                                                 f"{nominal:g}, which must lie below the high bound {high:g}"))
            continue
        out.append((name, kind, float(sd) if kind == "normal" else None))
    return tuple(out)


def _geometry_problems(crank: Crank, scale: float) -> list[Problem]:
    """Rules that relate parts to each other. They run even when other fields are bad: a
    field that did not parse is NaN, and every comparison with NaN is false, so only rules
    whose inputs are all valid can fire."""
    out = []
    R = crank.engine.crank_radius
    u = crank.length_unit

    def show(x):
        return round(x / scale, 6)

    for i, web in enumerate(crank.webs):
        p = f"webs.{i + 1}"
        throw, side = crank.throw_of_web(i), crank.journal_of_web(i)
        if throw < len(crank.pins) and web.width_pin < crank.pins[throw].diameter:
            out.append(Problem(f"{p}.width_pin", show(web.width_pin),
                               f"the pin (diameter {show(crank.pins[throw].diameter)} {u}) must lie inside its web: "
                               f"width_pin must be >= the pin diameter"))
        if side < len(crank.journals) and web.width_journal < crank.journals[side].diameter:
            out.append(Problem(f"{p}.width_journal", show(web.width_journal),
                               f"the journal (diameter {show(crank.journals[side].diameter)} {u}) must lie inside "
                               f"its web: width_journal must be >= the journal diameter"))
        if abs(web.width_journal - web.width_pin) / 2 >= R:
            out.append(Problem(f"{p}.width_journal", show(web.width_journal),
                               f"web end circles ({show(web.width_journal)} and {show(web.width_pin)} {u}) "
                               f"must differ in radius by less than the crank radius {show(R)} {u}"))
    thickness = [w.thickness for w in crank.webs if w.thickness > 0]
    if thickness:
        thinnest = min(range(len(crank.webs)), key=lambda i: crank.webs[i].thickness if crank.webs[i].thickness > 0
                       else math.inf)
        for part, radius in (("journal", crank.fillets.journal), ("pin", crank.fillets.pin)):
            if radius >= min(thickness) / 2:
                out.append(Problem(f"fillets.{part}", show(radius),
                                   f"must be smaller than half the thickness of the thinnest web "
                                   f"(webs.{thinnest + 1}: {show(min(thickness))} {u})"))
    oh = crank.oil_holes
    if oh.diameter > 0 and not (oh.in_journals or oh.in_pins):
        out.append(Problem("oil_holes.diameter", show(oh.diameter), "set in_journals and/or in_pins to place the holes"))
    for kind, parts, used in (("journals", crank.journals, oh.in_journals), ("pins", crank.pins, oh.in_pins)):
        small = [i for i, c in enumerate(parts) if used and oh.diameter >= min(c.length, c.diameter - c.bore)]
        if small:
            out.append(Problem("oil_holes.diameter", show(oh.diameter),
                               f"must be smaller than the length and wall of {kind}.{small[0] + 1}"))
    return out


def _unique(problems: list[Problem]) -> list[Problem]:
    """Each problem once, in the order first found."""
    seen, out = set(), []
    for p in problems:
        key = (p.field, repr(p.value), p.rule)
        if key not in seen:
            seen.add(key)
            out.append(p)
    return out


def _uncertainty_bound_problems(crank, parse=None) -> list[Problem]:
    """Each ``[uncertainty]`` bound must give a valid description: the inputs of one entry
    are set to their low (then high) bounds together, all else nominal, and the result is
    checked with every rule of a description (``parse``: the reader of its kind, default a
    crank description's)."""
    parse = parse or parse_crank
    import copy

    out = []
    for name, members in crank.uncertainty:
        for which, pick in (("low", 1), ("high", 2)):
            raw = copy.deepcopy(crank.raw)
            raw.pop("uncertainty", None)
            raw.pop("distributions", None)
            for member in members:
                parent_path, _, key = member[0].rpartition(".")
                for _, parent in (resolve_field(raw, parent_path) if parent_path else [("", raw)]):
                    for k in field_keys(parent, key):
                        parent[k] = _as_file_value(parent[k], member[pick])
            try:
                parse(raw, crank.source, check_uncertainty=False)
            except DescriptionError as exc:
                # One line per bound: a range applied to every web can break one rule eight times.
                more = len(exc.problems) - 1
                out.append(Problem(f"uncertainty.{name}", [list(m[1:]) for m in members] if len(members) > 1
                                   else list(members[0][1:]),
                                   f"its {which} bound breaks a rule: {exc.problems[0]}"
                                   + (f" (and {more} more)" if more else "")))
    return out


def _as_file_value(nominal, bound: float):
    """The bound as the file would hold it: an int field stays an int when the bound is whole,
    so that a non-whole bound of an integer (a cylinder count of 3.5) is caught by its rule."""
    if isinstance(nominal, int) and not isinstance(nominal, bool) and float(bound).is_integer():
        return int(bound)
    return bound


