"""A pytest plug-in for bench/testing_stress.sh: how many sim seconds a car.testing suite ran, per test file, and
the wall seconds its tests took (setup + call + teardown). Writes JSON to $CAR_SIMTIME_OUT at the session's end.

Sim seconds: a `sim` test's simulator clock when the test ends (each test starts at sim time 0 after the reset);
a car batch test's: the sim_time of the runs in its `results` fixture (counted once).
"""
import json
import os

import pytest

_files = {}
_seen_results = set()


def _entry(item):
    return _files.setdefault(item.location[0], {'sim_s': 0.0, 'wall_s': 0.0, 'tests': 0, 'failed': 0})


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_teardown(item):
    e = _entry(item)
    s = getattr(item, '_car_sim', None)
    if s is not None:
        e['sim_s'] += s.now()
    res = getattr(item, 'funcargs', {}).get('results')
    if res is not None and id(res) not in _seen_results:
        _seen_results.add(id(res))
        e['sim_s'] += sum(r['sim_time'] for r in res[1])


def pytest_runtest_logreport(report):
    e = _files.setdefault(report.location[0], {'sim_s': 0.0, 'wall_s': 0.0, 'tests': 0, 'failed': 0})
    e['wall_s'] += report.duration
    if report.when == 'call':
        e['tests'] += 1
    if report.failed:
        e['failed'] += 1


def pytest_sessionfinish(session):
    out = os.environ.get('CAR_SIMTIME_OUT')
    if out:
        with open(out, 'w') as f:
            json.dump(_files, f, indent=1)
