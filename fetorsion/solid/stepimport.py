"""A crank's ``[solid]`` STEP file as one OpenCASCADE volume (model units), placed where fetorsion
builds a crank (front centre at the origin, axis along +x, first pin at its described angle),
its length checked against the description's layout and its journals, pins, fillets and
drillings found (:mod:`fetorsion.solid.recognise`); or, for a throw, its slab of the solid."""

from __future__ import annotations

import math
from contextlib import contextmanager
from pathlib import Path

import gmsh
import numpy as np

from ..description.model import Crank
from ..errors import GeometryError
from .recognise import SolidFeatures, first_pin_turn, recognise, unit_slip


def imported_solid(crank: Crank, pieces, unit: float) -> tuple[int, SolidFeatures | None]:
    """The crank's ``[solid]`` STEP file as one OCC volume: its tag, and what was found on it
    (:func:`fetorsion.solid.recognise.recognise`; None for a throw's slab, whose whole crank was
    checked). Refused, naming the file, when it holds no closed volume, several bodies, a solid
    whose length disagrees with the description's layout (a wrong unit: :func:`~fetorsion.solid.recognise.unit_slip`), or
    journals and pins that are not the described ones.

    Parameters
    ----------
    crank : Crank
        The description (SI), with its ``[solid]`` file, placement and, for a throw, window.
    pieces : list
        Its layout (:func:`fetorsion.solid.geometry.layout`, model units).
    unit : float
        Metres per model length unit (:data:`fetorsion.solid.geometry.MODEL_UNIT`).

    Returns
    -------
    (int, SolidFeatures or None)
        The volume's tag in the current Gmsh model, and what was found on it.

    Raises
    ------
    GeometryError
        Naming the file, as above.
    """
    occ = gmsh.model.occ
    name = Path(crank.solid_step).name
    gmsh.option.setString("Geometry.OCCTargetUnit", "MM")  # OCC converts from the file header's unit
    try:
        with quiet_stdout():
            occ.importShapes(crank.solid_step)
    except Exception as exc:
        raise GeometryError(f"{name}: not a STEP file OpenCASCADE can read ({exc})") from None
    occ.synchronize()
    volumes = gmsh.model.getEntities(3)
    if not volumes:
        raise GeometryError(f"{name}: no closed volume in the file (open surfaces only?): give one solid crank")
    if len(volumes) > 1:
        out, _ = occ.fuse(volumes[:1], volumes[1:])
        occ.synchronize()
        if len(out) != 1:
            raise GeometryError(f"{name}: {len(out)} separate bodies, not one solid crank")
    (_, solid), = gmsh.model.getEntities(3)
    _place(crank, solid, pieces, unit)
    features = None
    if crank.solid_window is None:
        _check_length(name, solid, pieces)
        features = recognise(crank, pieces, solid, name, unit)
    else:  # a throw: its slab, moved to x = 0 and turned to put its pin at angle 0
        lo, hi, turn = crank.solid_window
        a, b = lo / unit, hi / unit
        box = occ.addBox(a, -1e4, -1e4, b - a, 2e4, 2e4)
        out, _ = occ.intersect([(3, solid)], [(3, box)])
        if len(out) != 1:
            raise GeometryError(f"{name}: the throw's slab x = {a:.6g}-{b:.6g} mm is {len(out)} pieces, not one")
        occ.translate(out, -a, 0, 0)
        occ.synchronize()
        solid = out[0][1]
        found = first_pin_turn(crank, pieces, solid, unit)  # its pin to angle 0, as found on it
        occ.rotate(out, 0, 0, 0, 1, 0, 0, turn if found is None else found)
        occ.synchronize()
        _check_length(name, solid, pieces)
    return solid, features


def _place(crank: Crank, solid: int, pieces, unit: float) -> None:
    """Move the imported ``solid`` where fetorsion builds a crank: ``[solid] front_centre`` to the
    origin, ``axis`` onto +x (one rotation about axis × x), then about x so that its first pin
    lies at the described angle (:func:`fetorsion.solid.recognise.first_pin_turn`; a CAD model's
    angular origin is its own)."""
    occ = gmsh.model.occ
    if crank.solid_placement is not None:
        axis, front = (np.asarray(v, float) for v in crank.solid_placement)
        occ.translate([(3, solid)], *(-front / unit))
        cos = float(axis[0])
        if cos < 1.0 - 1e-15:
            about = np.cross(axis, [1.0, 0.0, 0.0])
            if np.linalg.norm(about) < 1e-12:  # the axis is -x: half a turn about y
                about = np.array([0.0, 1.0, 0.0])
            occ.rotate([(3, solid)], 0, 0, 0, *about, math.acos(max(-1.0, cos)))
        occ.synchronize()
    if crank.solid_window is not None:
        return  # a throw's slab is turned once it is cut (its own pin found there)
    turn = first_pin_turn(crank, pieces, solid, unit)
    if turn is not None and abs(turn) > 1e-9:
        occ.rotate([(3, solid)], 0, 0, 0, 1, 0, 0, turn)
        occ.synchronize()


def _check_length(name: str, solid: int, pieces) -> None:
    """Refuse, naming the file, a solid whose length along x is not the layout's (a unit slip is
    named) or whose front end is not at x = 0."""
    x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(3, solid)
    length = pieces[-1].x1
    ratio = (x1 - x0) / length
    if abs(ratio - 1.0) > 0.02:
        slip = unit_slip(ratio)
        why = f"; {slip}" if slip else ""
        raise GeometryError(f"{name}: the solid is {x1 - x0:.6g} mm long along x, the description's crank "
                            f"{length:.6g} mm{why}")
    if abs(x0) > 0.02 * length:
        raise GeometryError(f"{name}: the solid starts at x = {x0:.6g} mm; its front (pulley) end must be at x = 0 "
                            "with the crank axis along x")


@contextmanager
def quiet_stdout():
    """File descriptor 1 sent to /dev/null for the duration (C++ writers ignore sys.stdout):
    OpenCASCADE's STEP reader and writer print to the process's stdout."""
    import os
    import sys

    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
