"""Off-screen images of the crank solid and its FE mode shapes with PyVista (no display needed).

VTK renders through EGL with Mesa's software rasteriser when there is no X server
(``scripts/setup.sh`` installs libegl1/libegl-mesa0/libgl1-mesa-dri); the EGL window is
selected before VTK is imported so it never looks for a display.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..description.defaults import DEFAULT_MESH_SIZE
from ..io import atomic_output

if TYPE_CHECKING:
    from ..description.model import Crank

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
# One rasteriser thread (Mesa's llvmpipe takes one per core otherwise): ``fetorsion run`` draws its
# mode images while its background studies hold the other core at a lower priority, and a
# second rasteriser thread only takes that core from them (Renault 21, 2 cores: run 45.2 → 43.8 s;
# one image alone 0.42 → 0.59 s). Read when the driver loads; a user's own setting is kept.
os.environ.setdefault("LP_NUM_THREADS", "1")

BACKGROUND = "white"
#: A mode is drawn with its largest displacement this share of the model's size.
MODE_SCALE_FRACTION = 0.08


def _pyvista():
    import pyvista as pv

    pv.OFF_SCREEN = True
    return pv


def surface(nodes: np.ndarray, tets: np.ndarray):
    """The outer surface of a tetrahedral mesh as a PyVista PolyData (corner nodes only).

    ``nodes`` (n, 3) in m, ``tets`` (m, 4) or (m, 10) node indices (VTK/meshio order: the
    first four are the corners).
    """
    pv = _pyvista()
    corners = np.asarray(tets)[:, :4]
    cells = np.hstack([np.full((len(corners), 1), 4), corners]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(len(corners), pv.CellType.TETRA, dtype=np.uint8),
                               np.asarray(nodes, dtype=float))
    return grid.extract_surface(algorithm="dataset_surface")


def mode_scale(nodes: np.ndarray, displacement: np.ndarray, fraction: float = MODE_SCALE_FRACTION) -> float:
    """Scale factor that makes the largest displacement ``fraction`` of the model's size."""
    size = np.ptp(nodes, axis=0).max()
    peak = np.linalg.norm(displacement, axis=1).max()
    return fraction * size / peak if peak > 0 else 0.0


def render_mode(nodes: np.ndarray, tets: np.ndarray, displacement: np.ndarray, path: str | Path, title: str = "",
                window_size: tuple[int, int] = (1400, 600), fraction: float = MODE_SCALE_FRACTION,
                places: Sequence[tuple[np.ndarray | Sequence[float], str]] = ()):
    """Write a PNG of one mode: deformed shape coloured by |u|, undeformed outline, two views,
    the places named (``places``: (point (3,) m, name), the pulley and flywheel ends, say) and
    the deformation's scale stated under the title.

    Parameters
    ----------
    nodes : (n, 3) array
        Node coordinates, m; the crank axis is x.
    tets : (m, 4) or (m, 10) int array
        Tetrahedra (VTK/meshio node order).
    displacement : (n, 3) array
        Mode shape at the nodes (any scale).
    path : str or Path
        Output PNG, written atomically.
    title : str
        Text on the image (frequency and kind, say).
    places : sequence of (array_like, str)
        Points to name on both views.
    """
    pv = _pyvista()
    nodes = np.asarray(nodes, dtype=float)
    displacement = np.asarray(displacement, dtype=float)
    surf = surface(nodes, tets)
    surf["u"] = displacement[surf["vtkOriginalPointIds"]]
    peak = np.linalg.norm(displacement, axis=1).max()
    surf["|u|"] = np.linalg.norm(surf["u"], axis=1) / (peak if peak > 0 else 1.0)
    warped = surf.warp_by_vector("u", factor=mode_scale(nodes, displacement, fraction))
    outline = surf.extract_feature_edges(feature_angle=40, boundary_edges=False, manifold_edges=False)
    plotter = pv.Plotter(off_screen=True, shape=(1, 2), window_size=window_size, border=False)
    plotter.set_background(BACKGROUND)
    for col, view in enumerate(("side", "iso")):
        plotter.subplot(0, col)
        plotter.add_mesh(outline, color="#999999", line_width=1.0)
        plotter.add_mesh(warped, scalars="|u|", cmap="viridis", show_scalar_bar=(col == 1),
                         scalar_bar_args={"title": "|u| / max |u|", "color": "black"})
        if view == "side":
            plotter.view_vector((0.0, -1.0, 0.0), viewup=(0.0, 0.0, 1.0))
        else:
            plotter.view_vector((1.0, -1.2, 0.8), viewup=(0.0, 0.0, 1.0))
        if places:  # marked on the model, named at the edge of the view on their side (x runs left to right)
            points = np.array([p for p, _ in places], float)
            plotter.add_points(points, color="crimson", point_size=12, render_points_as_spheres=True)
            corners = ("lower_left", "lower_right") if view == "side" else ("upper_left", "right_edge")
            for k, ((point, name), corner) in enumerate(zip(sorted(places, key=lambda q: q[0][0]), corners)):
                plotter.add_text(f"<- {name}" if k == 0 else f"{name} ->", position=corner, font_size=9,
                                 color="crimson")
        plotter.reset_camera()
        plotter.camera.zoom(1.15)
        if col == 0 and title:
            plotter.add_text(f"{title}\n{scale_text(fraction)}", font_size=11, color="black")
    return _screenshot(plotter, path)


