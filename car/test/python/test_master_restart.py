"""A roscore restarted under a running sim_node: the node registers its publishers, subscribers and services with
the new master (src/ros/master_watch.cpp), so new clients find /clock, the /gazebo services and cmd_vel again.

Everything ROS runs in its own process (roscore on a free port, sim_node, rostopic/rosservice as clients), since a
client registered with the old master would be as lost as the node. Each wait is on a condition, with generous
wall-clock bounds that only stop a broken run from hanging."""
import os
import signal
import subprocess
import time

import pytest
import yaml

import rosgraph
import roslib.packages as roslib_packages
from car.testing.sim import free_port, shutdown_signal

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
BOUND = 120.0  # [s] wall, per condition: a bound against hanging, not a speed requirement


def wait_for(what, condition, bound=BOUND):
    """Polls condition() until it returns a true value (returned), or fails after bound wall seconds."""
    deadline = time.monotonic() + bound
    while True:
        try:
            value = condition()
            if value:
                return value
        except Exception as e:  # a master or service not there yet
            last = e
        else:
            last = None
        if time.monotonic() > deadline:
            raise AssertionError('%s: not within %.0f s (last error: %s)' % (what, bound, last))
        time.sleep(0.2)


class Graph:
    """roscore on its own port, and ROS command-line clients against it."""

    def __init__(self, tmp_path):
        self.port = free_port()
        self.uri = 'http://localhost:%d' % self.port
        self.env = dict(os.environ, ROS_MASTER_URI=self.uri, ROS_LOG_DIR=str(tmp_path / 'log'),
                        ROS_HOME=str(tmp_path))
        self.tmp = tmp_path
        self.core = None
        self.procs = []

    def start_core(self):
        self.core = subprocess.Popen(['roscore', '-p', str(self.port)], env=self.env, start_new_session=True,
                                     stdout=open(self.tmp / ('roscore-%d.log' % time.monotonic_ns()), 'w'),
                                     stderr=subprocess.STDOUT)
        return wait_for('roscore up', self.master_pid)

    def stop_core(self):
        # roscore, rosmaster and rosout share the session started above
        os.killpg(self.core.pid, shutdown_signal())
        try:
            self.core.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(self.core.pid, signal.SIGKILL)
            self.core.wait()

    def master_pid(self):
        return rosgraph.Master('/test_master_restart', master_uri=self.uri).getPid()

    def state(self):
        return rosgraph.Master('/test_master_restart', master_uri=self.uri).getSystemState()

    def start(self, args, name):
        p = subprocess.Popen(args, env=self.env, stdout=open(self.tmp / (name + '.log'), 'w'),
                             stderr=subprocess.STDOUT)
        self.procs.append(p)
        return p

    def run(self, args, timeout=60):
        """A client command's stdout; raises if it fails."""
        return subprocess.run(args, env=self.env, capture_output=True, text=True, timeout=timeout,
                              check=True).stdout

    def close(self):
        for p in self.procs:
            if p.poll() is None:
                p.send_signal(shutdown_signal())
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        if self.core and self.core.poll() is None:
            self.stop_core()


def providers(state, kind, name):
    """The nodes the master lists for a topic or service; kind 0 = publishers, 1 = subscribers, 2 = services."""
    return next((nodes for n, nodes in state[kind] if n == name), [])


def model_state(graph, name):
    out = graph.run(['rosservice', 'call', '/gazebo/get_model_state', '{model_name: %s}' % name])
    return yaml.safe_load(out)


@pytest.fixture
def graph(tmp_path):
    g = Graph(tmp_path)
    yield g
    g.close()


def test_restarted_master_gets_the_nodes_topics_and_services_again(graph, tmp_path, car04_xml):
    graph.start_core()
    sim_node = roslib_packages.find_node('car', 'sim_node')[0]
    sim = graph.start([sim_node, '_world_name:=' + WORLD, '_rtf:=1'], 'sim_node')
    wait_for('sim_node serves /gazebo/spawn_urdf_model',
             lambda: '/gazebo' in providers(graph.state(), 2, '/gazebo/spawn_urdf_model'))
    urdf = tmp_path / 'car.urdf'
    urdf.write_text(car04_xml)
    graph.run([os.path.join(ROOT, 'scripts', 'spawn_model'), '-urdf', '-file', str(urdf), '-model', 'mycar'])
    wait_for('the node subscribes to /cmd_vel', lambda: '/gazebo' in providers(graph.state(), 1, '/cmd_vel'))

    old_pid = graph.master_pid()
    graph.stop_core()
    with pytest.raises(Exception):
        graph.master_pid()
    new_pid = graph.start_core()
    assert new_pid != old_pid
    assert sim.poll() is None, 'sim_node died with its master'

    # the new master lists the node's publishers, subscribers and services again ...
    wait_for('/clock on the new master', lambda: '/gazebo' in providers(graph.state(), 0, '/clock'))
    wait_for('/cmd_vel on the new master', lambda: '/gazebo' in providers(graph.state(), 1, '/cmd_vel'))
    wait_for('get_model_state on the new master',
             lambda: '/gazebo' in providers(graph.state(), 2, '/gazebo/get_model_state'))
    wait_for('/use_sim_time on the new master',
             lambda: rosgraph.Master('/t', master_uri=graph.uri).getParam('/use_sim_time') is True)

    # ... and a client that only knows the new master reaches them: /clock
    clock = yaml.safe_load(graph.run(['rostopic', 'echo', '-n', '1', '/clock'], timeout=BOUND).split('---')[0])
    assert clock['clock']['secs'] + clock['clock']['nsecs'] > 0

    # a service: unit_box_0 where box_house's <state> puts it, (-4.96407, -2.00354) on the floor
    box = wait_for('get_model_state answers', lambda: model_state(graph, 'unit_box_0'))
    assert box['success'] is True
    assert box['pose']['position']['x'] == pytest.approx(-4.96407, abs=0.01)
    assert box['pose']['position']['y'] == pytest.approx(-2.00354, abs=0.01)

    # a subscriber: cmd_vel from a publisher started after the restart drives the car forward (+x, from x = 0)
    graph.start(['rostopic', 'pub', '-r', '10', '/cmd_vel', 'geometry_msgs/Twist', '{linear: {x: 0.5}}'], 'cmd_vel')
    car = wait_for('the car drives on a new cmd_vel publisher',
                   lambda: (lambda s: s if s['pose']['position']['x'] > 0.2 else None)(model_state(graph, 'mycar')))
    assert abs(car['pose']['position']['y']) < 0.05
    assert sim.poll() is None
