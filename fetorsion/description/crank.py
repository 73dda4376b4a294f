"""The crank description: one TOML file, parsed into frozen dataclasses in SI units (a chain file and
a network: :mod:`.chain`, :mod:`.network`; the tables all three share: :mod:`.tables`).

Every later step (Gmsh solid, FE modal, lumped models, Campbell) reads a :class:`Crank`.
The file format is documented in ``docs/description-format.md``; ``geometry/*.toml`` are
examples. Lengths are in the unit the file names in ``[units] length``; every other
quantity carries its SI unit in its key name (``density_kgm3``, ``polar_inertia_kgm2``).

Validation collects every violated rule (field, value, rule) and raises one
:class:`~fetorsion.errors.DescriptionError` before any work starts.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..errors import DescriptionError, Problem
from .fields import CRANK_SCHEMA
from .model import (ATTACH_POINTS, MEASURED_F1, PAPER_FE_F1, PAPER_LUMPED_F1, Attachment, AttachPoint, Bearings, Crank,
                    Cylinder, Engine, Fillets, Material, OilFilm, OilHoles, PROCESSES, SURFACES, TREATMENTS, Web)
from .reader import Table, finite_number, read_length_unit, read_toml
from .excitation_table import read_excitation
from .splitpin import every_or_none, read_split, split_engine, split_problems
from .tables import (firing_problems, read_engine, read_dampers, read_design, read_limits, read_uncertainty,
                     read_distributions, unique_problems, uncertainty_bound_problems)


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
    the short-bearing film's isotropic equivalents per journal (:mod:`fetorsion.description.oilfilm`),
    NaN where a value was refused (the problem is recorded). Without ``load_n`` the loads are
    each journal's mean load from the crank's own gas and inertia forces, found once the crank
    is condensed (:func:`fetorsion.response.coupled.with_film_bearings`): until then the film's
    ``load`` is None and the stiffness placeholders are rigid.
    """
    from .oilfilm import film_coefficients, isotropic_equivalent

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


def _cylinder(t: Table, split: tuple[float, float] = (0.0, 0.0)) -> Cylinder:
    """A round part; ``split``: a pin's split angle (rad) and flying web (m), read by the caller."""
    d = t.number("diameter", length=True, positive=True)
    length = t.number("length", length=True, positive=True)
    bore = t.number("bore", 0.0, length=True, nonnegative=True)
    t.finish()
    if d > 0 and bore >= d:
        t.problems.append(Problem(f"{t.path}.bore", bore / t.scale, f"must be smaller than diameter ({d / t.scale:g})"))
    if split[0] and length > 0 and not split[1] < length:
        t.problems.append(Problem(f"{t.path}.flying_web_thickness", split[1] / t.scale,
                                  f"the flying web and the two half pins must fit the pin: must be less than its "
                                  f"length ({length / t.scale:g})"))
    return Cylinder(d, length, bore, *split)


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


def parse_crank(data: dict, source: str = "<crank>", check_uncertainty: bool = True) -> Crank:
    """Build a :class:`Crank` from a parsed TOML mapping; see :func:`load`.

    With ``check_uncertainty`` every bound of the ``[uncertainty]`` table is checked too:
    the description with that input at that bound must obey every rule.
    """
    problems: list[Problem] = []
    root = Table(data, "", problems, schema=CRANK_SCHEMA)
    unit = read_length_unit(root, source)
    name, notes = _meta(root, source)
    material = _material(root)
    raw_pins = data.get("pins")
    split = isinstance(raw_pins, list) and any(isinstance(p, dict) and "split_angle_deg" in p for p in raw_pins)
    engine = read_engine(root, split)
    journals, pins, webs, front, rear = _shaft_parts(root, engine)
    if split:
        problems.extend(every_or_none(pins))
        engine = split_engine(engine, pins)
        if engine.half_pin_angles and engine.firing_order:
            problems.extend(firing_problems(engine, "crank_angles_deg and the pins' split_angle_deg, throw angles"))
    ft = root.table("fillets", required=False)
    fillets = Fillets(ft.number("journal", 0.0, length=True, nonnegative=True),
                      ft.number("pin", 0.0, length=True, nonnegative=True))
    ft.finish()
    ot = root.table("oil_holes", required=False)
    oil = OilHoles(ot.number("diameter", 0.0, length=True, nonnegative=True),
                   ot.flag("in_journals"), ot.flag("in_pins"))
    ot.finish()
    step, placement = _solid(root, source) if "solid" in data else (None, None)
    attachments = _attachments(root)
    ex = data.get("excitation")
    bearings = (_bearings(root.table("bearings"), journals, ex.get("speed_range_rpm") if isinstance(ex, dict) else None)
                if "bearings" in data else None)
    uncertainty = read_uncertainty(root.table("uncertainty", required=False), data, problems)
    distributions = read_distributions(root.table("distributions", required=False), uncertainty, data, problems)
    design = read_design(root, data, problems)
    dampers = read_dampers(root)
    limits = read_limits(root)
    excitation = None
    if "excitation" in data:
        excitation = read_excitation(root.table("excitation"), Path(source).parent, engine)
    root.finish()

    crank = Crank(name, material, engine, journals, pins, webs, front, rear, fillets, oil,
                  attachments, unit, source, notes, uncertainty, excitation, data, bearings=bearings,
                  distributions=distributions, dampers=dampers, limits=limits, design=design, solid_step=step,
                  solid_placement=placement)
    problems.extend(_geometry_problems(crank, root.scale))
    if check_uncertainty and not problems:
        problems.extend(uncertainty_bound_problems(crank, parse_crank))
    if problems:
        raise DescriptionError(source, unique_problems(problems))
    return crank


