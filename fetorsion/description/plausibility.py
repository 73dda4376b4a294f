"""Plausibility: values that parse and obey every rule, yet fit no engine (most often a wrong
``[units] length``). Warnings, not errors: one line each, naming the field."""

from __future__ import annotations

import math

from .model import Crank
from .units import LENGTH_UNITS

# Engines span model engines (a few mm of stroke) to marine two-strokes (bore 0.96 m,
# stroke 3.2 m); the ratios cover car, truck, motorcycle and marine cranks with room to spare.
_STROKE_RANGE_M = (0.005, 4.0)
_RATIO_RULES = (  # (field, value of, relative to, low, high)
    ("journals.*.diameter", "journals", "diameter", 0.2, 3.0),
    ("pins.*.diameter", "pins", "diameter", 0.2, 3.0),
    ("webs.*.thickness", "webs", "thickness", 0.03, 2.0),
    ("journals.*.length", "journals", "length", 0.05, 3.0),
    ("pins.*.length", "pins", "length", 0.05, 3.0),
    ("front.*.diameter", "front", "diameter", 0.05, 5.0),
    ("front.*.length", "front", "length", 0.01, 5.0),
    ("rear.*.diameter", "rear", "diameter", 0.05, 5.0),
    ("rear.*.length", "rear", "length", 0.01, 5.0),
)


def plausibility_warnings(crank: Crank) -> list[str]:
    """One line for each dimension far outside any engine (a likely unit mix-up or typo).

    Not errors: the description is valid and the analysis runs; the user is told which
    value to check. Sizes are compared with the stroke, the one length every engine has.
    """
    u, scale = crank.length_unit, LENGTH_UNITS[crank.length_unit]
    stroke = crank.engine.stroke
    out = []
    lo, hi = _STROKE_RANGE_M
    if not lo <= stroke <= hi:
        hint = {True: 'is [units] length = "m" meant to be "mm"?', False: "is [units] length right?"}[
            u == "m" and stroke > hi]
        out.append(f"engine.stroke = {stroke / scale:g} {u} ({stroke:g} m) is outside any engine "
                   f"({lo * 1e3:g} mm to {hi:g} m): {hint}")
    for field_name, group, attr, low, high in _RATIO_RULES:
        values = [getattr(x, attr) for x in getattr(crank, group)]
        bad = [i for i, v in enumerate(values) if not low <= v / stroke <= high]
        if bad:
            i = bad[0]
            more = f" (and {len(bad) - 1} more)" if len(bad) > 1 else ""
            out.append(f"{field_name.replace('*', str(i + 1))} = {values[i] / scale:g} {u}{more} is "
                       f"{values[i] / stroke:.3g} × the stroke; engines have {low:g}-{high:g}: check the value")
    lam = crank.engine.crank_radius / crank.engine.rod_length
    if not 0.1 <= lam <= 0.5:
        out.append(f"engine.rod_length = {crank.engine.rod_length / scale:g} {u} gives crank radius/rod length "
                   f"{lam:.3g}; engines have 0.1-0.5: check the value")
    bore = crank.engine.bore
    if bore > 0 and not 0.3 <= bore / stroke <= 3.0:
        out.append(f"engine.bore = {bore / scale:g} {u} is {bore / stroke:.3g} × the stroke; engines have 0.3-3: "
                   "check the value")
    return out + _split_warnings(crank, u, scale)


#: Split pins of real engines: 15-30° on 90° V6s (semi-even and even firing), 60° on 60° V6s [R];
#: a flying web is a few millimetres to a third of the pin diameter thick.
_SPLIT_RANGE_DEG = (10.0, 75.0)
_FLYING_WEB_RATIO = (0.04, 0.5)


def _split_warnings(crank: Crank, u: str, scale: float) -> list[str]:
    """Split pins far from any engine's: the split angle, the flying web against the pin."""
    out = []
    for i, p in enumerate(crank.pins):
        if not p.split:
            continue
        deg = abs(math.degrees(p.split_angle))
        if not _SPLIT_RANGE_DEG[0] <= deg <= _SPLIT_RANGE_DEG[1]:
            out.append(f"pins.{i + 1}.split_angle_deg = {math.degrees(p.split_angle):g} is outside the splits of "
                       f"split-pin engines ({_SPLIT_RANGE_DEG[0]:g}-{_SPLIT_RANGE_DEG[1]:g} deg): check the value")
        ratio = p.flying_web / p.diameter
        if not _FLYING_WEB_RATIO[0] <= ratio <= _FLYING_WEB_RATIO[1]:
            out.append(f"pins.{i + 1}.flying_web_thickness = {p.flying_web / scale:g} {u} is {ratio:.3g} x the pin "
                       f"diameter; flying webs have {_FLYING_WEB_RATIO[0]:g}-{_FLYING_WEB_RATIO[1]:g}: check the value")
    return out