def scale_text(fraction: float = MODE_SCALE_FRACTION) -> str:
    """How a mode image's deformation is scaled (a mode shape has no size of its own)."""
    return (f"deformation drawn with its largest displacement {100 * fraction:g} % of the crank's length; "
            "colour |u| / max |u|; grey: undeformed edges")


def _screenshot(plotter, path) -> Path:
    """Write the plotter's picture to ``path`` atomically and close the plotter."""
    path = Path(path)
    try:
        with atomic_output(path) as tmp:
            plotter.screenshot(str(tmp))
    finally:
        plotter.close()
    return path


def render_gif(nodes, tets, displacement, path, title: str = "", frames: int = 16, window_size=(800, 500),
               fraction: float = MODE_SCALE_FRACTION):
    """Write an animated GIF of one mode swinging through a period (Pillow writes the GIF)."""
    from PIL import Image

    pv = _pyvista()
    nodes = np.asarray(nodes, dtype=float)
    displacement = np.asarray(displacement, dtype=float)
    surf = surface(nodes, tets)
    u = displacement[surf["vtkOriginalPointIds"]] * mode_scale(nodes, displacement, fraction)
    base = surf.points.copy()
    plotter = pv.Plotter(off_screen=True, window_size=window_size)
    plotter.set_background(BACKGROUND)
    moving = surf.copy()
    moving["|u|"] = np.linalg.norm(u, axis=1)
    plotter.add_mesh(moving, scalars="|u|", cmap="viridis", show_scalar_bar=False)
    plotter.view_vector((1.0, -1.2, 0.8), viewup=(0.0, 0.0, 1.0))
    if title:
        plotter.add_text(title, font_size=10, color="black")
    images = []
    try:
        for phase in np.linspace(0, 2 * np.pi, frames, endpoint=False):
            moving.points = base + np.sin(phase) * u
            plotter.render()
            images.append(Image.fromarray(plotter.screenshot(return_img=True)))
    finally:
        plotter.close()
    path = Path(path)
    with atomic_output(path) as tmp:
        images[0].save(tmp, save_all=True, append_images=images[1:], duration=80, loop=0)
    return path


# Journals, webs, pins, end sections: one colour per kind, picked to read in grey-scale too.
_COLOURS = {"front": "#7f7f7f", "journal": "#4c72b0", "web": "#c8c8c8", "pin": "#dd8452", "rear": "#7f7f7f",
            "fillet": "#d62728", "drilling": "#2ca02c"}


def render_solid(crank: Crank, path: str | Path, size: float = DEFAULT_MESH_SIZE,
                 window: tuple[int, int] = (1600, 900)) -> Path:
    """Render ``crank``'s solid to a PNG file, off-screen and atomically.

    Parameters
    ----------
    crank : fetorsion.description.model.Crank
    path : str or Path
        Output ``.png``.
    size : float
        Largest triangle edge of the picture's surface mesh, m.
    window : (int, int)
        Picture width and height, pixels.
    """
    from ..solid.geometry import build_solid, gmsh_session, surface_triangles

    pv = _pyvista()
    with gmsh_session("picture"):
        solid = build_solid(crank)
        points, tris, part, surface = surface_triangles(solid, size)
    kinds = np.array([p.kind for p in solid.parts], dtype=object)[part]
    # what the geometry step found on the solid, over the parts' colours: fillets, drillings
    kinds[np.isin(surface, solid.fillet_faces)] = "fillet"
    kinds[np.isin(surface, solid.hole_faces)] = "drilling"
    faces = np.column_stack([np.full(len(tris), 3), tris]).ravel()
    surf = pv.PolyData(points * 1e3, faces)  # mm reads better on the axes
    plotter = pv.Plotter(off_screen=True, window_size=list(window))
    plotter.set_background("white")
    for kind, colour in _COLOURS.items():
        sel = np.flatnonzero(kinds == kind)
        if sel.size:
            plotter.add_mesh(surf.extract_cells(sel), color=colour, smooth_shading=True, specular=0.3)
    found = (f"{sum(p.kind == 'journal' for p in solid.parts)} journals (blue), "
             f"{sum(p.kind == 'pin' for p in solid.parts)} pins (orange), webs (grey), "
             f"{len(solid.fillet_faces)} fillet faces (red), {len(solid.hole_faces)} drilling faces (green)")
    source = f"CAD solid {Path(crank.solid_step).name}" if getattr(crank, "solid_step", None) else "built from the dimensions"
    plotter.add_text(f"{crank.name}\n{source}: {found}", font_size=10, color="black")
    plotter.show_axes()
    # Look across the axis (x, horizontal in the picture), a little from the front and
    # above, so the throws at their crank angles show.
    centre = surf.center
    plotter.camera_position = [(centre[0] - 300, centre[1] - 900, centre[2] + 400), centre, (0, 0, 1)]
    plotter.reset_camera()
    plotter.camera.zoom(1.3)
    return _screenshot(plotter, path)
