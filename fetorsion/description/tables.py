"""The tables every description kind shares, read the same way in a crank description, a chain
and a network: ``[engine]``, ``[[dampers]]``, ``[limits]``, ``[uncertainty]``, ``[distributions]``
and ``[design]`` (``[excitation]``: :mod:`.excitation_table`); and the problems list's helpers."""

from __future__ import annotations

import math

from ..errors import DescriptionError, Problem
from .chain_fields import is_count
from .derived import table_at_temperature
from .design_space import DESIGN_OBJECTIVES, DesignSpace
from .model import DAMPER_STATIONS, DAMPER_TYPES, LAYOUTS, Articulation, Damper, Engine, Limits
from .reader import field_keys, Table, finite_number, resolve_field


def per_spring(t: Table, key: str, springs: int) -> tuple[float, ...]:
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


def read_engine(root: Table, split: bool = False) -> Engine:
    """The ``[engine]`` table (cylinders, cycle, stroke, rod, bore, crank angles, firing order), lengths
    in the file's unit converted to m; shared by crank descriptions and chain files. ``split``: the
    crank's pins are split (its ``[[pins]]`` say so), so the rods' places come from the half pins,
    not ``rod_spacing``, and the firing order is checked once the pins are read
    (:func:`firing_problems`)."""
    problems = root.problems
    et = root.table("engine")
    n = et.integer("cylinders")
    strokes = et.choice("cycle_strokes", (2, 4), 4)
    stroke = et.number("stroke", length=True, positive=True)
    rod = et.number("rod_length", length=True, positive=True)
    bore = et.number("bore", 0.0, length=True, nonnegative=True)
    angles = et.numbers("crank_angles_deg")
    firing = et.raw("firing_order")
    banks = _banks(et, n, split)
    et.finish()
    if firing is None:
        firing = []
    elif not (isinstance(firing, list) and all(isinstance(c, int) and not isinstance(c, bool) for c in firing)
              and (not n or sorted(firing) == list(range(1, n + 1)))):
        problems.append(Problem("engine.firing_order", firing,
                                f"must be a permutation of the cylinder numbers 1..{n or 'N'}"))
        firing = []
    throws = banks["throws"]
    if throws and angles and len(angles) != throws:
        per = "cylinder" if banks["layout"] != "vee" else "throw: a vee's two banks share each throw"
        problems.append(Problem("engine.crank_angles_deg", list(angles), f"must list one angle per {per} ({throws})"))
    if rod <= 0.5 * stroke:
        problems.append(Problem("engine.rod_length", rod / root.scale,
                                f"must be longer than the crank radius ({0.5 * stroke / root.scale:g})"))
    art = banks.get("articulation")
    if art is not None and art.rod_length <= 0.5 * stroke + art.knuckle_radius:
        problems.append(Problem("engine.articulated_rod_length", art.rod_length / root.scale,
                                f"must be longer than the crank radius and knuckle_radius together "
                                f"({(0.5 * stroke + art.knuckle_radius) / root.scale:g}): its piston is out of "
                                "the rod's reach at some angle"))
    engine = Engine(n, strokes, stroke, rod, tuple(math.radians(a) for a in angles), tuple(firing), bore,
                    banks["layout"], banks["cylinder_throws"], banks["bank_angles"], banks["rod_offsets"],
                    articulation=banks.get("articulation"))
    if n and firing and angles and len(angles) == throws and not split:
        problems.extend(firing_problems(engine))
    return engine


def firing_problems(engine: Engine, by: str = "crank_angles_deg") -> list[Problem]:
    """The firing order refused when the TDC lags (throw, split and bank angles) cannot fire it."""
    try:
        engine.firing_angles()
    except ValueError as exc:
        degrees = [round(math.degrees(a), 6) for a in engine.crank_angles]
        return [Problem("engine.firing_order", list(engine.firing_order), f"cannot be fired by {by} {degrees}: {exc}")]
    return []


#: How a vee's cylinders are numbered: "by-bank", the first bank's 1..T front to rear, then the
#: second's; "alternate", cylinders 1 and 2 on throw 1 (first bank, second bank), 3 and 4 on throw 2.
NUMBERINGS = ("by-bank", "alternate")
#: How a vee's two rods share a pin: side by side (each on its own half, ``rod_spacing`` apart),
#: fork-and-blade (one inside the other, both at mid-pin), master and articulated (the second
#: bank's rod on a knuckle pin of the first's, both at mid-pin).
RODS = ("side-by-side", "fork-and-blade", "articulated")
#: ``[engine]`` fields of master and articulated rods.
ARTICULATION_FIELDS = ("knuckle_radius", "knuckle_angle_deg", "articulated_rod_length")


