#!/usr/bin/env bash
# Regenerates everything under results/ (run from anywhere, after scripts/setup.sh):
#   results/renault21, results/peugeot_glx, results/peugeot_glx_engine  the full reports (fetorsion run --all, ~4 min)
#   results/mechanics                       balancing, flywheel, planetary figures (seconds)
#   results/chart                           the web stiffness methods against 3D FE (~3 min)
#   results/validation.*                    FE f1 and its [uncertainty] band against the measurements (~4 min)
#   results/studies                         FE Monte Carlo of f1 against the lumped band, with --studies
#                                           (scripts/fe_band.py: 2 x 24 coarse FE runs on the local
#                                           Dask cluster, ~3 min on 2 cores)
# With --chart it first recomputes the FE web chart itself (109 FE runs on the local Dask cluster,
# ~11 min serial before), resuming from results/chart/points.json (delete it, or run
# scripts/web_chart.py --fresh, to recompute) and the sample store (~/.cache/fetorsion/samples).
set -euo pipefail
cd "$(dirname "$0")/.."
py=.venv/bin/python
for arg in "$@"; do
  case "$arg" in
    --chart) nice -n 10 $py scripts/web_chart.py ;;
    --studies) nice -n 5 $py scripts/fe_band.py ;;
    *) echo "results.sh: unknown option $arg (use --chart, --studies)" >&2; exit 2 ;;
  esac
done
nice -n 10 $py scripts/stiffness_methods.py --modal 0.010
$py scripts/mechanics_results.py
nice -n 10 $py scripts/validation.py
.venv/bin/fetorsion run --all
