#!/usr/bin/env bash
# Runs every test tier through catkin: gtest (core), pytest (tools), rostest (launch files); then
# tools/test_workspace.sh (a fresh catkin workspace and the install space, docs/INSTALL.md).
# The verdict comes from catkin_test_results, since `catkin_make run_tests` exits 0 on failures.
set -euo pipefail
# The closing line is always "N passed, N failed, N skipped". Where nothing could be counted (the set-up, the
# build or catkin_test_results failed), the one failure counted is that.
closed=0
uncounted() {
  echo "test: $1"
  echo "0 passed, 1 failed, 0 skipped"
  closed=1
  exit 1
}
trap '[ "$closed" = 1 ] || { echo "test: stopped before the tests could be counted"; echo "0 passed, 1 failed, 0 skipped"; }' EXIT
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$ROOT/.ws"
rm -rf build/test_results
catkin_make run_tests -j2 > test.log 2>&1 || { tail -n 80 test.log; uncounted "build of the tests failed"; }
grep -E '^\[ *(RUN|  FAILED|  PASSED) *\]|passed|failed|FAILURE|ERROR' test.log | grep -v '^\[ RUN' | tail -n 40 || true
# car the ROS way: a fresh workspace (catkin_make, catkin_make_isolated, ROS's tools without a prompt) and the
# install space alone (the rostests against it, the source tree hidden); its checks join the counts below
bash "$ROOT/tools/test_workspace.sh" --junit build/test_results/car/workspace.xml > workspace.log 2>&1 || true
grep '^test_workspace: ' workspace.log | grep -v '^test_workspace: ok ' | tail -n 20 || true
[ -s build/test_results/car/workspace.xml ] || printf '<?xml version="1.0"?>\n<testsuite name="workspace" tests="1" failures="1" errors="0" skipped="0"><testcase classname="car.workspace" name="test_workspace_ran"><failure message="tools/test_workspace.sh wrote no results (see .ws/workspace.log)"/></testcase></testsuite>\n' > build/test_results/car/workspace.xml
set +e
summary="$(catkin_test_results build/test_results 2>&1)"
rc=$?
set -e
echo "$summary" | tail -n 30
# One closing line: N passed, N failed, N skipped.
counts="$(echo "$summary" | sed -n 's/^Summary: \([0-9]*\) tests, \([0-9]*\) errors, \([0-9]*\) failures, \([0-9]*\) skipped.*/\1 \2 \3 \4/p' | tail -n 1)"
[ -n "$counts" ] || uncounted "catkin_test_results printed no Summary line (exit $rc): nothing could be counted"
read -r total errors failures skipped <<< "$counts"
failed=$((errors + failures))
closed=1
echo "$((total - failed - skipped)) passed, $failed failed, $skipped skipped"
if [ "$rc" -ne 0 ] || [ "$failed" -ne 0 ] || [ "$total" -eq 0 ]; then
  # which tests failed, and the tail of each one's message (the summary above only counts them)
  /usr/bin/python3 "$ROOT/tools/test_failures.py" build/test_results || true
  echo "$((total - failed - skipped)) passed, $failed failed, $skipped skipped"
  exit 1
fi
