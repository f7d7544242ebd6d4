"""car.testing as a user meets it: pytest run in a subprocess on a tiny test file that uses the `sim` fixture.

Needs the workspace (sim_node) sourced, as the suite's other ROS tests do. Each run starts its own master on a
free port, so these run beside anything else.
"""
import os
import signal
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
CAR04 = os.path.join(ROOT, 'urdf', 'car_camera_lidar04.xacro')
BOX_HOUSE = os.path.join(ROOT, 'worlds', 'box_house.world')

HEADER = '''
import pytest
pytestmark = pytest.mark.car_sim(robot=%r, name='bot', world=%r)
''' % (CAR04, BOX_HOUSE)


def run_pytest(tmp_path, body, *args, name='test_user.py'):
    (tmp_path / name).write_text(HEADER + body)
    env = dict(os.environ)
    env.pop('ROS_MASTER_URI', None)  # the plug-in must not need one
    return subprocess.run([sys.executable, '-m', 'pytest', '-p', 'car.testing', '-p', 'no:cacheprovider', '-q',
                           str(tmp_path / name)] + list(args), cwd=str(tmp_path), env=env, capture_output=True,
                          text=True, timeout=600)


def test_run_for_stops_at_its_target_and_the_test_passes(tmp_path):
    # run_for(1.5) from sim time 0 pauses after step 1500 of 1 ms, exactly, whatever the load (the simulator
    # pauses itself); the robot, given no command, stays where it was spawned (0, 0)
    r = run_pytest(tmp_path, '''
def test_it(sim):
    t = sim.run_for(1.5)
    assert t == 1.5, t
    p = sim.pose('bot')
    assert abs(p.x) < 1e-3 and abs(p.y) < 1e-3, p
''')
    assert r.returncode == 0, r.stdout + r.stderr
    assert '1 passed' in r.stdout


def test_failing_until_names_its_wait_and_seed_and_leaves_plot_and_bag(tmp_path):
    r = run_pytest(tmp_path, '''
def test_it(sim):
    sim.record({'/odom': 'nav_msgs/Odometry'})
    sim.until(lambda: sim.pose('bot').x > 5, timeout=1.0, what='bot past x = 5 m')
''', '--car-seed', '7', '--junitxml', str(tmp_path / 'out' / 'junit.xml'))
    assert r.returncode == 1, r.stdout + r.stderr
    assert 'waiting for: bot past x = 5 m' in r.stdout
    assert '--car-seed 7' in r.stdout
    png = tmp_path / 'out' / 'car-artifacts' / 'test_user.py__test_it.png'
    bag = tmp_path / 'out' / 'car-artifacts' / 'test_user.py__test_it.bag'
    assert 'plot: %s' % png in r.stdout and 'bag: %s' % bag in r.stdout
    assert png.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
    import rosbag
    with rosbag.Bag(str(bag)) as b:
        stamps = [m.header.stamp.to_sec() for _, m, _ in b.read_messages(topics=['/odom'])]
    # odometry at 100 Hz over the 1 s the wait ran: about 100 messages, none after the pause
    assert 95 <= len(stamps) <= 110, len(stamps)
    assert max(stamps) < 1.1
    xml = (tmp_path / 'out' / 'junit.xml').read_text()
    assert 'car_bag' in xml and 'car_seed' in xml


def test_a_recording_read_after_a_wait_holds_every_message_sent_before_it(tmp_path):
    # a reader slower than the simulator: each message takes 10 ms of wall time to record (a busy machine's Python).
    # At rtf 0 run_for(5.0) is over long before 100 such messages are read, and the recording must still hold every
    # /gazebo/model_states message of those 5 s when run_for returns: car.testing's simulator publishes it at its
    # trajectory_rate, 20 Hz of sim time (ticks 50, 100, ... 5000), with a publisher queue of 100, so none is
    # dropped however slow the reader. (Without Sim._settle it held 9 of them when run_for returned.)
    r = run_pytest(tmp_path, '''
import time
from car.testing.sim import Recording
_record = Recording._cb
def _slow(self, msg, args):
    time.sleep(0.01)
    _record(self, msg, args)
Recording._cb = _slow

def test_it(sim):
    rec = sim.record({'/gazebo/model_states': 'gazebo_msgs/ModelStates'})
    assert sim.run_for(5.0) == 5.0
    n = len(rec['/gazebo/model_states'])
    assert n == 100, n
''')
    assert r.returncode == 0, r.stdout + r.stderr


