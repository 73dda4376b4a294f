"""A network chain file: stations, shafts, gear pairs, nonlinear elements and at most one crank
description as a part (``[[chain.stations]]``, ``[[chain.shafts]]``, ``[[chain.gears]]``,
``[[chain.nonlinear]]``, ``[[chain.cranks]]``)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from ..errors import DescriptionError, Problem
from .defaults import DEFAULT_PARTITION, DEFAULT_WEB_METHOD
from .chain_fields import CHAIN_SCHEMA
from .model import CONDENSED, CRANK_END_ALIASES, PARTITIONS, WEB_METHOD_NAMES
from .chain_model import GROUND, GearPair, Network, NetworkCrank, NonlinearSpring, Shaft
from .marine import (CK_FACTORS, PROPELLER_DAMPING, SIGMA_B_CAP_PA, Coupling, Propeller, ShaftSection, ShutDown,
                     StartUp,
                     loss_factor_of)
from .reader import Table, read_length_unit, read_toml
from .crank import crank_file
from .excitation_table import read_chain_excitation, stated_damping_excitation
from .tables import (read_dampers, read_engine, read_limits, read_variations, unique_problems,
                     uncertainty_bound_problems)


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
    _refuse_chain_lists(t, problems)
    cranks, labels, inertias, absolute, index = _crank_stations(_network_cranks(t, Path(source).parent, problems))
    _read_stations(t, cranks, labels, inertias, absolute, problems)
    index.update({s: i for i, s in enumerate(labels)})
    shafts, gears, nonlinear = _links(t, cranks, index, problems)
    couplings = _couplings(t, cranks, index, problems)
    shafts += [Shaft(c.i, c.j, c.stiffness_at(c.operating_temperature_c), 0.0,
                     loss_factor_of(c.relative_damping_at(c.operating_temperature_c))) for c in couplings]
    propellers = _propellers(t, index, inertias, absolute, problems)
    stations = t.get("cylinder_stations", [])
    constant_speed = t.flag("constant_speed", False)
    t.finish()
    if not problems:
        inside = [Shaft(c.first + s, c.first + s + 1, 1.0) for c in cranks for s in range(len(c.labels) - 1)]
        problems += _network_topology(labels, inside + shafts + [Shaft(e.i, e.j, 1.0) for e in nonlinear], gears)
        problems += _massless_gear_groups(labels, inertias, gears)
    engine = read_engine(root) if "engine" in data else None
    driver = cranks[0] if cranks and engine is None else None  # the crank's own engine drives its pins
    if driver is not None:
        engine = driver.crank.engine
        if stations:
            problems.append(Problem("chain.cylinder_stations", stations, "the crank's pins carry its cylinders "
                                    "when the chain file gives no [engine]; give [engine] to place them yourself"))
            stations = []
    cranks = [replace(c, drives=c is driver) for c in cranks]
    picked = _cylinder_stations(stations, index, len(labels), driver is None, engine, "engine" in data, problems)
    # at "front": the first station (the engine's speed reference); "rear": the last station that
    # turns at the engine's speed (a gear's far side is not the flywheel's); or a station's name
    dampers = read_dampers(root, tuple(labels))
    limits = read_limits(root, torque_only=True)
    has_dampers = any(v > 0 for v in absolute) or any(s.damping > 0 or s.loss_factor > 0 for s in shafts)
    excitation = _network_excitation(root, data, source, engine, cranks, has_dampers, problems)
    uncertainty, distributions = read_variations(root, data, problems)
    start = _start(root, engine, excitation, problems) if "start" in data else None
    stop = _stop(root, engine, excitation, problems) if "stop" in data else None
    root.finish()
    problems += _condensed_crank_problems(cranks, labels, shafts, gears, nonlinear, dampers)
    if problems:
        raise DescriptionError(source, unique_problems(problems))
    network = Network(name, tuple(labels), tuple(inertias), tuple(shafts), tuple(gears), tuple(absolute), source,
                      tuple(picked), engine, excitation, unit, data, limits, nonlinear=tuple(nonlinear),
                      cranks=tuple(cranks), uncertainty=uncertainty, distributions=distributions, dampers=dampers,
                      propellers=tuple(propellers), couplings=tuple(couplings), start=start,
                      constant_speed=constant_speed, stop=stop)
    if check_uncertainty:
        bounds = uncertainty_bound_problems(network, parse_network)
        if bounds:
            raise DescriptionError(source, bounds)
    return network


def _refuse_chain_lists(t: Table, problems: list[Problem]) -> None:
    """A plain chain's lists (``inertias_kgm2``, ...) have no place in a network: each one refused."""
    for key in ("inertias_kgm2", "stiffnesses_nm_per_rad", "labels", "absolute_damping_nms_per_rad",
                "relative_damping_nms_per_rad", "loss_factors"):
        if key in t.data:
            t.used.add(key)
            problems.append(Problem(f"chain.{key}", t.data[key], "a network ([[chain.stations]]) states this per "
                                    "station or shaft, not as a list"))


