"""Time to the first verified passing design (issue 45): the inline six with a [design] table.

    nice python benchmarks/bench_design.py [--workers 2] [--generations 12] [--mesh-size 10] [--command-only]

Writes the inline six with the [design] table of the docs' example (webs and pins may move, a
rubber damper may be added) to a temporary folder, and, in a fresh sample store (a temporary
one: the user's store is not touched), times:

1. the explorer's search alone, here, one candidate after the other;
2. the same search on a local Dask cluster of ``--workers`` processes (its start included);
3. the whole ``fetorsion design`` command (search here, then ``fetorsion run`` of the written file:
   the condensed FE crank's verdict), as a user types it;
4. the same command again on the same store: the search's candidates are found there.

For 3 and 4 the peak resident memory of the command's whole process tree (the command, its
background process and any worker; psutil, sampled every 0.1 s) and of its largest process.
``--command-only`` times 3 and 4 alone. Prints the wall times, the candidates evaluated, the share of the command spent in the search
(the part whose candidates spread over more workers; the confirming run is one FE crank), the
chosen design and the FE verdict. States the CPU.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import psutil

ROOT = Path(__file__).resolve().parents[1]
DESIGN = ROOT / "examples" / "inline6_design_table.toml"

def cpu() -> str:
    try:
        return next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor()


def run_measured(cmd: list[str], env: dict, cwd: Path) -> tuple[subprocess.CompletedProcess, float, int, int]:
    """(the finished process, wall s, peak RSS of its process tree, peak RSS of one process: bytes)."""
    peak = {"tree": 0, "one": 0}
    done = threading.Event()

    def sample(root: psutil.Process) -> None:
        while not done.is_set():
            try:
                procs = [root, *root.children(recursive=True)]
            except psutil.NoSuchProcess:
                return
            rss = []
            for q in procs:
                try:
                    rss.append(q.memory_info().rss)
                except psutil.NoSuchProcess:
                    pass
            peak["tree"] = max(peak["tree"], sum(rss))
            peak["one"] = max(peak["one"], max(rss, default=0))
            done.wait(0.1)

    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=cwd)
    watcher = threading.Thread(target=sample, args=(psutil.Process(p.pid),), daemon=True)
    watcher.start()
    out, err = p.communicate()
    wall = time.perf_counter() - t0
    done.set()
    watcher.join()
    return subprocess.CompletedProcess(cmd, p.returncode, out, err), wall, peak["tree"], peak["one"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--generations", type=int, default=12)
    ap.add_argument("--mesh-size", type=float, default=10.0, help="mm, the confirming run's")
    ap.add_argument("--command-only", action="store_true", help="time fetorsion design alone (3 and 4)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="fetorsion-bench-design-") as tmp:
        tmp = Path(tmp)
        os.environ["FETORSION_STORE"] = str(tmp / "store")
        import fetorsion
        from fetorsion.design.search import run_design_search
        from fetorsion.studies.runner import open_client, open_store

        src = tmp / "inline6_design.toml"
        src.write_text((ROOT / "geometry/inline6_diesel.toml").read_text() + "\n" + DESIGN.read_text())
        crank = fetorsion.load(src)
        print(f"CPU: {cpu()}, {os.cpu_count()} cores; inline six, 3 variables, {args.generations} generations")

        here = None
        if not args.command_only:
            t0 = time.perf_counter()
            here = run_design_search(crank, maxiter=args.generations, store=open_store(tmp / "s1"))
            t_here = time.perf_counter() - t0
            print(f"search here:            {t_here:7.1f} s, {len(here.candidates)} candidates "
                  f"({1e3 * t_here / len(here.candidates):.0f} ms each)")
            t0 = time.perf_counter()
            with open_client(workers=args.workers) as client:
                there = run_design_search(crank, maxiter=args.generations, store=open_store(tmp / "s2"), client=client)
            t_there = time.perf_counter() - t0
            same = [c.values for c in there.candidates] == [c.values for c in here.candidates]
            print(f"search, {args.workers} Dask workers: {t_there:7.1f} s (cluster start included), the same search: {same}")

        env = dict(os.environ, FETORSION_STORE=str(tmp / "s3"))
        cmd = [sys.executable, "-m", "fetorsion.cli", "design", str(src), "--out", str(tmp / "out"),
               "--generations", str(args.generations), "--mesh-size", str(args.mesh_size), "--force"]
        times, trees, ones = [], [], []
        for _ in range(2):
            p, wall, tree, one = run_measured(cmd, env, ROOT)
            times.append(wall)
            trees.append(tree)
            ones.append(one)
            if p.returncode not in (0, 1):
                raise SystemExit(f"fetorsion design failed:\n{p.stderr[-3000:]}")
        verdict = [line for line in p.stdout.splitlines() if line.startswith(("confirmation", "the designed crank"))]
        share = "" if here is None else (f" (search {t_here:.0f} s = {100 * t_here / times[0]:.0f} % of it, "
                                         "the part more workers share)")
        gib = 2.0**30
        print(f"fetorsion design:       {times[0]:7.1f} s{share}; peak RSS {trees[0] / gib:.2f} GiB (process tree), "
              f"{ones[0] / gib:.2f} GiB (largest process)")
        print(f"again, same store:      {times[1]:7.1f} s (the search's candidates found in the store); peak RSS "
              f"{trees[1] / gib:.2f} GiB (tree), {ones[1] / gib:.2f} GiB (largest)")
        print("the command's last lines:\n  " + "\n  ".join(p.stdout.splitlines()[-12:]))
        if here is None:
            print("\n".join(verdict))
            return
        b = here.best
        print(f"chosen: mass {b.objective:.2f} kg (given {here.given.objective:.2f}), explorer safety {b.safety:.3f}; "
              + "; ".join(f"{k} = {v:.3g}" for k, v in b.values.items())
              + (f"; {b.damper.kind} damper, ring {b.damper.ring_inertia:.4g} kg m^2" if b.damper else ""))
        print("\n".join(verdict))


if __name__ == "__main__":
    main()
