#!/usr/bin/env bash
# car as a Python-only package (docs/INSTALL.md "Python only"), the way a user without ROS gets it: pip builds a
# wheel of car/ (pyproject.toml: no catkin, no ROS), a second fresh venv installs that wheel, and there
#   - tools/pip_smoke.py: import car without rospy, car.World, gymnasium.make, the console scripts;
#   - the Python API tests that need no ROS master (car/test/python/pip_tests.txt) run against the installed
#     package, from outside the source tree's python/ folder.
# Before that, the pip build's CMake is configured with two libraries hidden, and must stop with one message that
# names their Debian packages. CI runs this after tools/test.sh. Venvs and build in a temporary folder (kept with
# --keep). Ends with "pip: ok" or "pip: FAILED (...)".
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
KEEP=0
[ "${1:-}" = "--keep" ] && KEEP=1
WORK="$(mktemp -d /tmp/car-pip.XXXXXX)"
cleanup() { [ "$KEEP" = 1 ] && echo "pip: kept $WORK" || rm -rf "$WORK"; }
trap cleanup EXIT
fail() { echo "pip: FAILED ($1)"; exit 1; }
PY=/usr/bin/python3   # Debian's Python, the one the wheel is for
export CMAKE_BUILD_PARALLEL_LEVEL="${JOBS:-2}"
t0=$SECONDS

# 1. missing system libraries: one message naming the Debian packages, no trace of the find modules
if cmake -S "$ROOT/car/cmake/pip" -B "$WORK/missing" -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON \
     -DCMAKE_DISABLE_FIND_PACKAGE_assimp=ON > "$WORK/missing.log" 2>&1; then
  fail "the pip build configured with Embree and assimp hidden"
fi
grep -q 'sudo apt-get install libembree-dev libassimp-dev$' "$WORK/missing.log" ||
  { cat "$WORK/missing.log"; fail "no apt-get line naming libembree-dev and libassimp-dev"; }
[ "$(grep -c 'CMake Error' "$WORK/missing.log")" = 1 ] || { cat "$WORK/missing.log"; fail "more than one CMake error"; }
echo "pip: missing libraries named: $(grep 'apt-get install' "$WORK/missing.log" | sed 's/^ *//')"

# 2. the wheel, built in one venv
"$PY" -m venv "$WORK/build"
"$WORK/build/bin/pip" wheel --quiet --no-deps "$ROOT/car" -w "$WORK/dist" > "$WORK/wheel.log" 2>&1 ||
  { tail -n 60 "$WORK/wheel.log"; fail "pip wheel"; }
WHEEL="$(ls "$WORK"/dist/car-*.whl)"
echo "pip: built $(basename "$WHEEL") ($(du -h "$WHEEL" | cut -f1)) in $((SECONDS - t0)) s"

# 3. a second, fresh venv (no system site packages: no rospy) with the wheel and pytest
"$PY" -m venv "$WORK/v"
"$WORK/v/bin/pip" install --quiet "$WHEEL[test,web]" > "$WORK/install.log" 2>&1 ||
  { tail -n 40 "$WORK/install.log"; fail "pip install of the wheel"; }
if "$WORK/v/bin/python" -c 'import rospy' 2> /dev/null; then fail "the fresh venv sees rospy"; fi
(cd "$WORK" && "$WORK/v/bin/python" "$ROOT/tools/pip_smoke.py") || fail "smoke test"

# 4. the Python API tests against the installed package (-P: the working folder is not put on sys.path)
mapfile -t tests < <(sed -e 's/#.*//' -e '/^ *$/d' "$ROOT/car/test/python/pip_tests.txt")
(cd "$WORK" && "$WORK/v/bin/python" -P -m pytest -q -p no:cacheprovider "${tests[@]/#/$ROOT/car/test/python/}") ||
  fail "pytest against the wheel"
echo "pip: ok ($((SECONDS - t0)) s)"
