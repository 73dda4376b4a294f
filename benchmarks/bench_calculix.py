"""fetorsion against CalculiX on the very same exported mesh: walls, ratio, frequencies.

    python benchmarks/bench_calculix.py                          # Peugeot GLX, default modal mesh
    python benchmarks/bench_calculix.py --purpose stress         # the 342 k-DOF stress mesh of issue 17

Steps (each a subprocess, timed from start to exit, start-up included):

1. ``fetorsion mesh FILE -o x.inp -o x.msh`` (one mesh written twice; not part of either wall);
2. ``fetorsion modal FILE --mesh x.msh --json fe.json``: fetorsion's wall;
3. ``ccx -i x`` (CalculiX ``*FREQUENCY`` on the C3D10 deck, free-free): CalculiX's wall.

Prints both walls, their ratio, peak memory and the largest relative difference of the
elastic frequencies. Use a crank without attachments (the Peugeot GLX is the crank alone):
the .inp deck carries the bare solid only. Needs ``ccx`` (Debian: ``apt-get install calculix-ccx``).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def timed(cmd: list[str], cwd: Path, env: dict | None = None) -> tuple[float, float, str]:
    """Run ``cmd``; (wall s, peak RSS GiB of that process, stdout). Raises on failure."""
    t = time.perf_counter()
    with open(cwd / "stdout.txt", "w") as out, open(cwd / "stderr.txt", "w") as err:
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=err, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{(cwd / 'stderr.txt').read_text()[-2000:]}")
    return wall, usage.ru_maxrss / 2**20, (cwd / "stdout.txt").read_text()


def ccx_frequencies(dat: Path) -> np.ndarray:
    """Frequencies (cycles/time, Hz) of CalculiX's eigenvalue output table, ascending."""
    text = dat.read_text()
    block = text.split("E I G E N V A L U E   O U T P U T")[1].split("P A R T I C I P A T I O N")[0]
    # MODE NO, EIGENVALUE, FREQUENCY real (rad/time), real (cycles/time), imaginary (rad/time)
    rows = re.findall(r"^\s*\d+\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$", block, flags=re.M)
    return np.array([float(r[2]) for r in rows])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--crank", default=str(ROOT / "geometry" / "peugeot_glx.toml"))
    p.add_argument("--mesh-size", type=float, default=10.0, help="global element size, mm")
    p.add_argument("--purpose", choices=("modal", "stress"), default="modal")
    p.add_argument("--modes", type=int, default=20, help="elastic modes")
    p.add_argument("--keep", metavar="DIR", help="work in DIR and keep the files")
    a = p.parse_args()
    if shutil.which("ccx") is None:
        sys.exit("ccx not found: apt-get install calculix-ccx")
    work = Path(a.keep) if a.keep else Path(tempfile.mkdtemp(prefix="fetorsion-ccx-"))
    work.mkdir(parents=True, exist_ok=True)
    crank = str(Path(a.crank).resolve())
    fetorsion = [sys.executable, "-m", "fetorsion.cli"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}

    t_mesh, _, out = timed(fetorsion + ["mesh", crank, "--mesh-size", str(a.mesh_size), "--purpose", a.purpose,
                                        "--modes", str(a.modes + 6), "-o", "x.inp", "-o", "x.msh"], work, env)
    print(out.strip().splitlines()[-1])
    t_fe, mem_fe, _ = timed(fetorsion + ["modal", crank, "--mesh", "x.msh", "--modes", str(a.modes),
                                         "--json", "fe.json"], work, env)
    fe = json.loads((work / "fe.json").read_text())
    t_ccx, mem_ccx, _ = timed(["ccx", "-i", "x"], work)
    f_fe = np.array([m["frequency_hz"] for m in fe["modes"]])
    f_ccx = ccx_frequencies(work / "x.dat")[6:6 + len(f_fe)]
    diff = np.abs(f_fe[:len(f_ccx)] / f_ccx - 1).max()
    t = fe["timings_s"]
    print(f"{Path(a.crank).stem}, {a.purpose} mesh {a.mesh_size:g} mm: {fe['mesh']['elements']} C3D10, "
          f"{fe['mesh']['dofs']} DOF, {a.modes} elastic modes (meshing {t_mesh:.1f} s, not counted)")
    print("| program | wall s | peak GiB | f1 Hz |")
    print("|---|---|---|---|")
    print(f"| fetorsion ({fe.get('first_torsional_hz', 0):.1f} Hz first torsional; assembly "
          f"{t.get('assembly', 0):.1f} s, factorise {t.get('factorize', 0):.1f} s, eigen {t.get('eigensolve', 0):.1f} s) "
          f"| {t_fe:.1f} | {mem_fe:.2f} | {f_fe[0]:.2f} |")
    print(f"| CalculiX {a.modes + 6} eigenvalues | {t_ccx:.1f} | {mem_ccx:.2f} | {f_ccx[0]:.2f} |")
    print(f"ratio fetorsion / CalculiX: {t_fe / t_ccx:.3f}; largest relative frequency difference "
          f"over {len(f_ccx)} elastic modes: {diff:.1e}")
    if not a.keep:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
