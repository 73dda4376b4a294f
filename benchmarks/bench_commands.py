"""Every command on the run's crank (issue 40): the first command that needs the condensed crank
builds and keeps it; the next ones read it from the store.

    nice python benchmarks/bench_commands.py [geometry/renault21.toml] [--repeat 3]

In a fresh store folder (a temporary one: the user's store is not touched), times whole
``fetorsion`` processes, as a user types them: ``condense`` (builds and keeps the crank), then
``campbell``, ``response`` and ``damper --optimise`` (each reads it), ``--repeat`` times each, and
prints the wall times, the store's size, and each command's first torsional frequency in bearings,
order-6 crossing speed and largest section torque (they must agree: one model). States the CPU.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def cpu() -> str:
    try:
        return next(line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor()


def timed(args, env) -> tuple[float, str, str]:
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "fetorsion.cli", *args], capture_output=True, text=True, env=env, cwd=ROOT)
    if p.returncode:
        raise SystemExit(f"fetorsion {' '.join(args)} failed:\n{p.stderr}")
    return time.perf_counter() - t0, p.stdout, p.stderr


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", nargs="?", default=str(ROOT / "geometry" / "renault21.toml"))
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="fetorsion-bench-store-") as store:
        env = {**os.environ, "FETORSION_STORE": store}
        print(f"{args.file} on {cpu()}, {os.cpu_count()} cores; store {store}")
        wall, out, err = timed(["condense", args.file], env)
        print(f"condense (builds and keeps the condensed crank): {wall:.1f} s")
        answers = {}
        for cmd in (["campbell"], ["response"], ["damper", "--optimise"]):
            times = []
            for _ in range(args.repeat):
                path = Path(store) / "out.json"
                wall, out, err = timed([*cmd, args.file, "--json", str(path)], env)
                if "building the condensed crank" in err:
                    raise SystemExit(f"{cmd[0]} built the crank again: the store was not used")
                times.append(wall)
            data = json.loads(path.read_text())
            answers[cmd[0]] = (data, out)
            print(f"{' '.join(cmd):<18} {', '.join(f'{t:.2f}' for t in times)} s")
        size = sum(p.stat().st_size for p in (Path(store) / "condensed").glob("*.npz"))
        print(f"store: {size / 2**20:.2f} MiB of condensed cranks")
        camp = answers["campbell"][0]
        first = [c for c in camp["crossings"] if c["mode_kind"].startswith("torsional")]
        six = next(c for c in first if c["order"] == 6.0 and c["mode"] == first[0]["mode"])
        print(f"campbell: f1 in bearings {first[0]['frequency_hz']:.1f} Hz, order 6 at {six['rpm']:.0f} rpm")
        worst = next(x for x in answers["response"][1].splitlines() if "largest section torque " in x).strip()
        print(f"response: {worst}")
        print(f"damper:   mode {answers['damper'][0]['mode_hz']:.1f} Hz; "
              + next(x for x in answers["damper"][1].splitlines() if "without a damper" in x).strip())
    return 0


if __name__ == "__main__":
    sys.exit(main())
