# Sourced by tools/test.sh and tools/test_slow.sh: the closing line and the verdict they share.
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

# verdict RESULTS TIER: counts the JUnit files under RESULTS (catkin_test_results, since `catkin_make run_tests`
# exits 0 on failures), checks the tier's floors (tools/test_floors.txt: each suite missing or below its floor
# counts as one failure; CAR_TEST_FLOORS=FILE reads another, for the floors' own test), prints the closing line
# and exits 1 on any failure or an empty count.
verdict() {
  local results="$1" tier="$2" summary rc counts total errors failures skipped failed floors short
  set +e
  summary="$(catkin_test_results "$results" 2>&1)"
  rc=$?
  floors="$(/usr/bin/python3 "$ROOT/tools/check_floors.py" --floors "${CAR_TEST_FLOORS:-$ROOT/tools/test_floors.txt}" \
    --tier "$tier" "$results" 2>&1)"
  set -e
  echo "$summary" | tail -n 30
  echo "$floors" | tail -n 40
  counts="$(echo "$summary" | sed -n 's/^Summary: \([0-9]*\) tests, \([0-9]*\) errors, \([0-9]*\) failures, \([0-9]*\) skipped.*/\1 \2 \3 \4/p' | tail -n 1)"
  [ -n "$counts" ] || uncounted "catkin_test_results printed no Summary line (exit $rc): nothing could be counted"
  read -r total errors failures skipped <<< "$counts"
  # a floor's report is one line per suite missing or short; none printed (the check itself failed) counts one
  short="$(echo "$floors" | grep -cE '^floors: (missing|short): ' || true)"
  echo "$floors" | grep -qE '^floors: [0-9]+ suites at or above their floor$' || [ "$short" -gt 0 ] || short=1
  failed=$((errors + failures + short))
  closed=1
  echo "$((total - errors - failures - skipped)) passed, $failed failed, $skipped skipped"
  if [ "$rc" -ne 0 ] || [ "$failed" -ne 0 ] || [ "$total" -eq 0 ]; then
    # which tests failed, and the tail of each one's message (the summary above only counts them)
    /usr/bin/python3 "$ROOT/tools/test_failures.py" "$results" || true
    echo "$floors" | grep -E '^floors: (missing|short): ' || true
    echo "$((total - errors - failures - skipped)) passed, $failed failed, $skipped skipped"
    exit 1
  fi
}
