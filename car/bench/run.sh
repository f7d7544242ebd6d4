#!/usr/bin/env bash
# Runs car's benchmarks beside their peer (PyBullet and MuJoCo from PyPI, installed into .venv on first use).
# usage: bench/run.sh [--repeat N] [--many-repeat M] [--no-sensors] [--json FILE]   (bench_physics.py --help)
# Each figure is the best of N interleaved rounds (default 5), its median beside it; about 5 min on a quiet
# machine (estimated; the run prints its own time).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../tools/env.sh"
"$ROOT/.venv/bin/python" -c "import pybullet, mujoco" 2>/dev/null || \
  "$ROOT/.venv/bin/pip" install -q --disable-pip-version-check -r "$ROOT/car/bench/requirements.txt"
"$ROOT/.venv/bin/python" "$ROOT/car/bench/bench_physics.py" "$@" 2>&1 | grep -v "^pybullet build time\|b3Warning\|No inertial data\|^base_footprint"
# start-up: time to the first step of box_house, cold and in a warm worker (bench_startup.py), into the --json file
json=""; prev=""
for arg in "$@"; do
  [ "$prev" = --json ] && json=$arg
  case $arg in --json=*) json=${arg#--json=} ;; -h|--help) exit 0 ;; esac
  prev=$arg
done
"$ROOT/.venv/bin/python" "$ROOT/car/bench/bench_startup.py" ${json:+--merge-json "$json"}
