"""Test floors (tools/check_floors.py, tools/test_floors.txt): a suite that vanished from the JUnit results, or
recorded fewer test cases than its floor, fails by its name, and tools/test.sh's closing line counts it."""
import os
import re
import shutil
import subprocess

import pytest

from conftest import REPO

CHECK = os.path.join(REPO, 'tools', 'check_floors.py')
FLOORS = os.path.join(REPO, 'tools', 'test_floors.txt')


def junit(path, cases, failed=()):
    """A JUnit file of test cases [(classname, name)], the ones named in failed failing."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write('<?xml version="1.0"?>\n<testsuite name="s" tests="%d" failures="%d" errors="0" skipped="0">\n'
                % (len(cases), len(failed)))
        for cls, name in cases:
            f.write('<testcase classname="%s" name="%s" time="0.1">' % (cls, name))
            if name in failed:
                f.write('<failure message="broken"/>')
            f.write('</testcase>\n')
        f.write('</testsuite>\n')


@pytest.fixture
def results(tmp_path):
    """A results folder as catkin leaves it: a gtest binary, a pytest run of two files, a rostest with its
    rosunit twin; and a floors file for it."""
    car = tmp_path / 'results' / 'car'
    junit(str(car / 'gtest-test_core.xml'), [('Model', 'a'), ('Model', 'b'), ('World', 'c')])
    junit(str(car / 'pytest-car.xml'), [('test.python.test_one', 'test_a'), ('test.python.test_one.TestX', 'test_b'),
                                        ('test.python.test_two', 'test_c')])
    junit(str(car / 'rostest-test_ros_drive.xml'), [('car.rostest', 'test_drive')])
    junit(str(car / 'rosunit-drive.xml'), [('drive', 'test_drive')])
    floors = tmp_path / 'floors.txt'
    floors.write_text('# tier suite floor\n'
                      'test gtest-test_core 3\n'
                      'test pytest-car 3\n'
                      'test pytest-car/test_one.py 2\n'
                      'test pytest-car/test_two.py 1\n'
                      'test rostest-test_ros_drive 1\n'
                      'slow workspace 20   # the slow tier: not checked with --tier test\n')
    return tmp_path


def check(folder, *args):
    return subprocess.run(['/usr/bin/python3', CHECK, '--floors', str(folder / 'floors.txt')] + list(args)
                          + [str(folder / 'results')], capture_output=True, text=True, timeout=60)


def test_every_suite_at_its_floor_passes(results):
    r = check(results, '--tier', 'test')
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout == 'floors: 5 suites at or above their floor\n'


def test_a_missing_gtest_binary_and_a_missing_pytest_file_fail_by_name(results):
    os.remove(str(results / 'results' / 'car' / 'gtest-test_core.xml'))
    junit(str(results / 'results' / 'car' / 'pytest-car.xml'), [('test.python.test_one', 'test_a'),
                                                                ('test.python.test_one.TestX', 'test_b')])
    r = check(results, '--tier', 'test')
    assert r.returncode == 1
    assert r.stdout.splitlines() == [
        'floors: missing: gtest-test_core (no results; floor 3)',
        'floors: short: pytest-car has 2 test cases, floor 3',
        'floors: missing: pytest-car/test_two.py (no results; floor 1)',
        'floors: 3 of 5 suites below their floor',
    ]


def test_a_short_suite_and_a_missing_rostest_fail_by_name(results):
    os.remove(str(results / 'results' / 'car' / 'rostest-test_ros_drive.xml'))
    junit(str(results / 'results' / 'car' / 'gtest-test_core.xml'), [('Model', 'a')])
    r = check(results, '--tier', 'test')
    assert r.returncode == 1
    assert r.stdout.splitlines() == [
        'floors: short: gtest-test_core has 1 test cases, floor 3',
        'floors: missing: rostest-test_ros_drive (no results; floor 1)',
        'floors: 2 of 5 suites below their floor',
    ]


def test_the_slow_tier_is_checked_on_its_own(results):
    r = check(results, '--tier', 'slow')
    assert r.returncode == 1
    assert r.stdout.splitlines() == ['floors: missing: workspace (no results; floor 20)',
                                     'floors: 1 of 1 suites below their floor']


def test_an_unreadable_result_file_is_missing(results):
    (results / 'results' / 'car' / 'rostest-test_ros_drive.xml').write_text('<testsuite')
    r = check(results, '--tier', 'test')
    assert r.returncode == 1
    assert r.stdout.splitlines()[0].startswith('floors: missing: rostest-test_ros_drive (unreadable results: ')


def test_a_tier_without_floors_fails(results):
    r = check(results, '--tier', 'nonesuch')
    assert r.returncode == 1
    assert 'has no floor for tier nonesuch' in r.stdout


@pytest.mark.skipif(not shutil.which('catkin_test_results'), reason='needs catkin_test_results (Debian: catkin)')
def test_the_closing_line_counts_each_suite_below_its_floor(results):
    """tools/test.sh's verdict (tools/test_lib.sh): every result passes, but a vanished suite is one failure in the
    closing line and the exit status is 1."""
    os.remove(str(results / 'results' / 'car' / 'gtest-test_core.xml'))
    script = 'ROOT=%s; source %s/tools/test_lib.sh; verdict %s test' % (REPO, REPO, results / 'results')
    env = dict(os.environ, CAR_TEST_FLOORS=str(results / 'floors.txt'))
    r = subprocess.run(['bash', '-c', script], capture_output=True, text=True, timeout=120, env=env)
    lines = r.stdout.splitlines()
    assert r.returncode == 1, r.stdout + r.stderr
    assert 'floors: missing: gtest-test_core (no results; floor 3)' in lines
    assert lines[-1] == '5 passed, 1 failed, 0 skipped'
    # once after the counts, again after the failures' list
    assert [l for l in lines if re.match(r'^\d+ passed, \d+ failed, \d+ skipped$', l)] == [lines[-1]] * 2


def test_the_repository_floors_name_every_tier_and_each_kind_of_suite():
    """tools/test_floors.txt itself: the README command's gtest binaries, pytest files and rostests, and the slow
    tier's install-space checks, each with a floor above zero."""
    rows = [l.split('#', 1)[0].split() for l in open(FLOORS)]
    rows = [r for r in rows if r]
    assert all(len(r) == 3 and int(r[2]) > 0 for r in rows), rows
    suites = {(r[0], r[1]) for r in rows}
    assert ('test', 'gtest-test_core') in suites
    assert ('test', 'pytest-car/test_check_floors.py') in suites
    assert ('slow', 'workspace') in suites
    rostests = sorted(f[:-len('.test')] for f in os.listdir(os.path.join(REPO, 'car', 'test', 'ros'))
                      if f.endswith('.test'))
    # in tools/test.sh's tier (catkin's run_tests), or in the slow tier (tools/test_slow.sh runs it in CI)
    missing = [t for t in rostests
               if not {('test', 'rostest-test_ros_' + t), ('slow', 'rostest-test_ros_' + t)} & suites]
    assert not missing, 'rostests without a floor: %s' % missing
