#!/usr/bin/env bash
# The default test run, RUNS times in a row, each under a busy load of LOAD processes (one
# spinning Python loop each), to show that no test depends on timing or a quiet machine.
# Prints one line per run (outcome, duration, load average) and exits non-zero if any failed.
#   bash scripts/soak-tests.sh [RUNS=10] [LOAD=2] [extra pytest arguments...]
set -uo pipefail
cd "$(dirname "$0")/.."
runs=${1:-10}; load=${2:-2}; shift $(( $# > 2 ? 2 : $# ))
pids=()
stop() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done; }
trap stop EXIT
for _ in $(seq "$load"); do python3 -c "while True: pass" & pids+=($!); done
failed=0
for i in $(seq "$runs"); do
  t0=$(date +%s)
  log=$(mktemp)
  .venv/bin/python -m pytest -q -p no:cacheprovider "$@" >"$log" 2>&1; rc=$?
  echo "run $i/$runs: exit $rc in $(( $(date +%s) - t0 )) s, load $(cut -d' ' -f1-3 /proc/loadavg): $(tail -1 "$log")"
  if [ $rc -ne 0 ]; then failed=$((failed + 1)); grep -E "^(FAILED|ERROR)" "$log"; cp "$log" "soak-failure-$i.log"; fi
  rm -f "$log"
done
echo "soak: $failed of $runs runs failed under $load busy processes"
[ $failed -eq 0 ]
