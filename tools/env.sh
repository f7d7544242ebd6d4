# Sourced by tools/run.sh, tools/test.sh and bench/run.sh: set up (idempotent), then enter the workspace's
# environment (ROS paths, and the venv first on PATH through the package's env hook).
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/tools/setup.sh"
set +u
# shellcheck disable=SC1091
source "$ROOT/.ws/devel/setup.bash"
set -u
