#!/usr/bin/env bash
# Soak (a benchmark, not a test): the seed car in box_house at rtf:=0 with /scan and the Kinect's cloud subscribed,
# sim_node's resident memory sampled every few sim seconds from the car's first scan and cloud; reports its growth
# per sim hour, RSS first/last/min/max after the warm-up and the node's warnings (issue 51).
# Usage: bash bench/soak.sh [--sim-seconds 3600] [--every 30] [--warmup 60] [--max-wall 0] [--rtf 0] [--no-cloud]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../tools/env.sh"
exec "$ROOT/.venv/bin/python" "$ROOT/car/bench/soak.py" "$@"
