"""Lockstep (docs/COMPAT-dropins.md "Lockstep", docs/TESTING.md): sim_node's ~lockstep, driven through car.testing
as a user would, each in a pytest subprocess on a tiny test file (as test_testing_plugin.py).

The node under test is lockstep_echo.py: it answers each /scan with a /cmd_vel after a deliberate wall-clock delay
and reports on /echo_lag the sim time that passed between the scan's stamp and its answer. Needs the workspace
(sim_node) sourced.
"""
import os
import pickle
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
HERE = os.path.dirname(os.path.realpath(__file__))
CAR04 = os.path.join(ROOT, 'urdf', 'car_camera_lidar04.xacro')
BOX_HOUSE = os.path.join(ROOT, 'worlds', 'box_house.world')
ECHO = os.path.join(HERE, 'lockstep_echo.py')
FOLLOWER = os.path.join(ROOT, 'examples', 'wall_follower', 'wall_follower.py')


def run_pytest(tmp_path, marker, body, *args, name='test_user.py'):
    (tmp_path / name).write_text('import pytest\npytestmark = pytest.mark.car_sim(%s)\n%s' % (marker, body))
    env = dict(os.environ)
    env.pop('ROS_MASTER_URI', None)
    return subprocess.run([sys.executable, '-m', 'pytest', '-p', 'car.testing', '-p', 'no:cacheprovider', '-q',
                           str(tmp_path / name)] + list(args), cwd=str(tmp_path), env=env, capture_output=True,
                          text=True, timeout=600)


def echo_marker(lockstep, *echo_args, timeout=5.0):
    return ('robot=%r, name="bot", nodes=[[%r, %r] + %r], rtf=0, lockstep=%r, lockstep_timeout=%r'
            % (CAR04, sys.executable, ECHO, list(echo_args), lockstep, timeout))


LAGS = '''
import os, json

def test_it(sim):
    rec = sim.record({'/echo_lag': 'std_msgs/Float64'})
    sim.until(lambda: len(rec['/echo_lag']) >= 4, timeout=600.0, what='4 answers')
    with open(os.environ['LAGS'], 'w') as f:
        json.dump([m.data for m in rec['/echo_lag']], f)
'''


def _lags(tmp_path, lockstep, delay):
    out = tmp_path / 'lags.json'
    os.environ['LAGS'] = str(out)
    try:
        r = run_pytest(tmp_path, echo_marker(lockstep, '--delay', str(delay)), LAGS)
    finally:
        del os.environ['LAGS']
    assert r.returncode == 0, r.stdout + r.stderr
    import json
    return json.loads(out.read_text())


def test_lockstep_answer_costs_no_sim_time(tmp_path):
    # a node that takes 0.2 s of wall time per scan: the simulator stood still at the scan's tick until the answer,
    # so the sim time it reports before answering is the scan's stamp, exactly
    lags = _lags(tmp_path, {'/scan': '/cmd_vel'}, 0.2)
    assert len(lags) >= 4
    assert lags == [0.0] * len(lags), lags


def test_without_lockstep_the_answer_costs_sim_time(tmp_path):
    # the comparison above can fail: at rtf 0 with no lockstep the simulator runs on while the node sleeps
    # 0.2 s of wall time (the waits pace it at >= 0.05x real time: >= 10 ms of sim time per answer)
    lags = _lags(tmp_path, {}, 0.2)
    assert len(lags) >= 4
    assert min(lags) >= 0.01, lags


TIMEOUT = '''
def test_it(sim):
    # the echo node is mute: the first scan's wait ends after 0.5 s of wall time, and the run goes on
    assert sim.run_for(1.0) >= 1.0
    log = sim.log_tail('sim_node.log', 400)
    lines = [l for l in log.splitlines() if 'car: lockstep: nothing on' in l]
    print('\\n'.join(lines))
    assert len(lines) == 1, log
'''


def test_timeout_warns_once_naming_the_topics_and_steps_on(tmp_path):
    r = run_pytest(tmp_path, echo_marker({'/scan': '/cmd_vel'}, '--mute', timeout=0.5), TIMEOUT, '-s')
    assert r.returncode == 0, r.stdout + r.stderr
    # the first scan is due at tick ceil(1000 / 5.5) = 182 of 1 ms (src/plugins/plugin.cpp Schedule)
    assert ('car: lockstep: nothing on /cmd_vel within 0.5 s of wall time after /scan at sim time 0.182 s: '
            'stepping on without waiting for /cmd_vel until a message on it arrives') in r.stdout, r.stdout


DUMP = '''
import os, pickle
from io import BytesIO

def test_it(sim):
    rec = sim.record({'/odom': 'nav_msgs/Odometry', '/scan': 'sensor_msgs/LaserScan'})
    sim.run_for(8.0)
    out = []
    for r in rec.snapshot():
        if r.stamp <= 7.9:
            b = BytesIO()
            r.msg.serialize(b)
            out.append((r.topic, r.stamp, b.getvalue()))
    with open(os.environ['DUMP'], 'wb') as f:
        pickle.dump(sorted(out), f)
'''


def _follower_run(tmp_path, tag):
    marker = ('robot=%r, name="car", world=%r, nodes=[[%r, %r]], rtf=0, lockstep={"/scan": "/cmd_vel"}'
              % (CAR04, BOX_HOUSE, sys.executable, FOLLOWER))
    os.environ['DUMP'] = str(tmp_path / ('%s.pkl' % tag))
    try:
        r = run_pytest(tmp_path, marker, DUMP, '--car-seed', '5')
    finally:
        del os.environ['DUMP']
    assert r.returncode == 0, r.stdout + r.stderr
    return pickle.loads((tmp_path / ('%s.pkl' % tag)).read_bytes())


def test_wall_follower_in_lockstep_is_deterministic(tmp_path):
    # the example's node in the loop: two runs with the same seed give the same messages, byte for byte
    a = _follower_run(tmp_path, 'a')
    b = _follower_run(tmp_path, 'b')
    odom = [m for m in a if m[0] == '/odom']
    assert len(odom) >= 780 and len([m for m in a if m[0] == '/scan']) >= 40
    # it drove (the node's commands reached the car): the last odometry differs from the first
    assert odom[0][2] != odom[-1][2]
    assert a == b
