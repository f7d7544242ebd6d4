#!/usr/bin/env bash
# Faults survived (a benchmark with figures, not a test): bench/faults.py on car's workspace.
# Usage: bash bench/faults.sh spawn-delete [--cycles 10000] | services [--calls 1000] [--threads 50]
#        | cmd-vel [--rate 10000] [--seconds 60]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../../tools/env.sh"
exec "$ROOT/.venv/bin/python" "$ROOT/car/bench/faults.py" "$@"