def _articulation(et, rods: str, bank: float, split: bool) -> Articulation | None:
    """The master and articulated rods of ``rods = "articulated"`` (None otherwise; their fields
    refused by name on other rods). The knuckle angle defaults to the bank angle (the articulated
    rod then lines up with its cylinder at the master's TDC); the articulated rod must be longer than
    crank radius and knuckle radius together, so that its piston is reached at every angle."""
    problems = et.problems
    if rods != "articulated":
        for key in ARTICULATION_FIELDS:
            if key in et.data:
                et.get(key)
                problems.append(Problem(f"engine.{key}", et.data[key], 'belongs to rods = "articulated"'))
        return None
    if split:
        problems.append(Problem("engine.rods", rods, "split pins carry side-by-side rods only"))
    if "rod_spacing" in et.data:
        problems.append(Problem("engine.rod_spacing", et.data["rod_spacing"], 'belongs to rods = "side-by-side" '
                                                                               "(master and articulated rods run at mid-pin)"))
    rk = et.number("knuckle_radius", length=True, positive=True)
    angle = et.number("knuckle_angle_deg", bank if math.isfinite(bank) else 0.0, above=-180.0, below=180.0 + 1e-9)
    la = et.number("articulated_rod_length", length=True, positive=True)
    if not all(math.isfinite(v) for v in (rk, angle, la)):
        return None
    return Articulation(rk, math.radians(angle), la)


