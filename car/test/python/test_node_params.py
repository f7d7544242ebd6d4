"""sim_node's number parameters that must be finite (src/ros/params.hpp): ~rtf NaN or inf stops the node with its
reason, ~lockstep_timeout NaN or inf falls back to 5 s with a warning. Each sim_node runs against its own rosmaster
on a free port. Needs the workspace (sim_node) sourced."""
import os
import subprocess
import time

import pytest
import roslib.packages as roslib_packages
from car.testing.sim import free_port, master_up, shutdown_signal

BOUND = 120.0  # [s] wall: a bound against hanging, not a speed requirement


@pytest.fixture
def master(tmp_path):
    """A rosmaster of its own; the environment to run nodes against it."""
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port, ROS_LOG_DIR=str(tmp_path / 'log'),
               ROS_HOME=str(tmp_path))
    core = subprocess.Popen(['rosmaster', '--core', '-p', str(port)], env=env, start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    # up before a node starts: world_markers, started at once, was refused a connection on a busy machine
    # (ConnectionRefusedError where the ~rate check was expected, clean-install proof of 2026-11-29)
    deadline = time.monotonic() + BOUND
    while not master_up(env['ROS_MASTER_URI']):
        assert core.poll() is None, 'rosmaster on port %d exited (%s)' % (port, core.returncode)
        assert time.monotonic() < deadline, 'rosmaster on port %d did not answer within %.0f s' % (port, BOUND)
        time.sleep(0.05)
    yield env
    # SIGINT, or SIGTERM where this run ignores SIGINT (the master would inherit that)
    os.killpg(core.pid, shutdown_signal())
    core.wait(timeout=30)


def exit_code(proc, what):
    """proc's exit status; the test fails, naming `what`, when it runs past BOUND."""
    try:
        return proc.wait(timeout=BOUND)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        pytest.fail('%s did not stop within %.0f s' % (what, BOUND))


def sim_node(env, *params, log):
    return subprocess.Popen([roslib_packages.find_node('car', 'sim_node')[0]] + list(params), env=env,
                            stdout=open(log, 'w'), stderr=subprocess.STDOUT)


@pytest.mark.parametrize('value', ['nan', 'inf'])
def test_non_finite_rtf_stops_the_node_with_the_reason(master, tmp_path, value):
    node = sim_node(master, '_rtf:=' + value, log=tmp_path / 'node.log')
    rc = exit_code(node, 'sim_node with ~rtf %s' % value)
    log = (tmp_path / 'node.log').read_text()
    assert rc == 1, log
    assert 'car: parameter ~rtf must be >= 0 (0 = as fast as possible), got %s' % value in log, log


@pytest.mark.parametrize('value', ['nan', 'inf'])
def test_non_finite_lockstep_timeout_warns_and_uses_5_s(master, tmp_path, value):
    node = sim_node(master, '_lockstep_timeout:=' + value, log=tmp_path / 'node.log')
    line = 'car: parameter ~lockstep_timeout must be > 0 [s], got %s: using 5' % value
    try:
        deadline = time.monotonic() + BOUND
        # the node reads ~lockstep_timeout once its world is loaded, then runs on
        while line not in (tmp_path / 'node.log').read_text():
            assert node.poll() is None, (tmp_path / 'node.log').read_text()
            assert time.monotonic() < deadline, 'no warning about ~lockstep_timeout %s within %.0f s:\n%s' % (
                value, BOUND, (tmp_path / 'node.log').read_text())
            time.sleep(0.1)
    finally:
        node.send_signal(shutdown_signal())
        try:
            node.wait(timeout=30)
        except subprocess.TimeoutExpired:
            node.kill()
            node.wait()


@pytest.mark.parametrize('value,shown', [('0', '0'), ('-2', '-2'), ('nan', 'nan'), ('fast', 'fast')])
def test_world_markers_rate_not_above_zero_stops_it_with_the_reason(master, tmp_path, value, shown):
    log = tmp_path / 'markers.log'
    node = subprocess.Popen([roslib_packages.find_node('car', 'world_markers')[0], '_rate:=' + value], env=master,
                            stdout=open(log, 'w'), stderr=subprocess.STDOUT)
    rc = exit_code(node, 'world_markers with ~rate %s' % value)
    text = log.read_text()
    assert rc == 1, text
    assert 'world_markers: ~rate must be > 0 [Hz of wall time], got %s\n' % shown in text, text