def _crank_stations(cranks: list[NetworkCrank]) -> tuple[list[NetworkCrank], list, list, list, dict]:
    """The cranks' stations first, their pulley station 1, the reference speed: (the cranks placed,
    labels, inertias (NaN: the lumped model's, when resolved), absolute dampings, index of each
    label and of each crank's pulley and flywheel alias)."""
    cranks = list(cranks)
    labels, inertias, absolute = [], [], []
    index = {}
    for k, c in enumerate(cranks):
        first = len(labels)
        cranks[k] = replace(c, first=first)
        labels += c.labels
        inertias += [math.nan] * len(c.labels)
        absolute += [0.0] * len(c.labels)
        index.update({f"{c.name}.{CRANK_END_ALIASES[0]}": first, f"{c.name}.{CRANK_END_ALIASES[1]}": len(labels) - 1})
    return cranks, labels, inertias, absolute, index


def _read_stations(t: Table, cranks, labels: list, inertias: list, absolute: list, problems: list[Problem]) -> None:
    """``[[chain.stations]]``, appended to ``labels``, ``inertias`` and ``absolute`` (after the cranks')."""
    for st in t.tables("stations", required=not cranks):
        label = st.text("name")
        if label in labels or label == GROUND:
            problems.append(Problem(f"{st.path}.name", label, "must be unique and not 'ground'"))
        labels.append(label)
        # 0: a pinion whose inertia the gear it meshes with carries (checked by _massless_gear_groups)
        inertias.append(st.number("inertia_kgm2", nonnegative=True))
        absolute.append(st.number("damping_nms_per_rad", 0.0, nonnegative=True))
        st.finish()


def _ends(tt: Table, ground: bool, index: dict, cranks, problems: list[Problem]) -> tuple[int, int] | None:
    """The two stations (0-based; -1: ground) a shaft, gear or nonlinear element is ``between``;
    None (the problem recorded) where they are not two different known stations."""
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


def _links(t: Table, cranks, index: dict, problems: list[Problem]) -> tuple[list, list, list]:
    """``[[chain.shafts]]``, ``[[chain.gears]]`` and ``[[chain.nonlinear]]``: (shafts, gear pairs,
    nonlinear elements), each whose ends or fields were refused left out."""
    shafts = []
    for sh in t.tables("shafts", required=not cranks):
        pair = _ends(sh, True, index, cranks, problems)
        k = sh.number("stiffness_nm_per_rad", positive=True)
        c = sh.number("damping_nms_per_rad", 0.0, nonnegative=True)
        eta = sh.number("loss_factor", 0.0, nonnegative=True)
        section = _shaft_section(sh, problems)
        sh.finish()
        if pair:
            shafts.append(Shaft(pair[0], pair[1], k, c, eta, section))
    gears = []
    for g in t.tables("gears", required=False):
        pair = _ends(g, False, index, cranks, problems)
        ratio = g.number("ratio", positive=True)
        g.finish()
        if pair:
            gears.append(GearPair(pair[0], pair[1], ratio))
    nonlinear = [e for e in (_nonlinear_spring(nl, _ends(nl, True, index, cranks, problems), problems)
                             for nl in t.tables("nonlinear", required=False)) if e is not None]
    return shafts, gears, nonlinear


