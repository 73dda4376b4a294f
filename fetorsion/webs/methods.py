"""The one registry of web methods: name -> ``method(crank, web_index, d_e) -> L_eb`` (m).

Add a method by writing such a function and naming it in :data:`WEB_METHODS`. Two methods
are computed rather than quoted (docs/web-chart.md): ``fe``, the static 3D FE of the web's
own throw (:mod:`fetorsion.webs.throwfe`), and ``chart``, fetorsion's computed counterpart
of the BICERA chart (:mod:`fetorsion.webs.chart`); they load Gmsh and scikit-fem only when
called.
"""

from __future__ import annotations

import math
from typing import Callable

from ..description.model import Crank
from ..description.defaults import DEFAULT_WEB_METHOD
from ..errors import FetorsionError
from .classical import beam, carter, ker_wilson


def fe(crank: Crank, web_index: int, d_e: float) -> float:
    """Web term of the throw's static 3D FE torsion (:mod:`fetorsion.webs.throwfe`), per web, m."""
    from .throwfe import web_equivalent_length_fe

    return web_equivalent_length_fe(crank, web_index, d_e)


def fe_held(crank: Crank, web_index: int, d_e: float) -> float:
    """Web term of the throw's stiffness inside the whole crank held by rigid bearings
    (:func:`fetorsion.webs.throwfe.held_throw_stiffnesses`), per web, m."""
    from .throwfe import web_equivalent_length_held

    return web_equivalent_length_held(crank, web_index, d_e)


def chart(crank: Crank, web_index: int, d_e: float) -> float:
    """Web term from fetorsion's computed BICERA-style chart (:mod:`fetorsion.webs.chart`), m."""
    from .chart import web_equivalent_length_chart

    return web_equivalent_length_chart(crank, web_index, d_e)


WebMethod = Callable[[Crank, int, float], float]

WEB_METHODS: dict[str, WebMethod] = {"carter": carter, "ker-wilson": ker_wilson, "beam": beam, "fe": fe,
                                     "fe-held": fe_held, "chart": chart}
#: What each method becomes with the crank in its bearings (``--support bearings``); the
#: classical formulas and the chart have no support condition.
IN_BEARINGS = {"fe": "fe-held"}

#: The methods that take a split pin's throw (its flying web): the throw FE, which builds the solid
#: with its half pins; the formulas and the chart describe a throw with one straight pin.
SPLIT_PIN_METHODS = ("fe", "fe-held")

__all__ = ["DEFAULT_WEB_METHOD", "IN_BEARINGS", "SPLIT_PIN_METHODS", "WEB_METHODS", "WebMethod", "crank_web_method",
           "web_equivalent_length"]


def crank_web_method(crank: Crank) -> str:
    """The web method a crank's analyses take when none is named: :data:`DEFAULT_WEB_METHOD`, or
    ``fe`` for a crank with split pins (which no formula takes)."""
    return SPLIT_PIN_METHODS[0] if any(p.split for p in getattr(crank, "pins", ())) else DEFAULT_WEB_METHOD


def web_equivalent_length(crank: Crank, web_index: int, d_e: float, method: str = DEFAULT_WEB_METHOD) -> float:
    """Equivalent length L_eb (m, at D_e) of web ``web_index`` (0-based) by ``method``."""
    try:
        fn = WEB_METHODS[method]
    except KeyError:
        raise FetorsionError(
            f"stiffness method {method!r} is not known; choose one of {', '.join(WEB_METHODS)}") from None
    pin = crank.pins[web_index // 2] if web_index // 2 < len(crank.pins) else None
    if pin is not None and pin.split and method not in SPLIT_PIN_METHODS:
        raise FetorsionError(
            f"webs.{web_index + 1}: pins.{web_index // 2 + 1} is a split pin (two half pins "
            f"{math.degrees(pin.split_angle):g} deg apart with a flying web): the {method} method has no term for "
            f"its flying web; use a throw FE method ({', '.join(SPLIT_PIN_METHODS)})")
    value = fn(crank, web_index, d_e)
    if not value > 0:
        raise FetorsionError(
            f"webs.{web_index + 1}: the {method} formula gives a non-positive equivalent length "
            f"({value:.4g} m); this web is outside the range the formula was made for")
    return value
