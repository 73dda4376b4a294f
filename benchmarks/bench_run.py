"""The main job against one modal analysis of the same crank, timed back to back (issue 26).

    nice python benchmarks/bench_run.py [geometry/renault21.toml] [--six] [--again]

Runs ``fetorsion modal FILE`` and then ``fetorsion run FILE`` (a fresh, empty sample store and
report folder in a temporary directory, so nothing is reused from earlier runs) and prints
both walls, their ratio and the run's steps. ``--six`` times a six-cylinder crank with no
shipped data instead: the description's journals, pins and webs repeated to seven, six and
twelve, crank angles 0-120-240-240-120-0, firing order 1-5-3-6-2-4, and the journal and pin
diameters moved inside their [uncertainty] ranges (56 and 50 mm) so that no stored throw
stiffness or fillet SCF matches it; its measured frequencies are dropped (it is not that crank).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def cpu_name() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def six_cylinder(text: str) -> str:
    """The description's text turned into the six-cylinder variant (see the module docstring)."""
    def blocks(kind):
        return re.findall(rf"\[\[{kind}\]\]\n(?:[^\[\n][^\n]*\n|\n)*?(?=\n*\[)", text)

    text = re.sub(r"(?m)^(measured_first_torsional_hz|paper_fe_first_torsional_hz|paper_lumped_first_torsional_hz)\b.*\n",
                  "", text)
    text = re.sub(r'(?m)^name = "(.*)"', r'name = "six-cylinder variant of \1 (benchmark)"', text, count=1)
    text = re.sub(r"(?m)^cylinders = 4\b", "cylinders = 6", text)
    text = re.sub(r"(?m)^crank_angles_deg = .*$", "crank_angles_deg = [0.0, 120.0, 240.0, 240.0, 120.0, 0.0]", text)
    text = re.sub(r"(?m)^firing_order = .*$", "firing_order = [1, 5, 3, 6, 2, 4]", text)
    for kind, extra in (("journals", 2), ("pins", 2), ("webs", 4)):
        found = blocks(kind)
        if not found:
            raise SystemExit(f"no [[{kind}]] blocks found")
        last = found[-1]
        text = text.replace(last, last + "".join([found[0]] * extra), 1)
    text = re.sub(r"(?m)^diameter = 54\.8$", "diameter = 56.0", text)
    text = re.sub(r"(?m)^diameter = 48\.0$", "diameter = 50.0", text)
    return text


def timed(cmd: list[str], env: dict) -> float:
    t = time.perf_counter()
    out = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t
    if out.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{out.stderr[-3000:]}")
    return wall


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("file", nargs="?", default=str(ROOT / "geometry" / "renault21.toml"))
    p.add_argument("--six", action="store_true", help="the six-cylinder variant without shipped data")
    p.add_argument("--again", action="store_true",
                   help="run a second time on the same store (issue 55: the second run against the first)")
    a = p.parse_args()
    exe = [sys.executable, "-c", "import sys; from fetorsion.cli import console; sys.exit(console())"]
    load_before = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        src = Path(a.file).resolve()
        crank = src
        if a.six:  # in the temporary folder (nothing left beside the user's file), its CSV paths made absolute
            crank = tmp / "six.toml"
            text = re.sub(r'(?m)^(pressure_csv\s*=\s*)"([^"]+)"',
                          lambda m: f'{m.group(1)}"{(src.parent / m.group(2)).resolve()}"', src.read_text())
            crank.write_text(six_cylinder(text))
        env = {**os.environ, "FETORSION_STORE": str(tmp / "store"), "PYTHONPATH": str(ROOT)}
        modal = timed(exe + ["modal", str(crank)], env)
        run = timed(exe + ["run", str(crank), "--out", str(tmp / "report"), "--no-html"], env)
        results = json.loads((tmp / "report" / "results.json").read_text())
        if a.again:
            again = timed(exe + ["run", str(crank), "--out", str(tmp / "again"), "--no-html"], env)
            second = json.loads((tmp / "again" / "results.json").read_text())
    fe = results.get("fe", {})
    print(f"{results.get('fe', {}).get('mesh', {}).get('dofs', '?')} DOF; {cpu_name()}, {os.cpu_count()} cores; "
          f"load average before {load_before:.2f}")
    print(f"| crank | fetorsion modal [s] | fetorsion run [s] | run / modal |\n|---|---|---|---|\n"
          f"| {'six-cylinder variant' if a.six else src.stem} | {modal:.1f} | {run:.1f} | {run / modal:.2f} |")
    print("run, by step [s]: " + ", ".join(f"{k} {v:.1f}" for k, v in results["timings_s"].items()))
    if fe:
        print("FE step: " + ", ".join(f"{k} {v:.1f}" for k, v in fe.get("timings_s", {}).items()))
    if a.again:
        print(f"second run, same store: {again:.1f} s ({again / run:.2f} of the first)")
        print("second run, by step [s]: " + ", ".join(f"{k} {v:.1f}" for k, v in second["timings_s"].items()))
    cond = results.get("bearings", {}).get("timings_s")
    if cond:
        print("condensed crank: " + ", ".join(f"{k} {v:.1f}" for k, v in cond.items()))


if __name__ == "__main__":
    main()
