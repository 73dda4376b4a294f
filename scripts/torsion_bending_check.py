"""How much of a free-free crank's first torsional frequency is torsion-bending coupling?

Run from the repository root (about 2 minutes on 2 cores at the default 12 mm mesh):

    nice -n 10 python scripts/torsion_bending_check.py [geometry/peugeot_glx.toml] [--size 0.012]

A lumped torsional chain has no bending, so it cannot follow a 3D crank whose throws, loaded
by their own eccentric inertia (pins, counterweights), also bend. This script solves the
free-free 3D FE modes of the bare crank (no attachments) twice, with a thin ring of surface
nodes at the middle of every main journal tied to a massless rigid body:

1. rings free: the crank as tested (the rings stiffen it only locally);
2. rings held in y and z (like bearings, tilt and twist free): the throws can no longer
   swing sideways, what is left is closer to the torsion-only chain.

It prints the lowest modes of each with each ring's twist and lateral tilt, and the gap
between the two first torsional frequencies. Static torsion of the throws (the ``fe`` web
method) is checked separately: the whole crank's static FE equals its throws in series
(tests/test_throwfe.py).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import fetorsion  # noqa: E402
from fetorsion.fe import assembly, eigen  # noqa: E402
from fetorsion.fe.crankfe import part_nodes  # noqa: E402
from fetorsion.solid.mesh import mesh_crank  # noqa: E402
from fetorsion.fe.rigid import RigidBody, reduction  # noqa: E402
from fetorsion.fe.tetmesh import TetMesh  # noqa: E402

RING_HALF_WIDTH = 0.004  # m either side of the journal's mid-plane


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", nargs="?", default=str(ROOT / "geometry" / "peugeot_glx.toml"))
    ap.add_argument("--size", type=float, default=0.012, help="global element size, m")
    args = ap.parse_args(argv)
    crank = fetorsion.load(args.file)
    cm = mesh_crank(crank, args.size)
    m, dof_of_node = assembly.skfem_mesh(TetMesh(cm.nodes, cm.tets))
    basis = assembly.p2_basis(m)
    pat = assembly.block_pattern(basis)
    mat = crank.material
    K = assembly.stiffness(basis, mat.youngs_modulus, mat.poisson_ratio, pat)
    M = assembly.mass(basis, mat.density, pat)
    bodies = []
    for j, journal in enumerate(crank.journals):
        nodes = part_nodes(cm, f"journal_{j + 1}")
        p = cm.nodes[nodes]
        xm = 0.5 * (p[:, 0].min() + p[:, 0].max())
        surface = np.hypot(p[:, 1], p[:, 2]) > 0.49 * journal.diameter
        ring = nodes[surface & (np.abs(p[:, 0] - xm) < RING_HALF_WIDTH)]
        bodies.append(RigidBody(f"J{j + 1}", dof_of_node[ring], 0.0, np.zeros((3, 3)), np.array([xm, 0.0, 0.0])))
    red = reduction(K.shape[0], bodies, m.doflocs.T)
    Kr, Mr = red.reduce(K), red.reduce(M)
    n = red.n_free
    sigma = -(2 * np.pi * 100.0) ** 2
    print(f"{crank.name}: {K.shape[0]} DOF, {len(bodies)} journal rings")
    first = {}
    lateral = [n + 6 * b + k for b in range(len(bodies)) for k in (1, 2)]  # ty, tz of every ring
    for label, drop in (("rings free", []), ("rings held in y, z", lateral)):
        keep = np.setdiff1d(np.arange(Kr.shape[0]), drop)
        res = eigen.lowest_modes(Kr[keep][:, keep], Mr[keep][:, keep], 12, sigma)
        pos = np.full(Kr.shape[0], -1)
        pos[keep] = np.arange(len(keep))
        print(f"\n{label}: mode (Hz), ring twist θx and ring tilt |θy, θz| (×1e3, M-normalised)")
        for j in range(len(res.omega2)):
            f = np.sqrt(abs(res.omega2[j])) / (2 * np.pi)
            if f < 1.0:
                continue
            v = res.vectors[:, j]
            tx = np.array([v[pos[n + 6 * b + 3]] for b in range(len(bodies))])
            tilt = np.array([np.hypot(v[pos[n + 6 * b + 4]], v[pos[n + 6 * b + 5]]) for b in range(len(bodies))])
            torsional = np.abs(tx).max() > np.abs(tilt).max()
            if torsional and label not in first:
                first[label] = f
            kind = "T" if torsional else "B"
            print(f"  {f:8.1f}  {kind}  twist {np.round(tx * 1e3, 1)}  tilt {np.round(tilt * 1e3, 1)}")
    if len(first) == 2:
        a, b = first.values()
        print(f"\nfirst torsional: {a:.1f} Hz free, {b:.1f} Hz held laterally ({100 * (b / a - 1):+.1f} %)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
