#!/usr/bin/env python3
"""Where a test run's time went, from its JUnit results (catkin's .ws/build/test_results after tools/test.sh, or
.ws/build/test_results_slow after tools/test_slow.sh): the slowest test cases and the slowest suites by JUnit time
(a suite as tools/check_floors.py names it: a result file, or a pytest file within one), and the wall time from
the first result file written to the last.

A rostest's JUnit time is its whole run (roslaunch, the simulator, the test node); rosunit-*.xml files, which
repeat a rostest's cases, are left out. `catkin_make run_tests -j2` runs two tests at once, so the JUnit times
add up to more than the wall time.

Usage: test_times.py [-n N] RESULTS_DIR"""
import argparse
import collections
import os
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_floors import pytest_file  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('results')
    ap.add_argument('-n', type=int, default=20, help='how many of the slowest (default 20)')
    a = ap.parse_args(argv)
    cases, suites, mtimes = [], collections.Counter(), []
    for dirpath, _, names in os.walk(a.results):
        for name in names:
            if not name.endswith('.xml') or name.startswith('rosunit-'):
                continue
            path = os.path.join(dirpath, name)
            try:
                root = ET.parse(path).getroot()
            except (ET.ParseError, OSError):
                continue
            suite = name[:-len('.xml')]
            mtimes.append(os.path.getmtime(path))
            for c in root.iter('testcase'):
                t = float(c.get('time') or 0)
                cases.append((t, suite, '%s.%s' % (c.get('classname', ''), c.get('name', ''))))
                suites[suite] += t
                f = pytest_file(c.get('classname')) if suite.startswith('pytest-') else None
                if f:
                    suites['%s/%s' % (suite, f)] += t
    if not cases:
        print('test_times: no JUnit results under %s' % a.results)
        return 1
    print('The %d slowest test cases by JUnit time [s]:' % a.n)
    for t, suite, case in sorted(cases, reverse=True)[:a.n]:
        print('  %8.1f  %-36s %s' % (t, suite, case))
    print('The %d slowest suites by JUnit time [s] (pytest files also within their result file):' % a.n)
    for suite, t in sorted(suites.items(), key=lambda kv: -kv[1])[:a.n]:
        print('  %8.1f  %s' % (t, suite))
    print('JUnit times sum to %.0f s over %d test cases; result files written over %.0f s of wall time' % (
        sum(c[0] for c in cases), len(cases), max(mtimes) - min(mtimes)))
    return 0


if __name__ == '__main__':
    sys.exit(main())