def _cylinder_stations(stations, index: dict, n: int, counted: bool, engine, has_engine_table: bool,
                       problems: list[Problem]) -> list[int]:
    """``chain.cylinder_stations`` (names or 1-based numbers of ``n`` stations) as 0-based stations;
    ``counted``: one per cylinder of ``engine`` is required (the network's own engine)."""
    picked = []
    if not isinstance(stations, list) or not all(
            (isinstance(c, str) and c in index) or (isinstance(c, int) and not isinstance(c, bool)
                                                    and 1 <= c <= n) for c in stations):
        problems.append(Problem("chain.cylinder_stations", stations, "must name a station (its name or 1-based "
                                "number) per cylinder"))
    else:
        picked = [index[c] if isinstance(c, str) else c - 1 for c in stations]
        if counted and engine is not None and engine.cylinders and len(picked) != engine.cylinders:
            problems.append(Problem("chain.cylinder_stations", stations,
                                    f"must name one station per cylinder ({engine.cylinders})"))
        elif not has_engine_table and picked:
            problems.append(Problem("chain.cylinder_stations", stations, "needs an [engine] table"))
    return picked


def _network_excitation(root: Table, data: dict, source: str, engine, cranks, has_dampers: bool,
                        problems: list[Problem]):
    """The network's own ``[excitation]``, or else its driving crank's, beside the damping it states."""
    excitation, ex_table = read_chain_excitation(root, data, source, engine, problems)
    if excitation is None and cranks and cranks[0].crank.excitation is not None and engine is cranks[0].crank.engine:
        # the crank's own [excitation] (its pressure file already read relative to the crank's folder)
        excitation, ex_table = cranks[0].crank.excitation, cranks[0].crank.raw.get("excitation", {})
    if excitation is not None:
        excitation = stated_damping_excitation(excitation, ex_table, has_dampers, "network", problems)
    return excitation


def _start(root: Table, engine, excitation, problems: list[Problem]) -> StartUp | None:
    """``[start]``: the engine's start, from its firing speed below the ``[excitation]`` range at a
    stated rate and mean indicated pressure; it needs an engine whose load is a mean indicated pressure."""
    st = root.table("start")
    start = StartUp(st.number("from_rpm", positive=True), st.number("rate_rpm_per_s", positive=True),
                    st.number("imep_pa", positive=True), st.text("source"))
    st.finish()
    if engine is None or excitation is None:
        problems.append(Problem("start", "given", "needs [engine] and [excitation]: the start is the engine's"))
        return None
    if excitation.load_kind == "peak" or excitation.pressure_curve is not None:
        problems.append(Problem("start.imep_pa", start.imep_pa, "needs an [excitation] loaded by a mean indicated "
                                "pressure (imep_pa, propeller_law_imep_pa or a harmonic table), not a peak pressure "
                                "or a pressure curve"))
    low = excitation.speed_range[0]
    if math.isfinite(start.from_rpm) and not start.from_rpm < low:
        problems.append(Problem("start.from_rpm", start.from_rpm, f"must be below the lowest speed of "
                                f"[excitation] speed_range_rpm, {low:g} rpm: the start runs up to it"))
    return start


def _stop(root: Table, engine, excitation, problems: list[Problem]) -> ShutDown | None:
    """``[stop]``: the coast-down after the fuel cut, every cylinder motored: it needs an engine whose
    motored cycle is known at p_mi 0 (the synthetic cycle, or a harmonic table's column at 0)."""
    st = root.table("stop")
    top = excitation.speed_range[1] if excitation is not None else 1.0
    stop = ShutDown(st.number("from_rpm", top, positive=True), st.number("to_rpm", positive=True),
                    st.number("rate_rpm_per_s", positive=True), st.text("source"))
    st.finish()
    if engine is None or excitation is None:
        problems.append(Problem("stop", "given", "needs [engine] and [excitation]: the stop is the engine's"))
        return None
    motored_at_zero = excitation.load_kind != "peak" and excitation.pressure_curve is None and (
        not excitation.tangential_harmonics or excitation.harmonic_imep[0] == 0.0)
    if not motored_at_zero:
        problems.append(Problem("stop", "given", "needs every cylinder's motored cycle at p_mi 0: the synthetic cycle by "
                                "imep_pa, or a harmonic table with a column at harmonic_imep_pa 0"))
    if math.isfinite(stop.from_rpm) and math.isfinite(stop.to_rpm) and not stop.from_rpm > stop.to_rpm:
        problems.append(Problem("stop.to_rpm", stop.to_rpm, f"must be below from_rpm ({stop.from_rpm:g} rpm): the "
                                "line coasts down"))
    return stop


