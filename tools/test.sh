#!/usr/bin/env bash
# The README's test command: every test tier a newcomer waits for, through catkin: gtest (core), pytest (tools),
# rostest (launch files); then each suite's floor (tools/test_floors.txt, tier `test`: a gtest binary, a pytest
# file or a rostest that vanished fails by its name). The slower tiers, a fresh catkin workspace and the rostests
# against the install space (tools/test_workspace.sh), run in CI after this one (.ci/run: tools/test_slow.sh),
# counted and floored the same way.
# The verdict comes from catkin_test_results, since `catkin_make run_tests` exits 0 on failures.
set -euo pipefail
# shellcheck source=tools/test_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/test_lib.sh"
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$ROOT/.ws"
rm -rf build/test_results
catkin_make run_tests -j2 > test.log 2>&1 || { tail -n 80 test.log; uncounted "build of the tests failed"; }
grep -E '^\[ *(RUN|  FAILED|  PASSED) *\]|passed|failed|FAILURE|ERROR' test.log | grep -v '^\[ RUN' | tail -n 40 || true
verdict build/test_results test
