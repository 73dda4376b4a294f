"""Why fetorsion's and CalculiX's frequencies differ by about 2e-4 on the very same mesh: quadrature.

    python benchmarks/bench_calculix_quadrature.py [--crank geometry/peugeot_glx.toml] [--mesh-size 20]

CalculiX integrates a C3D10 element's stiffness *and* mass with the same four-point rule
(``e_c3d.f``: ``mint3d=4`` with the ``gauss3d5`` points for ``lakonl(4:5).eq.'10'`` under the
default ``intscheme=0``; [CalculiX]), exact to degree 2. The consistent P2 mass integrand N_i N_j is
of degree 4 on a straight tetrahedron, so CalculiX's mass matrix is under-integrated; fetorsion
integrates both matrices to degree 4 (:data:`fetorsion.fe.assembly.INTORDER`, 11 points).

One mesh is written as ``.msh`` and ``.inp`` (``fetorsion mesh``); CalculiX solves the deck; the
same mesh is then solved in-process by :func:`fetorsion.fe.modal.modal` with each matrix
integrated to degree 4 (fetorsion's) or degree 2 (CalculiX's rule). If the quadrature is the cause,
fetorsion with CalculiX's rule for both matrices meets CalculiX's frequencies to the eigen-solvers'
tolerance, and the mass rule alone carries the gap. Prints a table: the largest and median relative
difference of the elastic frequencies against CalculiX's, per pair of rules.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_calculix import ccx_frequencies  # noqa: E402


def solve(mesh, material, modes: int, stiffness_order: int, mass_order: int) -> np.ndarray:
    """Elastic frequencies (Hz) of ``mesh`` with each matrix integrated to the given degree."""
    from unittest import mock

    from fetorsion.fe import assembly
    from fetorsion.fe.modal import modal

    stiffness, mass_blocks = assembly.stiffness, assembly.mass_blocks

    def k(basis, *args, **kwargs):
        return stiffness(assembly.p2_basis(basis.mesh, stiffness_order), *args, **kwargs)

    def m(basis, *args, **kwargs):
        return mass_blocks(assembly.p2_basis(basis.mesh, mass_order), *args, **kwargs)

    with mock.patch.object(assembly, "stiffness", k), mock.patch.object(assembly, "mass_blocks", m):
        return modal(mesh, material, modes=modes, keep_shapes=False).frequencies_hz


def points(order: int) -> int:
    """Quadrature points per tetrahedron of scikit-fem's rule of ``order``."""
    from skfem import MeshTet
    from skfem.quadrature import get_quadrature

    return get_quadrature(MeshTet().refdom, order)[0].shape[1]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--crank", default=str(ROOT / "geometry" / "peugeot_glx.toml"))
    p.add_argument("--mesh-size", type=float, default=20.0, help="global element size, mm")
    p.add_argument("--modes", type=int, default=12)
    p.add_argument("--keep", metavar="DIR", help="work in DIR and keep its files (a second call reuses CalculiX's)")
    a = p.parse_args()
    if shutil.which("ccx") is None:
        raise SystemExit("needs CalculiX: apt-get install calculix-ccx")
    import fetorsion
    from fetorsion.fe.tetmesh import TetMesh
    from fetorsion.solid.mesh import read_mesh

    crank = fetorsion.load(a.crank)
    exe = [sys.executable, "-c", "import sys; from fetorsion.cli import console; sys.exit(console())"]
    keep = Path(a.keep) if a.keep else None
    with tempfile.TemporaryDirectory() as tmp:
        tmp = keep or Path(tmp)
        tmp.mkdir(parents=True, exist_ok=True)
        ccx_wall = float("nan")
        if not (tmp / "x.dat").exists():  # --keep: CalculiX's solution of an earlier call is read again
            subprocess.run(exe + ["mesh", a.crank, "--mesh-size", str(a.mesh_size), "--modes", str(a.modes + 6),
                                  "-o", str(tmp / "x.inp"), "-o", str(tmp / "x.msh")],
                           check=True, capture_output=True, cwd=ROOT)
            t = time.perf_counter()
            subprocess.run(["ccx", "-i", "x"], cwd=tmp, check=True, capture_output=True)
            ccx_wall = time.perf_counter() - t
        ccx = ccx_frequencies(tmp / "x.dat")
        cm = read_mesh(tmp / "x.msh", crank)
        mesh = TetMesh(cm.nodes, cm.tets)
    elastic = ccx[6:][: a.modes]
    print(f"{crank.name}, {a.mesh_size:g} mm: {len(mesh.tets)} ten-node tetrahedra, {3 * len(np.unique(mesh.tets))} DOF; "
          f"CalculiX {ccx_wall:.1f} s, its first elastic {elastic[0]:.3f} Hz")
    print("| stiffness rule | mass rule | largest relative difference to CalculiX | median |")
    print("|---|---|---|---|")
    for ks, ms in ((4, 4), (2, 2), (4, 2), (2, 4)):
        f = solve(mesh, crank.material, len(elastic), ks, ms)[: len(elastic)]
        d = np.abs(f / elastic - 1)
        print(f"| degree {ks} ({points(ks)} points) | degree {ms} ({points(ms)} points) | {d.max():.2e} | {np.median(d):.2e} |")


if __name__ == "__main__":
    main()
