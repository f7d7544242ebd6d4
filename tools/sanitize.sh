#!/usr/bin/env bash
# Sanitizer runs (issue 28, docs/RELIABILITY.md). Builds car's own targets instrumented in their own catkin
# workspaces beside .ws/ (never touching it), runs the tests, and fails on any sanitizer report:
#   asan   .ws-asan/, clang with -DCAR_SANITIZE=address,undefined (and -DCAR_FUZZ=ON: the same build serves
#          tools/fuzz.sh): every gtest (test_core) and the Python API tests that load car._core (Debian's python3 is
#          not instrumented: the runtime is preloaded, see below)
#   tsan   .ws-tsan/, clang with -DCAR_SANITIZE=thread: test_threads (the publishing thread, the pacer, the pool behind
#          parallel_for, built without car_sim) and test_core's threaded gtests (the island solver on 1-3 threads,
#          the bounding boxes and a fleet's lidars on the threads, the cameras' banded rendering), which needs car_sim
#          built with TSan
#   tsan-quick  test_threads only
#   tsan-ros    sim_node built with TSan under two rostests (after tsan): node_rates (the publishing thread, the
#          pacer, /clock) and sensors (the tutorial car in box_house: the island pool, the lidar's and the Kinect's
#          banded rendering through parallel_for, the publishing thread under load). roscpp and Boost are not
#          instrumented; TSan still sees their pthread locks, and tools/sanitizers/tsan.supp names what remains.
# Usage: tools/sanitize.sh [asan|asan-gtest|asan-pytest] [tsan|tsan-quick]   (asan and tsan when none given).
# JOBS=N for the builds (default 2).
# Each process writes its reports to $OUT/<stage>/ (log_path): any file there fails the stage. Suppressions, for
# third-party code only, are in tools/sanitizers/*.supp, each with its reason.
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT/car"
# shellcheck source=tools/sanitizers/workspace.sh
source "$ROOT/tools/sanitizers/workspace.sh"
ensure_clang || { echo "sanitizers: could not install clang 14"; exit 1; }
JOBS="${JOBS:-2}"
OUT="$ROOT/.ws-san-reports"
SUPP="$ROOT/tools/sanitizers"
stages=("$@")
[ ${#stages[@]} -gt 0 ] || stages=(asan tsan)

# The Python API tests that load car._core and need no package beyond Debian's (the venv's ray, viser and
# gymnasium are not needed by these).
PY_TESTS=(test_world_api test_inertia test_model_check test_spawn_sdf test_check_sdf test_bad_corpus test_fixtures
  test_world_tools test_spawn_args test_static_tf test_world_map test_xacro_tool test_xacro14 test_arbotix)
# test_core's gtests that run car_sim's threads: island_world.cpp's islands on 1-3 threads, raycast's banded
# camera and fan rendering through parallel_for (test_threads holds the rest).
TSAN_FILTER='SelfCollide.TheThreadedDispatcherKeepsTheRule:WorldPhysics.IslandsOnTwoThreadsMatchOneBitForBit:WorldPhysics.ManyCarsOnAnyThreadCountMatchBitForBit:WorldPhysics.FleetLidarsOnTwoThreadsMatchOneBitForBit:RestReuse.ManyCarsBoxesOnTheThreadsAreBulletsBitForBit:RayKernels.*:Camera.*:DepthCamera.*:MultiCamera.*'

declare -A took result
failed=0
now() { date +%s; }

build() {  # build WS SANITIZERS CXX EXTRA_CMAKE_ARG TARGETS...
  local ws="$1" san="$2" cxx="$3" extra="$4" cc=gcc; shift 4
  [ "$cxx" = g++ ] || cc="${cxx/++/}"
  make_workspace "$ws"
  set +u; source /opt/ros/noetic/setup.bash 2>/dev/null; set -u
  if [ ! -f "$ws/build/Makefile" ]; then
    (cd "$ws" && CC="$cc" CXX="$cxx" catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
      -DCATKIN_ENABLE_TESTING=ON -DCAR_SANITIZE="$san" -DCAR_VENV="$ROOT/.venv" "$extra" -j"$JOBS" "$@" > build.log 2>&1) ||
      { tail -n 40 "$ws/build.log"; return 1; }
  else
    make -C "$ws/build" -j"$JOBS" "$@" > "$ws/build.log" 2>&1 || { tail -n 40 "$ws/build.log"; return 1; }
  fi
}

reports() {  # reports DIR: 0 when the folder holds no report
  if compgen -G "$1/*" > /dev/null; then
    echo "sanitize: reports in $1:"
    for f in "$1"/*; do echo "---- $f"; head -n 60 "$f"; done
    return 1
  fi
}

stage() {  # stage NAME COMMAND...: times it and records pass/fail
  local name="$1" t0 rc; shift
  echo "sanitize: $name ..."
  t0=$(now)
  "$@"; rc=$?
  took[$name]=$(( $(now) - t0 ))
  if [ $rc -eq 0 ]; then result[$name]=ok; else result[$name]="FAILED ($rc)"; failed=1; fi
  echo "sanitize: $name: ${result[$name]} in ${took[$name]} s"
  return $rc
}

asan_gtest() {
  local d="$OUT/asan-gtest"; rm -rf "$d"; mkdir -p "$d"
  LLVM_PROFILE_FILE=/dev/null ASAN_OPTIONS="log_path=$d/asan:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1" \
  LSAN_OPTIONS="suppressions=$SUPP/lsan.supp:print_suppressions=0" \
  UBSAN_OPTIONS="log_path=$d/ubsan:print_stacktrace=1:halt_on_error=1:suppressions=$SUPP/ubsan.supp" \
    "$ROOT/.ws-asan/devel/lib/car/test_core" --gtest_brief=1 > "$d.log" 2>&1
  local rc=$?
  tail -n 5 "$d.log"
  reports "$d" || rc=1
  return $rc
}

asan_pytest() {
  local d="$OUT/asan-pytest" files=() t PY=/usr/bin/python3; rm -rf "$d"; mkdir -p "$d"
  # the project's venv (tools/setup.sh) where there is one: PyPI's xacro for the xacro cases
  [ -x "$ROOT/.venv/bin/python3" ] && PY="$ROOT/.venv/bin/python3"
  for t in "${PY_TESTS[@]}"; do files+=("test/python/$t.py"); done
  # Debian's python3 is not built with ASan, so the runtime (clang's shared one, which holds UBSan's too) must come
  # first: LD_PRELOAD. detect_leaks=0 because
  # CPython does not free its interned objects and module state at exit (every run would report them; leaks in
  # car's own code are checked by the gtests above). PYTHONMALLOC=malloc: objects go through ASan's malloc, not
  # pymalloc's arenas, so an overflow into a Python object is seen.
  ( set +u; source "$ROOT/.ws-asan/devel/setup.bash"; set -u
    LD_PRELOAD="$(clang++-14 -print-file-name=libclang_rt.asan-x86_64.so)" PYTHONMALLOC=malloc LLVM_PROFILE_FILE=/dev/null \
    LLVM_PROFILE_FILE=/dev/null ASAN_OPTIONS="log_path=$d/asan:detect_leaks=0:hard_rss_limit_mb=2048" \
    UBSAN_OPTIONS="log_path=$d/ubsan:print_stacktrace=1:halt_on_error=1:suppressions=$SUPP/ubsan.supp" \
      "$PY" -m pytest -q -p no:cacheprovider "${files[@]}" > "$d.log" 2>&1 )
  local rc=$?
  tail -n 5 "$d.log"
  reports "$d" || rc=1
  return $rc
}

tsan_run() {  # tsan_run NAME BINARY [ARGS...]
  local d="$OUT/$1" bin="$2"; shift 2; rm -rf "$d"; mkdir -p "$d"
  OMP_NUM_THREADS=2 TSAN_OPTIONS="log_path=$d/tsan:halt_on_error=0:second_deadlock_stack=1:suppressions=$SUPP/tsan.supp" \
    "$bin" --gtest_brief=1 "$@" > "$d.log" 2>&1
  local rc=$?
  tail -n 5 "$d.log"
  reports "$d" || rc=1
  return $rc
}

# rostest RUNs sim_node from .ws-tsan's devel space (rosrun finds the workspace sourced first); every process it
# starts inherits TSAN_OPTIONS, and only the instrumented sim_node writes reports.
tsan_ros() {
  local d="$OUT/tsan-ros" t rc=0; rm -rf "$d"; mkdir -p "$d"
  for t in node_rates sensors; do
    # the venv first, as .ws/'s env hook puts it (this workspace's hook looks for one beside its src/)
    # car's Python package from .ws/ (tools/setup.sh's release build, with car._core): the tools and the tests are
    # Python, only sim_node is instrumented
    ( set +u; source "$ROOT/.ws-tsan/devel/setup.bash"; set -u; export PATH="$ROOT/.venv/bin:$PATH"
      export PYTHONPATH="$ROOT/.ws/devel/lib/python3/dist-packages:$PYTHONPATH"
      # each binary finds its own libcar_sim by its RUNPATH: sim_node the TSan one, car._core the release one
      unset LD_LIBRARY_PATH
      OMP_NUM_THREADS=2 TSAN_OPTIONS="log_path=$d/tsan:halt_on_error=0:second_deadlock_stack=1:report_signal_unsafe=0:suppressions=$SUPP/tsan.supp" \
        rostest car "$t.test" > "$d-$t.log" 2>&1 ) || rc=1
    tail -n 4 "$d-$t.log"
  done
  reports "$d" || rc=1
  return $rc
}

for s in "${stages[@]}"; do
  case "$s" in
    asan)
      stage asan-build build "$ROOT/.ws-asan" address,undefined clang++-14 -DCAR_FUZZ=ON test_core _core || continue
      stage asan-gtest asan_gtest
      stage asan-pytest asan_pytest ;;
    asan-gtest|asan-pytest)  # one half, on the build that is there
      stage "$s" "${s/-/_}" ;;
    tsan|tsan-quick)
      stage tsan-build-threads build "$ROOT/.ws-tsan" thread clang++-14 -DCAR_FUZZ=OFF test_threads || continue
      stage tsan-threads tsan_run tsan-threads "$ROOT/.ws-tsan/devel/lib/car/test_threads"
      [ "$s" = tsan ] || continue
      stage tsan-build-core build "$ROOT/.ws-tsan" thread clang++-14 -DCAR_FUZZ=OFF test_core || continue
      stage tsan-core tsan_run tsan-core "$ROOT/.ws-tsan/devel/lib/car/test_core" --gtest_filter="$TSAN_FILTER" ;;
    tsan-ros)
      stage tsan-build-node build "$ROOT/.ws-tsan" thread clang++-14 -DCAR_FUZZ=OFF sim_node || continue
      stage tsan-ros tsan_ros ;;
    *) echo "sanitize: unknown stage '$s' (asan, tsan, tsan-quick, tsan-ros)"; exit 2 ;;
  esac
done

summary=""
for k in "${!took[@]}"; do summary+="$k ${result[$k]} ${took[$k]} s; "; done
if [ $failed -eq 0 ]; then
  echo "sanitize: clean: ${summary%; }"
else
  echo "sanitize: FAILED: ${summary%; }"
fi
exit $failed