def _meta(root: Table, source: str) -> tuple[str, dict]:
    """``[meta]``: the name (default: the file's stem) and the free notes, the reference
    frequencies among them checked."""
    problems = root.problems
    meta = root.table("meta", required=False)
    name = meta.text("name", default=Path(source).stem)
    notes = {k: v for k, v in meta.data.items() if k != "name"}
    meta.used.update(meta.data)
    for key in (MEASURED_F1, PAPER_FE_F1):
        if key in notes and not (finite_number(notes[key]) and notes[key] > 0):
            problems.append(Problem(f"meta.{key}", notes[key], "must be a frequency in Hz > 0"))
    lumped_refs = notes.get(PAPER_LUMPED_F1, {})
    if not (isinstance(lumped_refs, dict) and all(finite_number(v) and v > 0 for v in lumped_refs.values())):
        problems.append(Problem(f"meta.{PAPER_LUMPED_F1}", lumped_refs, "must be a table of partition = frequency "
                                "in Hz > 0 ({ \"17\" = 535.35 })"))
    return name, notes


def _material(root: Table) -> Material:
    """``[material]``: the elastic constants, density and the optional strength fields."""
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
    return material


def _shaft_parts(root: Table, engine: Engine) -> tuple[tuple[Cylinder, ...], tuple[Cylinder, ...], tuple[Web, ...],
                                                     tuple[Cylinder, ...], tuple[Cylinder, ...]]:
    """(journals, pins, webs, front, rear): the shaft's pieces, as many journals, pins and webs as
    the ``engine``'s layout has throws."""
    n = engine.cylinders // (2 if engine.layout == "vee" else 1)  # throws: as the layout has them, not as listed
    journals = tuple(_cylinder(t) for t in root.tables("journals"))
    raw_engine = root.data.get("engine") if isinstance(root.data.get("engine"), dict) else {}
    pins = tuple(_cylinder(t, read_split(t, raw_engine)) for t in root.tables("pins"))
    webs = tuple(_web(t) for t in root.tables("webs"))
    front = tuple(_cylinder(t) for t in root.tables("front", required=False))
    rear = tuple(_cylinder(t) for t in root.tables("rear", required=False))
    for key, items, want in (("journals", journals, n + 1), ("pins", pins, n), ("webs", webs, 2 * n)):
        if n and len(items) != want:
            what = (f"{n}-cylinder" if n == engine.cylinders else
                    f"{n}-throw ({engine.cylinders} cylinders, {engine.layout})")
            root.problems.append(Problem(key, f"{len(items)} entries", f"a {what} crank needs {want} [[{key}]]"))
    return journals, pins, webs, front, rear


def _solid(root: Table, source: str) -> tuple[str | None, tuple | None]:
    """``[solid]``: the STEP file (absolute path; None where refused) and its placement (None: as
    fetorsion builds a crank)."""
    problems = root.problems
    step = placement = None
    st = root.table("solid")
    given = st.text("step")
    st.text("source", default="")
    axis = st.numbers("axis", required=False) or (1.0, 0.0, 0.0)
    centre = st.numbers("front_centre", required=False) or (0.0, 0.0, 0.0)
    if len(axis) != 3 or not math.hypot(*axis) > 0:
        problems.append(Problem("solid.axis", st.data.get("axis"), "must be [x, y, z], a direction (not zero)"))
    elif len(centre) != 3:
        problems.append(Problem("solid.front_centre", st.data.get("front_centre"), "must be [x, y, z]"))
    else:
        n = math.hypot(*axis)
        placement = (tuple(a / n for a in axis), tuple(v * st.scale for v in centre))
        if placement == ((1.0, 0.0, 0.0), (0.0, 0.0, 0.0)):
            placement = None  # already as fetorsion builds it
    st.finish()
    path = Path(source).parent / given
    if not given.lower().endswith((".step", ".stp")):
        problems.append(Problem("solid.step", given, "must be a STEP file (.step or .stp)"))
    elif not path.is_file():
        problems.append(Problem("solid.step", given, f"no such file ({path})"))
    else:
        step = str(path.resolve())
    return step, placement


