"""Off-screen picture of the crank solid, so a user sees the crank they described."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from .crank import Crank
from .geometry import build_solid, gmsh_session, surface_triangles
from .io import atomic_output

# Journals, webs, pins, end sections: one colour per kind, picked to read in grey-scale too.
_COLOURS = {"front": "#7f7f7f", "journal": "#4c72b0", "web": "#c8c8c8", "pin": "#dd8452", "rear": "#7f7f7f"}


def render_png(crank: Crank, path, size: float = 0.006, window: tuple[int, int] = (1600, 900)) -> Path:
    """Render ``crank``'s solid to a PNG file, off-screen and atomically.

    Parameters
    ----------
    crank : Crank
    path : str or Path
        Output ``.png``.
    size : float
        Largest triangle edge of the picture's surface mesh, m.
    window : (int, int)
        Picture width and height, pixels.
    """
    # VTK needs a display unless told to render through EGL; respect a user's own choice.
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    pv.OFF_SCREEN = True
    with gmsh_session("picture"):
        solid = build_solid(crank)
        points, tris, part = surface_triangles(solid, size)
    kinds = np.array([p.kind for p in solid.parts])[part]
    faces = np.column_stack([np.full(len(tris), 3), tris]).ravel()
    surf = pv.PolyData(points * 1e3, faces)  # mm reads better on the axes
    plotter = pv.Plotter(off_screen=True, window_size=list(window))
    plotter.set_background("white")
    for kind, colour in _COLOURS.items():
        sel = np.flatnonzero(kinds == kind)
        if sel.size:
            plotter.add_mesh(surf.extract_cells(sel), color=colour, smooth_shading=True, specular=0.3)
    plotter.add_text(f"{crank.name}", font_size=12, color="black")
    plotter.show_axes()
    # Look across the axis (x, horizontal in the picture), a little from the front and
    # above, so the throws at their crank angles show.
    centre = surf.center
    plotter.camera_position = [(centre[0] - 300, centre[1] - 900, centre[2] + 400), centre, (0, 0, 1)]
    plotter.reset_camera()
    plotter.camera.zoom(1.3)
    path = Path(path)
    with atomic_output(path) as tmp:
        plotter.screenshot(str(tmp))
    plotter.close()
    return path
