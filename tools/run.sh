#!/usr/bin/env bash
# Sets up (idempotent), then expands and checks the bundled car. Extra arguments go to check_model.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/tools/setup.sh"
set +u
# shellcheck disable=SC1091
source "$ROOT/.ws/devel/setup.bash"
set -u
exec "$ROOT/.ws/devel/lib/car/check_model" "$ROOT/urdf/car_camera_lidar04.xacro" "$@"
