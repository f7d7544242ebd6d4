"""The regression sweep over start poses, with car batch (docs/BATCH.md): the node's own control law
(wall_follower.command) drives the car in the core, without ROS, from each start pose in sweep.yaml for 20 s.

No master and no node process: each run is deterministic and takes about a second of wall time, so a sweep of
many poses is cheap; test_wall_follower.py tests the node itself.
"""
import os

import pytest

from car import batch, scenario

HERE = os.path.dirname(os.path.abspath(__file__))
SWEEP = os.path.join(HERE, 'sweep.yaml')

# the car's footprint half-diagonal is about 0.25 m: a lidar range below this is a touch [m]
TOUCH = 0.25


@pytest.fixture(scope='module')
def results(tmp_path_factory):
    runs = scenario.load(SWEEP)
    # serially in this process; a Ray run gives the same numbers bit for bit (test/python/test_batch.py)
    return runs, batch.run_all(runs, str(tmp_path_factory.mktemp('sweep')), serial=True, progress=False,
                               resume=False)


def test_every_start_pose_ran(results):
    runs, res = results
    assert len(res) == 4
    assert [r['status'] for r in res] == ['ok'] * 4, [r['error'] for r in res if r['status'] != 'ok']
    # the first trajectory sample is the start pose each run was given [m]
    starts = [(round(r['robots'][0]['trajectory'][0][1], 1), round(r['robots'][0]['trajectory'][0][2], 1))
              for r in res]
    assert starts == [(0.0, 0.0), (-2.0, 1.5), (2.5, -1.0), (-3.0, -1.0)], starts


def test_no_run_touches_anything(results):
    for run, res in zip(*results):
        row = res['robots'][0]
        assert row['collisions'] == 0, '%s: %d contacts' % (run['overrides'], row['collisions'])
        assert row['min_obstacle'] > TOUCH, '%s: came within %.3f m' % (run['overrides'], row['min_obstacle'])


def test_every_run_keeps_driving(results):
    # 20 s at up to 0.4 m/s: a car that follows walls covers metres; one that creeps at a wall (0.05 m/s) does not
    for run, res in zip(*results):
        assert res['robots'][0]['distance'] > 4.0, '%s: %.2f m' % (run['overrides'], res['robots'][0]['distance'])
