#!/usr/bin/env bash
# Sets up (idempotent), then runs the simulator: the seed car in box_house (roslaunch car sim.launch).
# Arguments go to roslaunch, e.g. rviz:=true rtf:=0 paused:=true.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
exec roslaunch car sim.launch "$@"
