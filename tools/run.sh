#!/usr/bin/env bash
# Sets up (idempotent), then runs the simulator: the seed car in box_house (roslaunch car sim.launch).
# Arguments go to roslaunch, e.g. rviz:=true rtf:=0 paused:=true.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/tools/setup.sh"
set +u
# shellcheck disable=SC1091
source "$ROOT/.ws/devel/setup.bash"
set -u
exec roslaunch car sim.launch "$@"