def _condensed_crank_problems(cranks, labels, shafts, gears, nonlinear, dampers) -> list[Problem]:
    """A condensed crank offers the network its pulley and flywheel only, and drives its own pins:
    what joins or damps its inner stations, or a network ``[engine]`` beside it, is refused."""
    problems = []
    for c in cranks:
        inner = [labels[s] for s in joined_inside(c, shafts, gears, nonlinear)] if c.condensed else []
        if inner:
            problems.append(Problem("chain.cranks.1.dof", CONDENSED, f"a condensed crank offers the network only its "
                                    f"{c.name}.pulley and {c.name}.flywheel; {', '.join(inner)} joined here"))
        if c.condensed:
            inner = set(c.labels[1:-1])
            problems += [Problem(f"dampers.{k + 1}.at", d.at, f"an inner station of the condensed crank {c.name}: a "
                                 f"damper on it goes in the crank description, or at {c.name}.pulley / flywheel")
                         for k, d in enumerate(dampers) if d.at in inner]
        if c.condensed and not c.drives:
            problems.append(Problem("engine", "given", "a condensed crank's pins carry its own cylinders (its [engine] "
                                    "and [excitation]): leave the network's [engine] out"))
    return problems


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
        dof = ct.choice("dof", PARTITIONS + (CONDENSED,), DEFAULT_PARTITION)
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
            data = read_toml(path)
            if "chain" in data:
                problems.append(Problem(f"{ct.path}.file", file, "must name a crank description (journals, pins, "
                                        "webs and [engine]), not a chain file"))
                continue
            crank = crank_file(path, data)
        except DescriptionError as exc:
            problems.append(Problem(f"{ct.path}.file", file, f"is not a valid crank description: {exc}"))
            continue
        if crank.dampers:
            problems.append(Problem(f"{ct.path}.file", file, "its [[dampers]] are not read in a network yet: join "
                                    "the damper's ring as a station with a shaft, and leave [[dampers]] out"))
            continue
        condensed = dof == CONDENSED
        # a condensed crank keeps the default partition's station names: its front and rear are
        # what the network's other parts may join (its pulley and flywheel)
        out.append(NetworkCrank(name, crank, DEFAULT_PARTITION if condensed else dof, method, condensed=condensed))
    return out


def joined_inside(part: NetworkCrank, shafts: Sequence[Shaft], gears: Sequence[GearPair],
                  nonlinear: Sequence[NonlinearSpring]) -> list[int]:
    """The inner stations of crank ``part`` (neither its first nor its last) that a shaft, gear
    or nonlinear element joins, ascending: a condensed crank has no such stations to offer."""
    inner = set(range(part.first + 1, part.first + len(part.labels) - 1))
    ends = [(x.i, x.j) for x in (*shafts, *gears, *nonlinear)]
    return sorted({a for pair in ends for a in pair if a in inner})


