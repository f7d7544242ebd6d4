#!/usr/bin/env bash
# The slow tiers, moved out of the README's command (tools/test.sh) into CI, which runs this after it (.ci/run):
# the tests too slow for a newcomer's wait (web_view: a headless browser; the adversarial corpus through the tools
# and spawn_model, a process per case), and car the ROS way: a fresh catkin workspace (catkin_make,
# catkin_make_isolated, ROS's tools without a prompt) and the install space alone (the suite's rostests against
# it, the source tree hidden): tools/test_workspace.sh.
# Its checks are JUnit test cases in .ws/build/test_results_slow/, counted and floored (tools/test_floors.txt, tier
# `slow`) as tools/test.sh counts its own; it ends with the same closing line, `N passed, N failed, N skipped`, and
# exits 1 on any failure.
set -euo pipefail
# shellcheck source=tools/test_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/test_lib.sh"
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$ROOT/.ws"
results=build/test_results_slow
rm -rf "$results"
mkdir -p "$results/car"
# the rostests too slow for the README's command (car/CMakeLists.txt leaves them out of run_tests), in the devel
# space as catkin's run_tests runs a rostest; a result file missing is a floor's failure
for t in web_view bad_spawn; do
  rostest --pkgdir="$ROOT/.ws/src/car" --package=car --results-filename "test_ros_$t.xml" \
    --results-base-dir "$PWD/$results" "$ROOT/.ws/src/car/test/ros/$t.test" < /dev/null > "rostest-$t.log" 2>&1 ||
    echo "test_slow: rostest $t.test failed (.ws/rostest-$t.log)"
done
# the pytest files too slow for it: the adversarial corpus through check_model, world_tool and the Python API, a
# process per case (car/CMakeLists.txt leaves it out of run_tests' pytest), as catkin runs pytest
(cd "$ROOT/.ws/src/car" && CAR_DEVEL_PREFIX="$ROOT/.ws/devel" /usr/bin/python3 -m pytest -q -p no:cacheprovider \
  --junitxml="$ROOT/.ws/$results/car/pytest-slow.xml" test/python/test_bad_corpus.py) < /dev/null > pytest-slow.log 2>&1 ||
  echo "test_slow: pytest test_bad_corpus.py failed (.ws/pytest-slow.log)"
bash "$ROOT/tools/test_workspace.sh" --junit "$results/car/workspace.xml" > workspace.log 2>&1 || true
grep '^test_workspace: ' workspace.log | grep -v '^test_workspace: ok ' | tail -n 20 || true
[ -s "$results/car/workspace.xml" ] || printf '<?xml version="1.0"?>\n<testsuite name="workspace" tests="1" failures="1" errors="0" skipped="0"><testcase classname="car.workspace" name="test_workspace_ran"><failure message="tools/test_workspace.sh wrote no results (see .ws/workspace.log)"/></testcase></testsuite>\n' > "$results/car/workspace.xml"
verdict "$results" slow