DUMP = '''
import os, pickle
from io import BytesIO

def test_it(sim):
    import rospy
    from geometry_msgs.msg import Twist
    rec = sim.record({'/odom': 'nav_msgs/Odometry', '/scan': 'sensor_msgs/LaserScan'})
    msg = Twist()
    msg.linear.x, msg.angular.z = 0.4, 0.3
    sim.publish('/cmd_vel', msg)
    sim.run_for(2.0)
    out = []
    for r in rec.snapshot():
        if r.stamp <= 1.9:
            b = BytesIO()
            r.msg.serialize(b)
            out.append((r.topic, r.stamp, b.getvalue()))
    with open(os.environ['DUMP'], 'wb') as f:
        pickle.dump(sorted(out), f)
'''


def _dump(tmp_path, seed, tag):
    os.environ['DUMP'] = str(tmp_path / ('%s.pkl' % tag))
    try:
        r = run_pytest(tmp_path, DUMP, '--car-seed', str(seed))
    finally:
        del os.environ['DUMP']
    assert r.returncode == 0, r.stdout + r.stderr
    import pickle
    return pickle.loads((tmp_path / ('%s.pkl' % tag)).read_bytes())


def test_same_seed_gives_identical_recorded_messages(tmp_path):
    a = _dump(tmp_path, 3, 'a')
    b = _dump(tmp_path, 3, 'b')
    # odometry 100 Hz and scans 5.5 Hz over 1.9 s: 190 + 10 messages
    assert len([m for m in a if m[0] == '/odom']) >= 185
    assert len([m for m in a if m[0] == '/scan']) >= 10
    # the robot drove from the first step (the command held before the run began)
    assert a[0][0] == '/odom' and a[0][2] != a[1][2]
    assert a == b


def test_another_seed_gives_other_scans(tmp_path):
    # the comparison above can fail: the lidar's noise (stddev 0.01 m) follows the seed
    a = _dump(tmp_path, 3, 'a')
    c = _dump(tmp_path, 4, 'c')
    assert [m for m in a if m[0] == '/scan'] != [m for m in c if m[0] == '/scan']


WHERE = '''
import os

def test_it(sim):
    # sim time passes on this worker's own simulator; the master it talks to is in ROS_MASTER_URI
    t = sim.run_for(0.5)
    with open(os.path.join(os.environ['OUT'], os.environ['PYTEST_XDIST_WORKER']), 'w') as f:
        f.write('%s %s %.3f %d' % (os.environ['ROS_MASTER_URI'], sim.master_uri, t, sim.seed))
'''


def _two_workers(tmp_path, *args):
    """Two modules, one test each, under -n 2: xdist's load schedule sends fewer than two tests per worker round
    robin, so each worker runs one module. Returns {worker: [ROS_MASTER_URI, sim.master_uri, sim time, seed]}."""
    pytest.importorskip('xdist')
    (tmp_path / 'test_b.py').write_text(HEADER + WHERE)
    out = tmp_path / 'out'
    out.mkdir()
    os.environ['OUT'] = str(out)
    try:
        r = run_pytest(tmp_path, WHERE, str(tmp_path / 'test_b.py'), '-n', '2', *args, name='test_a.py')
    finally:
        del os.environ['OUT']
    assert r.returncode == 0, r.stdout + r.stderr
    assert '2 passed' in r.stdout, r.stdout
    seen = {p.name: p.read_text().split() for p in out.iterdir()}
    assert sorted(seen) == ['gw0', 'gw1'], seen
    return seen


def test_two_xdist_workers_get_their_own_masters(tmp_path):
    seen = _two_workers(tmp_path)
    (env0, own0, t0, _), (env1, own1, t1, _) = seen['gw0'], seen['gw1']
    # each worker's tests (and the processes they start) see the master that worker started
    assert env0 == own0 and env1 == own1, seen
    assert env0 != env1, 'both workers used %s' % env0
    assert float(t0) >= 0.5 and float(t1) >= 0.5, seen


def test_xdist_workers_share_the_controllers_random_seed(tmp_path):
    # --car-seed random is drawn once, by the controller: the failure report's replay command holds for every worker
    seen = _two_workers(tmp_path, '--car-seed', 'random')
    assert seen['gw0'][3] == seen['gw1'][3], seen


# A background job of a script (`pytest &`) starts with SIGINT ignored, and the master and launches the plug-in starts
# would inherit that: they are asked to stop with SIGTERM there (a suite run that way once waited 30 s per master),
# with SIGINT (a clean shutdown, as Ctrl-C) everywhere else.
@pytest.mark.parametrize('handler, expected', [(signal.default_int_handler, signal.SIGINT),
                                               (signal.SIG_IGN, signal.SIGTERM)],
                         ids=['sigint-reaches', 'sigint-ignored'])
def test_processes_are_stopped_with_a_signal_that_reaches_them(handler, expected):
    from car.testing.sim import shutdown_signal
    old = signal.signal(signal.SIGINT, handler)
    try:
        assert shutdown_signal() == expected
    finally:
        signal.signal(signal.SIGINT, old)
