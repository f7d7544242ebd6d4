#!/usr/bin/env bash
# Runs the README's suite (tools/test.sh; CI's slower tiers, tools/test_slow.sh, are left out) N times in a row
# (default 3) while BUSY processes (default 2, at nice 0) keep the CPU loaded, and reports each run's verdict. A
# suite whose tests wait on sim-time conditions, never for a while, passes every time however slow the machine is;
# a test that depends on the machine's speed shows up as a run that fails here and passes when the machine is quiet.
#
# Usage: bash tools/stress_test.sh [N]     Environment: BUSY=2
# Exit status: 0 when every run passed. Logs: .ws/stress/run-I.log
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
N="${1:-3}"
BUSY="${BUSY:-2}"
cd "$ROOT"
bash tools/setup.sh || exit 1
LOGS="$ROOT/.ws/stress"
mkdir -p "$LOGS"

busy=()
stop_busy() {
  for pid in "${busy[@]}"; do kill "$pid" 2>/dev/null; done
  busy=()
}
# stopped by a signal: stop the busy loops and the run in progress, then exit (a trap alone would go on)
trap stop_busy EXIT
trap 'stop_busy; [ -n "${suite:-}" ] && kill -TERM -- "-$suite" 2>/dev/null; pkill -P $$; exit 143' INT TERM
for _ in $(seq "$BUSY"); do
  # a busy loop at nice 0: it competes with the simulator and the tests for every time slice
  nice -n 0 bash -c 'while :; do :; done' &
  busy+=($!)
done
echo "stress: $BUSY busy processes (pids ${busy[*]}); load: $(cut -d' ' -f1-3 /proc/loadavg)"

failed=0
verdicts=()
for i in $(seq "$N"); do
  t0=$SECONDS
  # in the background and waited for: bash runs a trap only between commands, and `wait` is one it interrupts
  # (a foreground suite would keep a TERM waiting until the suite ended)
  # its own process group (set -m), so a signal stops the whole suite: catkin, rostest, the nodes
  set -m
  bash tools/test.sh > "$LOGS/run-$i.log" 2>&1 &
  suite=$!
  set +m
  wait "$suite"
  rc=$?
  verdict="$(grep -E '^[0-9]+ passed, [0-9]+ failed, [0-9]+ skipped' "$LOGS/run-$i.log" | tail -n 1)"
  line="run $i/$N: ${verdict:-no verdict} (exit $rc, $((SECONDS - t0)) s, load $(cut -d' ' -f1-3 /proc/loadavg))"
  echo "stress: $line"
  verdicts+=("$line")
  if [ "$rc" -ne 0 ]; then
    failed=$((failed + 1))
    # the failing tests, by name
    grep -E 'FAILURE|ERROR|\[  FAILED  \]' "$LOGS/run-$i.log" | grep -v '^\s*$' | head -n 20
  fi
done
stop_busy
echo "stress: $((N - failed)) of $N runs green under $BUSY busy processes"
printf '  %s\n' "${verdicts[@]}"
[ "$failed" -eq 0 ]