def _nonlinear_spring(t: Table, pair, problems: list[Problem]) -> NonlinearSpring | None:
    """One ``[[chain.nonlinear]]`` element (a clutch damper's or a DMF's springs with friction):
    every field checked here, by name, before any analysis."""
    name = t.text("name")
    k = t.numbers("stiffnesses_nm_per_rad")
    angles = t.numbers("stage_angles_deg", required=False)
    friction = t.number("friction_torque_nm", 0.0, nonnegative=True)
    stick = t.number("stick_stiffness_nm_per_rad", 0.0, nonnegative=True)
    preload = t.number("preload_nm", 0.0)
    kc = t.numbers("coast_stiffnesses_nm_per_rad", required=False)
    angles_c = t.numbers("coast_stage_angles_deg", required=False)
    slip = t.number("slip_torque_nm", 0.0, nonnegative=True)
    source = t.text("source")
    t.finish()
    before = len(problems)
    for side, ks, a, needed in (("", k, angles, True), ("coast_", kc, angles_c, bool(kc or angles_c))):
        if not needed:
            continue
        if not ks or not all(v > 0 for v in ks):
            problems.append(Problem(f"{t.path}.{side}stiffnesses_nm_per_rad", list(ks),
                                    "must be a list of stiffnesses, each > 0"))
        if len(a) != max(len(ks) - 1, 0) or not all(x > 0 for x in a) or list(a) != sorted(set(a)):
            problems.append(Problem(f"{t.path}.{side}stage_angles_deg", list(a), "must give where each stage after "
                                    "the first begins: one fewer than the stiffnesses, each > 0, ascending"))
    if stick and stick <= max((*k, *kc), default=0.0):
        problems.append(Problem(f"{t.path}.stick_stiffness_nm_per_rad", stick, "must exceed the stiffest stage "
                                "(the friction sticks through it)"))
    if slip and slip <= abs(preload):
        problems.append(Problem(f"{t.path}.slip_torque_nm", slip, f"must exceed the mean torque it carries "
                                f"(preload_nm {preload:g}): below it the clutch slips for good"))
    if len(problems) > before or pair is None:
        return None
    return NonlinearSpring(pair[0], pair[1], k, tuple(math.radians(a) for a in angles), friction,
                           stick, preload, name, source, kc, tuple(math.radians(a) for a in angles_c), slip)


def _network_topology(labels, shafts, gears) -> list[Problem]:
    """A network must hang together (one piece through shafts and gears), and its gears must not
    close a loop (a loop of rigid meshes over-constrains the angles)."""
    n = len(labels)
    if n < 1:
        return [Problem("chain.stations", list(labels), "needs at least 1 station")]
    if n == 1 and not any(s.j < 0 for s in shafts):
        return [Problem("chain.stations", list(labels), "one station alone has no elastic mode: give it a shaft "
                                                        "to 'ground', or a second station")]
    parent = list(range(n))

    def root(a):
        return _root(parent, a)

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
    if not out:
        out += _locked_loops(labels, shafts, gears)
    return out


def _root(parent: list[int], a: int) -> int:
    """The representative of station ``a``'s group in the union-find ``parent`` (paths halved)."""
    while parent[a] != a:
        parent[a] = parent[parent[a]]
        a = parent[a]
    return a


def _massless_gear_groups(labels, inertias, gears) -> list[Problem]:
    """Stations moving together through gears (one angle for the group) must have some inertia
    between them: a station of inertia 0 is a gear whose inertia its mate carries (a crank's
    station, NaN until its lumped model is built, has its own)."""
    groups: dict[int, list[int]] = {}
    parent = list(range(len(labels)))
    for g in gears:
        parent[_root(parent, g.i)] = _root(parent, g.j)
    for i in range(len(labels)):
        groups.setdefault(_root(parent, i), []).append(i)
    return [Problem("chain.stations", [labels[i] for i in group],
                    "have no inertia: a station of inertia 0 must be meshed ([[chain.gears]]) with one that has some"
                    if len(group) > 1 else "has no inertia: only a gear meshed with one that has some may have 0")
            for group in groups.values() if not any(inertias[i] > 0 or math.isnan(inertias[i]) for i in group)]