def _banks(et, n: int, split: bool = False) -> dict:
    """``[engine]``'s layout fields: which throw each cylinder drives, the angle of its bank
    (added to its throw's TDC lag) and its rod's place along the pin. In-line: cylinder c on
    throw c; opposed: the same, the cylinders alternating between two banks 180° apart (the
    second, fourth ... in the second); vee: two cylinders per throw, numbered by
    ``numbering``, the second bank's ``bank_angle_deg`` later to TDC (negative: earlier). With
    ``split`` pins each rod runs at its half pin's mid-length (set with the pins), so
    ``rod_spacing`` is neither needed nor taken."""
    problems = et.problems
    layout = et.text("layout", "in-line", choices=LAYOUTS)
    out = {"layout": layout if layout in LAYOUTS else "in-line", "throws": n, "cylinder_throws": (),
           "bank_angles": (), "rod_offsets": ()}
    vee_only = ("bank_angle_deg", "numbering", "rods", "rod_spacing") + ARTICULATION_FIELDS
    if out["layout"] != "vee":
        for key in vee_only:
            if key in et.data:
                et.get(key)
                problems.append(Problem(f"engine.{key}", et.data[key], 'belongs to layout = "vee"'))
        if out["layout"] == "opposed" and n:
            out["bank_angles"] = tuple(math.pi * (c % 2) for c in range(n))
        return out
    bank = et.number("bank_angle_deg", above=-180.0, below=180.0 + 1e-9)
    numbering = et.text("numbering", "by-bank", choices=NUMBERINGS)
    rods = et.text("rods", "side-by-side", choices=RODS)
    spacing = et.number("rod_spacing", 0.0 if rods != "side-by-side" or split else None, length=True,
                        positive=True) if (rods == "side-by-side" and not split) or "rod_spacing" in et.data else 0.0
    if split and "rod_spacing" in et.data:
        problems.append(Problem("engine.rod_spacing", et.data["rod_spacing"], "split pins carry each rod at its half "
                                "pin's mid-length: leave rod_spacing out"))
        spacing = 0.0
    if bank == 0:
        problems.append(Problem("engine.bank_angle_deg", bank, "must not be 0: two banks at 0° are an in-line engine"))
    out["articulation"] = _articulation(et, rods, bank, split)
    if rods == "fork-and-blade" and "rod_spacing" in et.data:
        problems.append(Problem("engine.rod_spacing", et.data["rod_spacing"], 'belongs to rods = "side-by-side" '
                                                                               "(a fork's blade runs at mid-pin)"))
    if n % 2:
        problems.append(Problem("engine.cylinders", n, "a vee has two cylinders on each throw: must be even"))
        return out
    throws = n // 2
    first = [c < throws if numbering == "by-bank" else c % 2 == 0 for c in range(n)]
    out.update(throws=throws,
               cylinder_throws=tuple(c % throws if numbering == "by-bank" else c // 2 for c in range(n)),
               bank_angles=tuple(0.0 if f else math.radians(bank if math.isfinite(bank) else 0.0) for f in first),
               rod_offsets=tuple((-0.5 if f else 0.5) * (spacing if math.isfinite(spacing) else 0.0) for f in first))
    return out


# The inertia key of each damper type: a viscous damper's housing, a rubber or tuned damper's hub.
_HUB_KEY = {"viscous": "housing_inertia_kgm2", "rubber": "hub_inertia_kgm2", "tuned": "hub_inertia_kgm2"}


def read_dampers(root: Table, stations: tuple[str, ...] = ()) -> tuple[Damper, ...]:
    """The ``[[dampers]]`` tables (crank descriptions and chain files): one problem per bad field.

    Every type needs ``ring_inertia_kgm2`` > 0; ``viscous`` needs ``damping_nms_per_rad`` > 0 and
    takes ``housing_inertia_kgm2``; ``rubber`` needs ``stiffness_nm_per_rad`` and ``loss_factor``
    (or a ``dynamic_table`` of [frequency Hz, stiffness N m/rad, loss factor] rows, frequency
    ascending) and takes ``hub_inertia_kgm2``; ``tuned`` needs ``stiffness_nm_per_rad`` and takes
    ``hub_inertia_kgm2`` and ``damping_nms_per_rad``. ``at``: ``front`` (pulley end, default) or
    ``rear`` (flywheel side). ``allowed_power_w`` (optional, > 0): the heat it may dissipate
    continuously, its maker's rating, which the verdict checks. In a network ``at`` may also name
    one of its ``stations``.
    """
    out = []
    places = tuple(DAMPER_STATIONS) + tuple(s for s in stations if s not in DAMPER_STATIONS)
    for t in root.tables("dampers", required=False):
        kind = t.text("type", choices=DAMPER_TYPES)
        at = t.text("at", "front", choices=places)
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
        if kind in DAMPER_TYPES and at in places:
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
    # the name is checked against the fatigue methods' registry (fetorsion.design.methods, a later
    # stage) when a command loads the description or a run starts
    method = t.text("fatigue_method", "")
    lim = Limits(source=source, fatigue_method=method,
                 fatigue_strength_bending=t.number("fatigue_strength_bending_pa", 0.0, nonnegative=True),
                 fatigue_required_safety=t.number("fatigue_required_safety", 0.0, nonnegative=True),
                 additional_bending=t.number("additional_bending_pa", 0.0, nonnegative=True))
    if 0 < lim.fatigue_required_safety < 1.0:
        t.problems.append(Problem(f"{t.path}.fatigue_required_safety", lim.fatigue_required_safety,
                                  "must be >= 1 (a safety factor)"))
    t.finish()
    return lim


def read_uncertainty(t: Table, data: dict, problems: list[Problem], table: str = "uncertainty", keys=None,
                     nominal_inside: bool = True):
    """Ranges of reconstructed inputs: ``"path" = [low, high]``, or a named group
    ``name = {"path" = [low, high], ...}`` whose members move together (low with low),
    e.g. a material's E and density. Each range must contain its nominal value (unless
    ``nominal_inside`` is False: a design space may leave the given design out). ``keys``: the
    entries read (default all of ``t``); ``table`` names them in messages."""
    out = []
    for name, spec in t.data.items():
        if keys is not None and name not in keys:
            continue
        t.used.add(name)
        members = spec.items() if isinstance(spec, dict) else [(name, spec)]
        group = []
        for path, rng in members:
            where_name = f"{table}.{name}" + (f".{path}" if isinstance(spec, dict) else "")
            if not (isinstance(rng, list) and len(rng) == 2 and all(finite_number(v) for v in rng)
                    and rng[0] < rng[1]):
                problems.append(Problem(where_name, rng, "must be [low, high], finite numbers with low < high"))
                continue
            targets = resolve_field(data, path)
            if not targets or any(isinstance(v, bool) or not isinstance(v, (int, float)) for _, v in targets):
                problems.append(Problem(where_name, rng, f"'{path}' does not name a numeric field of this description"))
                continue
            if is_count(path):
                problems.append(Problem(where_name, rng, f"'{path}' is a count (an integer field): it cannot take the "
                                        f"values between {rng[0]:g} and {rng[1]:g}; [{table}] moves dimensions and "
                                        "properties (describe each count as a description of its own)"))
                continue
            refused = {p.field for p in problems}  # a nominal value already refused is reported once
            for where, v in targets:
                if nominal_inside and where not in refused and not rng[0] <= v <= rng[1]:
                    problems.append(Problem(where_name, rng, f"must contain the nominal value {where} = {v}"))
            group.append((path, float(rng[0]), float(rng[1])))
        out.append((name, tuple(group)))
    return tuple(out)


#: Distributions an ``[uncertainty]`` input may have (``fetorsion study`` samples them; the
#: one-at-a-time sensitivity and the grid use the range alone).
DISTRIBUTIONS = ("uniform", "triangular", "normal")


def read_distributions(t: Table, uncertainty, data: dict, problems: list[Problem]):
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


def unique_problems(problems: list[Problem]) -> list[Problem]:
    """Each problem once, in the order first found."""
    seen, out = set(), []
    for p in problems:
        key = (p.field, repr(p.value), p.rule)
        if key not in seen:
            seen.add(key)
            out.append(p)
    return out


def uncertainty_bound_problems(crank, parse) -> list[Problem]:
    """Each ``[uncertainty]`` bound must give a valid description: the inputs of one entry
    are set to their low (then high) bounds together, all else nominal, and the result is
    checked with every rule of a description (``parse``: the reader of its kind, called with
    ``check_uncertainty=False``)."""
    import copy

    out = []
    for name, members in crank.uncertainty:
        for which, pick in (("low", 1), ("high", 2)):
            raw = copy.deepcopy(crank.raw)
            raw.pop("uncertainty", None)
            raw.pop("distributions", None)
            raw.pop("design", None)  # a design space of the nominal crank, not of its uncertain variants
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


def read_variations(root: Table, data: dict, problems: list[Problem]) -> tuple[tuple, tuple]:
    """(``[uncertainty]``, ``[distributions]``) of any description kind."""
    uncertainty = read_uncertainty(root.table("uncertainty", required=False), data, problems)
    return uncertainty, read_distributions(root.table("distributions", required=False), uncertainty, data, problems)


def read_design(root: Table, data: dict, problems: list[Problem]) -> DesignSpace | None:
    """``[design]`` (:class:`~fetorsion.description.model.DesignSpace`): the named fields, and every
    other key an input's range as in ``[uncertainty]`` (groups move together: their first member
    is the design variable)."""
    if "design" not in data:
        return None
    t = root.table("design")
    objective = t.choice("objective", DESIGN_OBJECTIVES, "mass")
    damper = t.choice("damper", DAMPER_TYPES, DAMPER_TYPES[0]) if "damper" in t.data else None
    ratio = ring = None
    if "damper_inertia_ratio" in t.data:
        r = t.numbers("damper_inertia_ratio")
        if not (r and len(r) == 2 and 0 < r[0] < r[1] <= 1):
            problems.append(Problem("design.damper_inertia_ratio", t.data["damper_inertia_ratio"],
                                    "must be [low, high] with 0 < low < high <= 1"))
        else:
            ratio = (float(r[0]), float(r[1]))
    if "damper_ring_radius" in t.data:
        ring = t.number("damper_ring_radius", length=True, positive=True)
    required = t.number("required_safety", None) if "required_safety" in t.data else None
    if required is not None and not required >= 1:
        problems.append(Problem("design.required_safety", required, "must be >= 1"))
    heat = t.number("damper_heat_rating_w", positive=True) if "damper_heat_rating_w" in t.data else None
    orders, margin = (), 0.0
    if "resonance_orders" in t.data:
        orders = t.numbers("resonance_orders")
        if not all(q > 0 for q in orders) or t.data["resonance_orders"] == []:
            problems.append(Problem("design.resonance_orders", t.data["resonance_orders"],
                                    "must be a non-empty list of orders > 0"))
            orders = ()
    if "resonance_margin" in t.data:
        margin = t.number("resonance_margin", above=0.0, below=1.0)
    for key, other in (("resonance_orders", "resonance_margin"), ("resonance_margin", "resonance_orders")):
        if key in t.data and other not in t.data:
            problems.append(Problem(f"design.{other}", None, f"is required with {key}"))
    if damper is not None and "damper_inertia_ratio" not in t.data:  # a bad one is refused above
        problems.append(Problem("design.damper_inertia_ratio", None, f"is required with damper = {damper!r}"))
    if damper is not None and objective == "mass" and "damper_ring_radius" not in t.data:
        problems.append(Problem("design.damper_ring_radius", None, "is required with a damper and objective mass "
                                "(the ring's mass is its inertia over the radius squared)"))
    for key in ("damper_inertia_ratio", "damper_ring_radius", "damper_heat_rating_w") if damper is None else ():
        if key in t.data:
            problems.append(Problem(f"design.{key}", t.data[key],
                                    "goes with damper = " + " or ".join(f'"{k}"' for k in DAMPER_TYPES)))
    named = {"objective", "damper", "damper_inertia_ratio", "damper_ring_radius", "required_safety",
             "damper_heat_rating_w", "resonance_orders", "resonance_margin"}
    ranges = read_uncertainty(t, data, problems, "design", keys=[k for k in t.data if k not in named],
                              nominal_inside=False)
    inputs = tuple(group[0] for _, group in ranges if group)
    if not inputs and damper is None:
        problems.append(Problem("design", None, "names no input to move and no damper to add"))
    t.finish()
    return DesignSpace(inputs, objective, damper, ratio, ring, required, heat, tuple(orders),
                       float(margin) if margin == margin else 0.0)
