"""Issue 17: wall of ``fetorsion modal`` from process start, and its steps, for two source trees.

Each run is a fresh process (start-up, imports and meshing included), one after the other,
``--repeat`` times; the best of each figure is printed with the machine load before each run
(a shared machine: compare rows taken together only).

    python benchmarks/bench_modal_steps.py                       # this tree, Peugeot GLX, default mesh
    python benchmarks/bench_modal_steps.py --tree /tmp/base      # another checkout's fetorsion
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time


def run_once(crank: str, tree: str | None, modes: int) -> dict:
    """One ``fetorsion modal --json -`` in a fresh interpreter: wall from before start-up to exit."""
    env = dict(os.environ)
    # The tree goes first on sys.path (PYTHONPATH comes after the current directory), and an
    # editable install's import finder on sys.meta_path, which outranks sys.path, is dropped.
    code = ("import sys; sys.meta_path[:] = [f for f in sys.meta_path if '__editable__' not in "
            f"getattr(f, '__module__', '')]; sys.path.insert(0, {os.path.abspath(tree or '.')!r}); "
            "import fetorsion; print('tree', fetorsion.__file__, file=sys.stderr); "
            "from fetorsion.cli import main; sys.exit(main())")
    cmd = [sys.executable, "-c", code, "modal", crank, "--modes", str(modes), "--json", "-"]
    t = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t
    if out.returncode != 0:
        raise SystemExit(out.stderr)
    used = next(line.split(" ", 1)[1] for line in out.stderr.splitlines() if line.startswith("tree "))
    if not used.startswith(os.path.abspath(tree or ".")):
        raise SystemExit(f"ran {used}, not the tree {tree}")
    text = out.stdout
    d = json.loads(text[text.index("{"):text.rindex("}") + 1])
    tim = d.get("timings_s", {})
    return {"wall": wall, **{k: float(v) for k, v in tim.items()},
            "f1": d["modes"][0]["frequency_hz"] if d.get("modes") else float("nan"),
            "freqs": [m["frequency_hz"] for m in d.get("modes", [])]}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--crank", default="geometry/peugeot_glx.toml")
    p.add_argument("--tree", action="append", default=[], help="source tree(s) to compare (default: this one)")
    p.add_argument("--repeat", type=int, default=2)
    p.add_argument("--modes", type=int, default=20)
    a = p.parse_args()
    trees = a.tree or [""]
    best = {t: None for t in trees}
    for _ in range(a.repeat):
        for tree in trees:
            load = os.getloadavg()[0]
            r = run_once(a.crank, tree or None, a.modes)
            print(f"{tree or 'this tree'}: load {load:.2f} " + " ".join(
                f"{k} {v:.2f}" for k, v in r.items() if k != "freqs"), flush=True)
            b = best[tree]
            best[tree] = r if b is None else {k: (min(v, b[k]) if k != "freqs" else v) for k, v in r.items()}
    keys = [k for k in best[trees[0]] if k not in ("freqs", "f1")]
    print("| tree | " + " | ".join(keys) + " |\n|" + "---|" * (len(keys) + 1))
    for tree, r in best.items():
        print(f"| {tree or 'this tree'} | " + " | ".join(f"{r[k]:.2f}" for k in keys) + " |")
    if len(trees) > 1:
        f0, f1 = best[trees[0]]["freqs"], best[trees[1]]["freqs"]
        print("largest relative frequency difference:", max(abs(x / y - 1) for x, y in zip(f1, f0)))


if __name__ == "__main__":
    main()
