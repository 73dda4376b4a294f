"""Split pins: a vee throw whose pin is two half pins at their own angles with a flying web between
them (the even-firing 90° V6). Read from ``[[pins]]`` ``split_angle_deg`` and
``flying_web_thickness``, checked against the engine and the pin, and turned into each cylinder's
half-pin angle and rod place (:func:`split_engine`). docs/vee-engines.md, *split pins*.

Which rod runs on which half: the first bank's rod sits in front on a vee's pin (as side-by-side
rods do), so it runs on the front half, at its throw's angle a_t; the second bank's on the rear
half, at a_t + δ. Each big end is at its half's mid-length, (L + w)/4 from the pin's mid-length
(L the pin length, w the flying web's thickness).
"""

from __future__ import annotations

import math
from dataclasses import replace

from collections.abc import Callable

from ..errors import Problem
from .model import Crank, Cylinder, Engine
from .reader import Table


def read_split(t: Table, raw_engine: dict) -> tuple[float, float]:
    """(split angle rad, flying web m) of one ``[[pins]]`` table ``t`` (0, 0: unsplit), each field
    checked: a split needs a vee with side-by-side rods (``raw_engine``: the file's ``[engine]``),
    a flying web needs a split, the angle is not 0 and lies in (−180, 180)."""
    if "split_angle_deg" not in t.data and "flying_web_thickness" not in t.data:
        return 0.0, 0.0
    problems = t.problems
    if "split_angle_deg" not in t.data:
        t.used.add("flying_web_thickness")
        problems.append(Problem(f"{t.path}.flying_web_thickness", t.data["flying_web_thickness"],
                                "belongs to a split pin: give split_angle_deg too"))
        return 0.0, 0.0
    angle = t.number("split_angle_deg", above=-180.0, below=180.0)
    web = t.number("flying_web_thickness", length=True, positive=True)
    layout = raw_engine.get("layout", "in-line")
    rods = raw_engine.get("rods", "side-by-side")
    if angle == 0:
        problems.append(Problem(f"{t.path}.split_angle_deg", 0, "must not be 0 (an unsplit pin: leave the split "
                                                                 "fields out)"))
    elif layout != "vee":
        problems.append(Problem(f"{t.path}.split_angle_deg", t.data["split_angle_deg"],
                                f'a split pin carries the two rods of a vee: needs layout = "vee" (engine.layout '
                                f'is "{layout}")'))
    elif rods != "side-by-side":
        problems.append(Problem(f"{t.path}.split_angle_deg", t.data["split_angle_deg"],
                                f'each half of a split pin carries one rod: needs rods = "side-by-side" '
                                f'(engine.rods is "{rods}")'))
    return (math.radians(angle) if math.isfinite(angle) else math.nan), web


def every_or_none(pins: tuple[Cylinder, ...]) -> list[Problem]:
    """Split pins on some throws only are refused: the rods' places would need ``rod_spacing`` on
    the others, and no engine mixes them."""
    split = [i + 1 for i, p in enumerate(pins) if p.split_angle != 0]
    if split and len(split) != len(pins):
        return [Problem("pins", f"split: {split}", "split_angle_deg must be given on every pin or on none")]
    return []


def split_engine(engine: Engine, pins: tuple[Cylinder, ...]) -> Engine:
    """``engine`` with each cylinder's half-pin angle and rod place on split ``pins`` (unchanged
    without split pins, or when the pins do not match its throws)."""
    if not any(p.split for p in pins) or len(pins) != engine.throws or not engine.bank_angles:
        return engine
    halves, offsets = [], []
    for c in range(engine.cylinders):
        pin = pins[engine.throw_of_cylinder(c)]
        rear = engine.bank_angles[c] != 0.0  # the reader gives the first bank exactly 0 (and refuses a 0 bank angle)
        halves.append(pin.split_angle if rear else 0.0)
        offsets.append((1.0 if rear else -1.0) * 0.25 * (pin.length + pin.flying_web))
    return replace(engine, half_pin_angles=tuple(halves), rod_offsets=tuple(offsets))


def centre_distance(stroke: float, split_angle: float) -> float:
    """Distance (m) between the two half pins' centres: the chord 2R sin(|δ|/2), R = stroke/2."""
    return stroke * math.sin(0.5 * abs(split_angle))


def split_problems(crank: Crank, show: Callable[[float], float], u: str) -> list[Problem]:
    """Each split pin's halves must have length (more than their fillet, and room for a drilling
    at each half's mid-length) and overlap: the half pins' centre distance below the diameter.
    ``show`` turns m into the file's unit ``u``."""
    out = []
    r, hole = crank.fillets.pin, crank.oil_holes.diameter if crank.oil_holes.in_pins else 0.0
    for i, p in enumerate(crank.pins):
        if not p.split or not all(math.isfinite(v) for v in (p.split_angle, p.flying_web, p.length)):
            continue
        where, h = f"pins.{i + 1}", p.half_length
        if not h > r:
            out.append(Problem(f"{where}.flying_web_thickness", show(p.flying_web),
                               f"leaves each half pin (length - flying web)/2 = {show(h)} {u}: must be longer than "
                               f"the {show(r)} {u} pin fillet at its outer end; thin the flying web or lengthen the pin"))
        elif hole > 0 and not 0.5 * h - 0.5 * hole - r > 1e-9:
            out.append(Problem(f"{where}.flying_web_thickness", show(p.flying_web),
                               f"leaves each half pin {show(h)} {u}: no room for the {show(hole)} {u} oil drilling at "
                               f"its mid-length beside the {show(r)} {u} fillet (needs more than 2 x fillet + "
                               f"drilling = {show(2 * r + hole)} {u})"))
        chord = centre_distance(crank.engine.stroke, p.split_angle)
        if not chord < p.diameter:
            out.append(Problem(f"{where}.split_angle_deg", round(math.degrees(p.split_angle), 6),
                               f"the two half pins do not overlap: at stroke {show(crank.engine.stroke)} {u} and "
                               f"split {math.degrees(p.split_angle):g} deg their centres lie 2R sin(split/2) = "
                               f"{show(chord)} {u} apart, not less than the pin diameter {show(p.diameter)} {u}; "
                               "the flying web alone would carry the throw"))
    return out
