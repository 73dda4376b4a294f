"""The ``[excitation]`` table of every description kind (a crank description, a chain, a network):
the operating data and damping, and the cylinder pressure as a synthetic cycle or a measured CSV;
a chain's or network's own ``[excitation]`` beside the damping it states."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

from ..errors import Problem
from .defaults import DEFAULT_DAMPING_BAND, DEFAULT_DAMPING_BAND_SOURCE, DEFAULT_DAMPING_RATIO, DEFAULT_OVERSPEED
from .model import Engine, Excitation
from .reader import MAX_DESCRIPTION_BYTES, Table, finite_number


EXCITATION_SOURCES = ("imep_pa", "propeller_law_imep_pa", "peak_pressure_pa", "pressure_csv")  # or tangential_harmonics


def read_excitation(t: Table, folder: Path, engine: Engine | None, zero_damping_ok: bool = False) -> Excitation:
    """The ``[excitation]`` table; a pressure CSV path is relative to the description file. A chain
    that states its own dampers may set ``modal_damping_ratio = 0`` (``zero_damping_ok``).
    The synthetic cycle is checked against the ``engine`` it drives (a bore, four strokes, a
    peak pressure above the motored one)."""
    strokes = engine.strokes_per_cycle if engine else 4
    common = _operating_fields(t, zero_damping_ok)
    if "tangential_harmonics" in t.data:
        return _harmonic_table(t, common)
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
    return _synthetic_cycle(t, given[0], engine, common)


def _operating_fields(t: Table, zero_damping_ok: bool) -> dict:
    """The :class:`Excitation` fields every pressure source shares: masses, speeds, damping and their sources."""
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
    bending = t.number("bending_damping_ratio", 0.0, positive=True, below=1.0) if "bending_damping_ratio" in t.data \
        else None
    bending_source = t.text("bending_damping_ratio_source", "").strip()
    if bending is not None and not bending_source:
        t.problems.append(Problem(f"{t.path}.bending_damping_ratio_source", bending_source,
                                  "is required with bending_damping_ratio: say where it comes from (a measurement, "
                                  "a published value)"))
    elif bending is None and bending_source:
        t.problems.append(Problem(f"{t.path}.bending_damping_ratio_source", bending_source,
                                  "names the source of a bending_damping_ratio the table does not give"))
    return dict(bending_damping_ratio=bending, bending_damping_ratio_source=bending_source,
                reciprocating_mass=mass, rotating_mass=rotating, speed_range=tuple(speeds), modal_damping_ratio=zeta, overspeed=overspeed,
                damping_band=(float(band[0]), float(band[1])),
                damping_source=source.strip() if "modal_damping_band" in t.data else DEFAULT_DAMPING_BAND_SOURCE,
                modal_damping_ratio_source=t.text("modal_damping_ratio_source", "").strip())


def _synthetic_cycle(t: Table, key: str, engine: Engine | None, common: dict) -> Excitation:
    """The synthetic cycle's excitation: its load ``key`` (``imep_pa``, ``propeller_law_imep_pa`` or
    ``peak_pressure_pa``), the cycle's fields, checked against the ``engine`` it drives."""
    raw = t.get(key)
    pairs = [(1.0, raw)] if finite_number(raw) else raw
    if key == "propeller_law_imep_pa":  # p_mi at the top of the speed range, ∝ n² below (a fixed-pitch propeller)
        if not (finite_number(raw) and raw > 0):
            t.problems.append(Problem(f"{t.path}.{key}", raw, "must be a finite pressure > 0 (Pa): the mean indicated "
                                      "pressure at the top of speed_range_rpm"))
            raw = 1.0
        pairs = [(common["speed_range"][1] if common["speed_range"] else 1.0, raw)]
    elif not (isinstance(pairs, list) and pairs and all(
            isinstance(p, (list, tuple)) and len(p) == 2 and all(finite_number(v) for v in p) and p[1] > 0
            for p in pairs) and all(a[0] < b[0] for a, b in zip(pairs, pairs[1:]))):
        t.problems.append(Problem(f"{t.path}.{key}", raw,
                                  "must be a finite pressure > 0 (Pa) or a list of [rpm, Pa] pairs with rpm ascending"))
        pairs = [(1.0, 1.0)]
    ex = Excitation(
        compression_ratio=t.number("compression_ratio", above=1.0),
        load_kind={"imep_pa": "imep", "propeller_law_imep_pa": "propeller_imep"}.get(key, "peak"),
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
        t.problems.append(Problem(f"{t.path}.{key}", raw, "the synthetic cycle is a 4-stroke cycle; give "
                                  "pressure_csv for a 2-stroke engine"))
    if engine is not None and not engine.bore > 0:
        t.problems.append(Problem("engine.bore", engine.bore, f"must be > 0 for the gas force of {t.path}.{key}"))
    motored_peak = ex.intake_pressure * ex.compression_ratio ** ex.polytropic_exponent
    if ex.load_kind == "peak" and ex.compression_ratio > 1 and min(p for _, p in ex.load) <= motored_peak:
        # Polytropic compression from BDC at the intake pressure: the motored pressure at TDC.
        t.problems.append(Problem(f"{t.path}.peak_pressure_pa", raw, f"must be above the motored peak "
                                  f"p_intake·CR^n = {motored_peak:.4g} Pa at every speed"))
    return ex


#: The units a tangential-pressure harmonic table may be written in, to Pa.
PRESSURE_UNITS = {"Pa": 1.0, "bar": 1.0e5, "MPa": 1.0e6}


def _harmonic_table(t: Table, common: dict) -> Excitation:
    """The engine maker's tangential-pressure harmonics (``[[excitation.tangential_harmonics]]``: each
    ``order`` with ``sine`` and ``cosine``, or ``amplitude`` and ``phase_deg`` (p_q sin(qθ + φ)), one
    value per ``harmonic_imep_pa`` column, in ``tangential_pressure_unit``) and the load's mean
    indicated pressure: ``imep_pa`` (a value or [rpm, Pa] pairs) or ``propeller_law_imep_pa`` (at the
    top of the speed range, ∝ n² below it)."""
    unit = PRESSURE_UNITS[t.choice("tangential_pressure_unit", tuple(PRESSURE_UNITS), "Pa")]
    columns = t.numbers("harmonic_imep_pa")
    # a column at 0 is the motored cylinder's: what a misfiring one follows
    if not (columns and all(c >= 0 for c in columns) and all(a < b for a, b in zip(columns, columns[1:]))):
        t.problems.append(Problem(f"{t.path}.harmonic_imep_pa", list(columns), "must be mean indicated pressures >= 0 "
                                  "(Pa), ascending: the table's columns"))
    rows, misfire = [], []
    for h in t.tables("tangential_harmonics"):
        order = h.number("order", positive=True)
        if "amplitude" in h.data:
            amp, phase = h.numbers("amplitude"), [math.radians(v) for v in h.numbers("phase_deg")]
            sine, cosine = [a * math.cos(f) for a, f in zip(amp, phase)], [a * math.sin(f) for a, f in zip(amp, phase)]
        else:
            sine, cosine = h.numbers("sine"), h.numbers("cosine")
        if "misfire_sine" in h.data or "misfire_cosine" in h.data:
            misfire.append((order, h.number("misfire_sine") * unit, h.number("misfire_cosine") * unit))
        h.finish()
        if not len(sine) == len(cosine) == len(columns):
            h.problems.append(Problem(h.path, dict(h.data), f"needs one value per harmonic_imep_pa column "
                                      f"({len(columns)}) in sine and cosine (or amplitude and phase_deg)"))
        rows.append((order, tuple(v * unit for v in sine), tuple(v * unit for v in cosine)))
    if misfire and len(misfire) != len(rows):
        t.problems.append(Problem(f"{t.path}.tangential_harmonics", f"{len(misfire)} of {len(rows)} orders",
                                  "misfire_sine and misfire_cosine: give them for every order or for none"))
    load = [k for k in ("imep_pa", "propeller_law_imep_pa") if k in t.data]
    if len(load) != 1:
        t.problems.append(Problem(t.path, load or None, "with tangential_harmonics give exactly one of imep_pa, "
                                  "propeller_law_imep_pa (the load's mean indicated pressure)"))
        load, pairs, kind = [], [(1.0, 1.0)], "imep"
    elif load[0] == "propeller_law_imep_pa":
        pairs, kind = [(common["speed_range"][1], t.number("propeller_law_imep_pa", positive=True))], "propeller_imep"
    else:
        raw = t.get("imep_pa")
        pairs, kind = ([(1.0, raw)] if finite_number(raw) else raw), "imep"
        if not (isinstance(pairs, list) and pairs and all(isinstance(p, (list, tuple)) and len(p) == 2 and all(
                finite_number(v) for v in p) and p[1] > 0 for p in pairs)):
            t.problems.append(Problem(f"{t.path}.imep_pa", raw, "must be a pressure > 0 (Pa) or [rpm, Pa] pairs"))
            pairs = [(1.0, 1.0)]
    t.finish()
    return Excitation(tangential_harmonics=tuple(rows), harmonic_imep=tuple(columns), load_kind=kind,
                      load=tuple((float(a), float(b)) for a, b in pairs), misfire_harmonics=tuple(misfire), **common)


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


def read_chain_excitation(root: Table, data: dict, source: str, engine: Engine | None,
                          problems: list[Problem]) -> tuple[Excitation | None, dict]:
    """A chain's or network's own ``[excitation]`` (it needs an ``[engine]``; a zero modal ratio
    allowed, the file may state its damping) and its raw table; (None, {}) without one."""
    if "excitation" not in data:
        return None, {}
    if engine is None:
        problems.append(Problem("excitation", "[excitation]", "needs an [engine] table (and chain.cylinder_stations)"))
    ex_table = data["excitation"] if isinstance(data["excitation"], dict) else {}
    return read_excitation(root.table("excitation"), Path(source).parent, engine, zero_damping_ok=True), ex_table


def stated_damping_excitation(excitation: Excitation, ex_table: dict, has_dampers: bool, kind: str,
                              problems: list[Problem]) -> Excitation:
    """A chain's or network's ``[excitation]`` beside the damping it states: where it states
    absolute, relative or hysteretic damping and no ``modal_damping_ratio``, no modal damping is
    added (a default ratio on top would count it twice); where it states none, the modal ratio
    must be > 0 (an undamped resonance has no finite response)."""
    if "modal_damping_ratio" not in ex_table and has_dampers:
        return replace(excitation, modal_damping_ratio=0.0)
    if not excitation.modal_damping_ratio > 0 and not has_dampers:
        problems.append(Problem("excitation.modal_damping_ratio", excitation.modal_damping_ratio,
                                f"must be > 0 when the {kind} states no absolute, relative or hysteretic damping "
                                "(an undamped resonance has no finite response)"))
    return excitation
