#!/usr/bin/env bash
# Regenerates everything under results/ (run from anywhere, after scripts/setup.sh):
#   results/renault21, results/peugeot_glx  the full reports (fetorsion run --all, ~2 min)
#   results/mechanics                       balancing, flywheel, planetary figures (seconds)
#   results/chart                           the web stiffness methods against 3D FE (~3 min)
# With --chart it first recomputes the FE web chart itself (53 FE points, ~11 min on 2 cores),
# which resumes from results/chart/points.json unless that file is removed.
set -euo pipefail
cd "$(dirname "$0")/.."
py=.venv/bin/python
if [ "${1:-}" = "--chart" ]; then
  nice -n 10 $py scripts/web_chart.py
fi
nice -n 10 $py scripts/stiffness_methods.py --modal 0.010
$py scripts/mechanics_results.py
.venv/bin/fetorsion run --all