def speed_walk(n: int, shafts: Sequence[Shaft], gears: Sequence[GearPair]):
    """Each station's speed over station 1's, walked breadth-first from it (a shaft keeps the
    speed, a gear multiplies it by its ratio): (factors (n,) with NaN where the walk does not
    reach, each station's parent on the walk, [(a, b, ratio)] the links a → b whose speed
    a × ratio differs from b's: each closes a locked loop, listed once).

    Parameters
    ----------
    n : int
        Stations.
    shafts : sequence of Shaft
        Springs (``j`` = -1: to ground, no link); nonlinear elements join as shafts do.
    gears : sequence of GearPair
        θ_j = ratio θ_i.
    """
    import numpy as np

    links = {s: [] for s in range(n)}
    for s in shafts:
        if s.j >= 0:
            links[s.i].append((s.j, 1.0))
            links[s.j].append((s.i, 1.0))
    for g in gears:
        links[g.i].append((g.j, g.ratio))
        links[g.j].append((g.i, 1.0 / g.ratio))
    speed, parent = np.full(n, np.nan), {0: None}
    if n:
        speed[0] = 1.0
    queue, conflicts = [0] if n else [], []
    while queue:
        a = queue.pop(0)
        for b, r in links[a]:
            if np.isnan(speed[b]):
                speed[b], parent[b] = speed[a] * r, a
                queue.append(b)
            elif parent.get(a) != b and abs(speed[a] * r / speed[b] - 1.0) > 1e-9 and a < b:
                conflicts.append((a, b, speed[a] * r / speed[b]))
    return speed, parent, conflicts


def _locked_loops(labels, shafts, gears) -> list[Problem]:
    """A loop of shafts and gears whose speed ratios do not multiply to 1 cannot turn as one (its
    shafts would wind up without end: a locked loop, no rigid-body motion): each such loop named
    by its stations, once."""
    _, parent, conflicts = speed_walk(len(labels), shafts, gears)

    def up(x):
        path = []
        while x is not None:
            path.append(x)
            x = parent[x]
        return path

    out = []
    for a, b, ratio in conflicts:
        pa, pb = up(a), up(b)
        common = next(x for x in pa if x in pb)
        loop = pa[:pa.index(common) + 1] + pb[:pb.index(common)][::-1]
        out.append(Problem("chain", [labels[k] for k in loop], f"these stations' shafts and gears form a loop whose "
                           f"speed ratios multiply to {ratio:.6g}, not 1: it cannot turn as one"))
    return out


def _shaft_section(sh: Table, problems: list[Problem]) -> ShaftSection | None:
    """A shaft's section for the class rule's stress limit (``diameter_m``, ``bore_m``,
    ``tensile_strength_pa``, ``feature``, ``material``): None where none of them is given; the
    diameter, strength and feature are required together."""
    keys = ("diameter_m", "tensile_strength_pa", "feature", "bore_m", "material")
    if not any(k in sh.data for k in keys):
        return None
    d = sh.number("diameter_m", positive=True)
    bore = sh.number("bore_m", 0.0, nonnegative=True)
    strength = sh.number("tensile_strength_pa", positive=True)
    feature = sh.choice("feature", tuple(CK_FACTORS), "")
    material = sh.choice("material", tuple(SIGMA_B_CAP_PA), "carbon")
    if bore >= d:
        problems.append(Problem(f"{sh.path}.bore_m", bore, f"must be smaller than diameter_m ({d})"))
    if problems and any(p.field.startswith(f"{sh.path}.") for p in problems):
        return None
    return ShaftSection(d, strength, feature, bore, material)


