#!/bin/bash
# The wall-follower example's tests (car.testing + car batch) N times in a row beside two busy loops (the load of
# tools/stress_test.sh): failures, and the real-time factor (sim s / wall s) per run. Needs the workspace sourced.
#   bash bench/testing_stress.sh [N=20] [OUTDIR=bench/out/testing_stress]
set -u
N=${1:-20}
OUT=${2:-bench/out/testing_stress}
HERE=$(cd "$(dirname "$0")/.." && pwd)
PY=${PYTHON:-$HERE/../.venv/bin/python}
mkdir -p "$OUT"
pids=()
for i in 1 2; do (while :; do :; done) & pids+=($!); done
trap 'kill "${pids[@]}" 2>/dev/null' EXIT
for i in $(seq 1 "$N"); do
  start=$(date +%s.%N)
  CAR_SIMTIME_OUT="$OUT/run$i.json" PYTHONPATH="$HERE/bench:${PYTHONPATH:-}" "$PY" -m pytest -q -p no:cacheprovider \
    -p car.testing -p testing_simtime "$HERE/examples/wall_follower" > "$OUT/run$i.log" 2>&1
  rc=$?
  end=$(date +%s.%N)
  echo "$i rc=$rc wall=$(echo "$end - $start" | bc) $(tail -1 "$OUT/run$i.log")"
done
"$PY" - "$OUT" "$N" <<'PYEOF'
import json, statistics, sys
out, n = sys.argv[1], int(sys.argv[2])
runs = [json.load(open('%s/run%d.json' % (out, i))) for i in range(1, n + 1)]
failed = sum(sum(f['failed'] for f in r.values()) for r in runs)
def rtf(r, key=None):
    fs = [v for k, v in r.items() if key is None or key in k]
    return sum(f['sim_s'] for f in fs) / sum(f['wall_s'] for f in fs)
print('runs %d, failed test reports %d' % (n, failed))
for key, name in ((None, 'suite'), ('test_wall_follower', 'node tests (ROS, lockstep)'), ('test_sweep', 'car batch sweep')):
    v = [rtf(r, key) for r in runs]
    print('%-26s rtf median %.2f  min %.2f  max %.2f  (sim s per run %.1f)' % (
        name, statistics.median(v), min(v), max(v),
        statistics.median(sum(f['sim_s'] for k, f in r.items() if key is None or key in k) for r in runs)))
PYEOF
