#!/usr/bin/env python3
"""Test floors: fails when a suite of the test suite records fewer test cases than its floor in
tools/test_floors.txt, or none at all, naming each one. Run by tools/test.sh (tier `test`) and tools/test_slow.sh
(tier `slow`, from .ci/run) after catkin_test_results, which only fails when a result file says so or the total
is zero: a gtest binary, a pytest file, a rostest or the install-space tier that silently vanishes records no
failure at all.

A suite is a JUnit file under the results folder, named by its file name less `.xml` (`gtest-test_core`,
`rostest-test_ros_drive`, `rosunit-drive`, `pytest-car`, `workspace`), or one pytest file within a pytest-*.xml,
named `pytest-car/test_world_api.py` (from each test case's classname: pytest writes `test.python.test_world_api`
or `test.python.test_world_api.TestClass`). A rostest's own file holds one case, whatever its test node ran; the
node's cases are in its rosunit-*.xml (named by the .test file's test-name). A suite's count is its test cases,
skipped ones included (as catkin_test_results counts them).

Usage: check_floors.py [--floors FILE] [--tier TIER] RESULTS_DIR
       check_floors.py --print [--tier TIER] RESULTS_DIR     (the counts there, as floor lines)
Prints one line per suite below its floor:
  floors: missing: SUITE (no results; floor N)
  floors: short: SUITE has M test cases, floor N
then `floors: K of S suites below their floor` (or `floors: S suites at or above their floor`); exits 1 when
K > 0 (or the floors file has no line for the tier), 0 otherwise.
"""
import argparse
import collections
import os
import sys
import xml.etree.ElementTree as ET

FLOORS = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'test_floors.txt')


def pytest_file(classname):
    """`test.python.test_world_api.TestX` -> `test_world_api.py`: the last module component (classes start with
    a capital letter). An empty classname (pytest's collection errors) gives None."""
    parts = [p for p in (classname or '').split('.') if p]
    while parts and parts[-1][:1].isupper():
        parts.pop()
    return parts[-1] + '.py' if parts else None


def counts(root):
    """{suite: number of test cases} over every JUnit file under root, and {suite: why unreadable}."""
    found = collections.Counter()
    unreadable = {}
    for dirpath, _, files in sorted(os.walk(root)):
        for name in sorted(files):
            if not name.endswith('.xml'):
                continue
            suite = name[:-len('.xml')]
            path = os.path.join(dirpath, name)
            try:
                cases = list(ET.parse(path).getroot().iter('testcase'))
            except (ET.ParseError, OSError) as e:
                unreadable[suite] = str(e)
                continue
            found[suite] += len(cases)
            if suite.startswith('pytest-'):
                for case in cases:
                    f = pytest_file(case.get('classname'))
                    if f:
                        found['%s/%s' % (suite, f)] += 1
    return found, unreadable


def read_floors(path, tier):
    """[(suite, floor)] of the tier, in file order. Lines: `TIER SUITE FLOOR`; `#` starts a comment."""
    out = []
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            line = line.split('#', 1)[0].split()
            if not line:
                continue
            if len(line) != 3 or not line[2].isdigit():
                raise SystemExit('floors: %s:%d: expected `TIER SUITE FLOOR`, got %r' % (path, number, ' '.join(line)))
            if tier is None or line[0] == tier:
                out.append((line[1], int(line[2])))
    return out


def check(root, floors):
    """The report's lines and the number of suites below their floor."""
    found, unreadable = counts(root)
    lines = []
    for suite, floor in floors:
        if suite in unreadable:
            lines.append('floors: missing: %s (unreadable results: %s; floor %d)' % (suite, unreadable[suite], floor))
        elif suite not in found:
            lines.append('floors: missing: %s (no results; floor %d)' % (suite, floor))
        elif found[suite] < floor:
            lines.append('floors: short: %s has %d test cases, floor %d' % (suite, found[suite], floor))
    bad = len(lines)
    if bad:
        lines.append('floors: %d of %d suites below their floor' % (bad, len(floors)))
    else:
        lines.append('floors: %d suites at or above their floor' % len(floors))
    return lines, bad


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('results', help='the JUnit results folder (catkin: .ws/build/test_results)')
    ap.add_argument('--floors', default=FLOORS, help='the floors file (default tools/test_floors.txt)')
    ap.add_argument('--tier', help='only the floors of this tier (test, slow); default every line')
    ap.add_argument('--print', action='store_true', help='print the counts found as floor lines, check nothing')
    a = ap.parse_args(argv)
    if a.print:
        found, _ = counts(a.results)
        for suite in sorted(found):
            print('%s %s %d' % (a.tier or 'test', suite, found[suite]))
        return 0
    floors = read_floors(a.floors, a.tier)
    if not floors:
        print('floors: %s has no floor for tier %s' % (a.floors, a.tier))
        return 1
    lines, bad = check(a.results, floors)
    print('\n'.join(lines))
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