def _attachments(root: Table) -> tuple[Attachment, ...]:
    """``[[attachments]]``: the rigid bodies fixed to the crank, in the file's order."""
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
    return tuple(attachments)


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
    out.update(_treatment(mt))
    if out["tensile_strength"] and out["yield_strength"] and out["yield_strength"] > out["tensile_strength"]:
        mt.problems.append(Problem("material.yield_strength_pa", mt.data["yield_strength_pa"],
                                   f"must not exceed tensile_strength_pa ({mt.data['tensile_strength_pa']})"))
    return out


def _treatment(mt: Table) -> dict:
    """``surface_treatment`` of ``[material]`` with its factor and source: a treatment other than
    ``none`` needs both (fetorsion ships no factor of its own), and a factor or source needs a
    treatment."""
    out = {"surface_treatment": None, "surface_treatment_factor": None, "surface_treatment_source": ""}
    if "surface_treatment" in mt.data:
        value = mt.text("surface_treatment", choices=TREATMENTS)
        out["surface_treatment"] = value if value in TREATMENTS else None
    treated = out["surface_treatment"] not in (None, "none")
    if "surface_treatment_factor" in mt.data:
        value = mt.number("surface_treatment_factor", positive=True)
        out["surface_treatment_factor"] = None if math.isnan(value) else value
    out["surface_treatment_source"] = mt.text("surface_treatment_source", "").strip()
    if treated:
        for key in ("surface_treatment_factor", "surface_treatment_source"):
            if key not in mt.data:
                mt.problems.append(Problem(f"material.{key}", None,
                                           f"is required with surface_treatment = {out['surface_treatment']!r}: "
                                           "the factor on the local fatigue strength and where it comes from (a "
                                           "test of the process, a guideline's table)"))
    else:
        for key in ("surface_treatment_factor", "surface_treatment_source"):
            if key in mt.data:
                mt.problems.append(Problem(f"material.{key}", mt.data[key],
                                           "belongs to a surface_treatment other than 'none'"))
    return out


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
    out.extend(split_problems(crank, show, u))
    spacing = max((abs(2 * o) for o in crank.engine.rod_offsets), default=0.0)
    short = [i for i, p in enumerate(crank.pins) if spacing >= p.length and not p.split]
    if short:
        out.append(Problem("engine.rod_spacing", show(spacing), f"the two big ends must sit on the pin: must be less "
                           f"than the length of pins.{short[0] + 1} ({show(crank.pins[short[0]].length)} {u})"))
    oh = crank.oil_holes
    if oh.diameter > 0 and not (oh.in_journals or oh.in_pins):
        out.append(Problem("oil_holes.diameter", show(oh.diameter), "set in_journals and/or in_pins to place the holes"))
    for kind, parts, used in (("journals", crank.journals, oh.in_journals), ("pins", crank.pins, oh.in_pins)):
        small = [i for i, c in enumerate(parts) if used and oh.diameter >= min(c.half_length, c.diameter - c.bore)]
        if small:
            out.append(Problem("oil_holes.diameter", show(oh.diameter),
                               f"must be smaller than the length and wall of {kind}.{small[0] + 1}"))
        radius = crank.fillets.journal if kind == "journals" else crank.fillets.pin
        for i, c in enumerate(parts):
            if used and i not in small and not c.split and _drilling_gap(c.length, oh.diameter, radius) <= _TOUCH_M:
                out.append(Problem(f"{kind}.{i + 1}.length", show(c.length), _drilling_meets_fillet(
                    kind[:-1], c.length, radius, oh.diameter, show, u)))
    return out


#: Closer than this (m) a drilling's exit touches its fillet: a nanometre, below any drawing's tolerance
#: and above the rounding of the lengths' arithmetic.
_TOUCH_M = 1e-9


def _drilling_gap(length: float, diameter: float, fillet: float) -> float:
    """Axial distance (m) between a drilling's exit, at mid-length of a journal or pin, and the
    fillets at its ends (where each fillet meets the cylinder, one radius from the web)."""
    return 0.5 * length - 0.5 * diameter - fillet


def _drilling_meets_fillet(part: str, length: float, fillet: float, diameter: float, show, u: str) -> str:
    """Why a drilling that reaches its fillet is refused, in the crank's words. Tangent, the two
    edges make a surface Gmsh cannot mesh (docs/plausible-cranks.md); overlapping, the fillet and the drilling are
    one notch that neither the rule's nor the FE path's fillet and bore models describe."""
    gap = _drilling_gap(length, diameter, fillet)
    meet = "touches" if abs(gap) <= _TOUCH_M else f"cuts {show(-gap)} {u} into"
    return (f"its {show(length)} {u} leaves no room for the {show(diameter)} {u} oil drilling at mid-length: the "
            f"drilling's exit {meet} the {show(fillet)} {u} fillets (2 x fillet + drilling = "
            f"{show(2 * fillet + diameter)} {u}); lengthen the {part}, or shrink the fillet or the drilling")


def crank_file(path: Path, data: dict) -> Crank:
    """The crank description read from ``path`` (its parsed TOML ``data``), a variant's base
    read under it (``extends``)."""
    if "extends" in data:
        data = extended(path, data)
    return parse_crank(data, source=str(path))