def _propellers(t: Table, index: dict, inertias: list, absolute: list, problems: list[Problem]) -> list[Propeller]:
    """``[[chain.propellers]]``: each propeller's station takes its inertia in water (its stated
    inertia the dry one) and its damping to ground linearised at ``damping_speed_rpm``."""
    out = []
    for pt in t.tables("propellers", required=False):
        station = pt.text("station")
        blades = pt.integer("blades", minimum=2)
        share = pt.number("entrained_water_share", nonnegative=True)
        model = pt.choice("damping_model", tuple(PROPELLER_DAMPING), "propeller_law")
        torque = pt.number("rated_torque_nm", positive=True)
        rated = pt.number("rated_speed_rpm", positive=True) * math.pi / 30.0
        speed = pt.number("damping_speed_rpm", rated * 30.0 / math.pi, positive=True) * math.pi / 30.0
        exponent = pt.number("torque_exponent", 2.0, positive=True)
        shares = pt.numbers("blade_order_shares", required=False)
        if any(v < 0 for v in shares):
            problems.append(Problem(f"{pt.path}.blade_order_shares", list(shares), "each must be >= 0"))
        name, source = pt.text("name", station), pt.text("source")
        passage = pt.number("passage_rate_rpm_per_s", 0.0, positive=True) if "passage_rate_rpm_per_s" in pt.data else 0.0
        pt.finish()
        s = index.get(station)
        if s is None or not inertias[s] > 0:
            problems.append(Problem(f"{pt.path}.station", station, "must name a station of the network with an "
                                    "inertia > 0 (its dry inertia), not a crank's"))
            continue
        if any(p.field.startswith(f"{pt.path}.") for p in problems):
            continue
        each = "damping_speed_rpm" not in pt.data  # the law at each speed, not linearised at one the file names
        p = Propeller(s, blades, inertias[s], share, torque, rated, speed, model, exponent, shares, name, source, passage,
                      each)
        inertias[s], absolute[s] = p.inertia, absolute[s] + p.damping(speed)
        out.append(p)
    return out


def _couplings(t: Table, cranks, index: dict, problems: list[Problem]) -> list[Coupling]:
    """``[[chain.couplings]]``: flexible couplings from their data sheets (nominal and, optionally,
    warm stiffness and relative damping), each taken at its operating temperature."""
    out = []
    for ct in t.tables("couplings", required=False):
        pair = _ends(ct, False, index, cranks, problems)
        k, psi = ct.number("stiffness_nm_per_rad", positive=True), ct.number("relative_damping", nonnegative=True)
        t0 = ct.number("temperature_c")
        warm = [k_ in ct.data for k_ in ("warm_stiffness_nm_per_rad", "warm_relative_damping", "warm_temperature_c")]
        k1 = ct.number("warm_stiffness_nm_per_rad", positive=True) if any(warm) else 0.0
        psi1 = ct.number("warm_relative_damping", nonnegative=True) if any(warm) else 0.0
        t1 = ct.number("warm_temperature_c", above=t0 if math.isfinite(t0) else None) if any(warm) else math.nan
        t_op = ct.number("operating_temperature_c", t0 if math.isfinite(t0) else 0.0)
        torque = ct.number("permissible_vibratory_torque_nm", 0.0, nonnegative=True)
        power = ct.number("permissible_power_w", 0.0, nonnegative=True)
        ambient = ct.number("ambient_c", math.nan) if "ambient_c" in ct.data else math.nan
        t_max = _max_temperature(ct, power, ambient, t1, problems)
        name, source = ct.text("name", "coupling"), ct.text("source")
        tolerance = ct.number("stiffness_tolerance", 0.0, nonnegative=True, below=1.0)
        maximum = ct.number("maximum_torque_nm", 0.0, nonnegative=True)
        ct.finish()
        if pair and not any(p.field.startswith(f"{ct.path}.") for p in problems):
            out.append(Coupling(pair[0], pair[1], k, psi, t0, t_op, k1, psi1, t1, torque, power, ambient, name,
                                source, t_max, tolerance, maximum))
    return out


def _max_temperature(ct: Table, power: float, ambient: float, warm: float, problems: list[Problem]) -> float:
    """A coupling's ``max_temperature_c`` (default its warm temperature), with ``ambient_c`` checked:
    both belong to the sheet's P_KV, and the maximum must lie above the ambient."""
    for key in ("ambient_c", "max_temperature_c"):
        if key in ct.data and not power > 0:
            problems.append(Problem(f"{ct.path}.{key}", ct.data[key], "needs permissible_power_w (the heat balance "
                                    "of the sheet's P_KV)"))
    t_max = ct.number("max_temperature_c", warm) if "max_temperature_c" in ct.data else warm
    if math.isfinite(t_max) and math.isfinite(ambient) and not t_max > ambient:
        problems.append(Problem(f"{ct.path}.max_temperature_c", t_max, f"must be above ambient_c ({ambient:g})"))
    return t_max
