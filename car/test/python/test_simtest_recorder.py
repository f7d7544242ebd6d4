"""simtest.Recorder's rules for runs after a reset (test/ros/simtest.py), fed messages by hand in arrival order."""
import os
import sys

import pytest

import rospy
from nav_msgs.msg import Odometry

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'ros'))
import simtest  # noqa: E402


class FakeSubscriber:
    """Stands in for rospy.Subscriber (no master): connected at once, remembers whether it was unregistered."""
    def __init__(self, topic, msg_type, cb, callback_args=None, **kwargs):
        self.name, self.cb, self.args, self.unregistered = topic, cb, callback_args, False

    def deliver(self, msg):
        self.cb(msg, self.args)

    def get_num_connections(self):
        return 1

    def unregister(self):
        self.unregistered = True


@pytest.fixture
def recorder(monkeypatch):
    monkeypatch.setattr(simtest.rospy, 'Subscriber', FakeSubscriber)
    return simtest.Recorder('/gazebo/ground_truth/mycar')


def odom(t):
    m = Odometry()
    m.header.stamp = rospy.Time.from_sec(t)
    return m


def stamps(r):
    return [round(m.header.stamp.to_sec(), 3) for m in r.msgs]


def test_restart_subscribes_again(recorder):
    old = recorder.sub
    recorder.restart()
    assert old.unregistered and recorder.sub is not old and not recorder.sub.unregistered


def test_old_connections_message_read_after_restart_is_ignored(recorder):
    old = recorder.sub
    old.deliver(odom(7.37))
    recorder.restart()
    # published at 7.38 s before the pause, read after the records were cleared
    old.deliver(odom(7.38))
    assert stamps(recorder) == []
    with pytest.raises(AssertionError, match='no message at sim time 4.050'):
        recorder.until(4.05, timeout=0.05)


def test_new_connection_keeps_whatever_comes_first(recorder):
    recorder.restart()
    # the first messages of the run dropped on the way (a connection's queue drops the oldest)
    for t in (0.45, 0.5, 4.05):
        recorder.sub.deliver(odom(t))
    assert stamps(recorder) == [0.45, 0.5, 4.05]


def test_stamp_going_back_without_restart_starts_a_new_run(recorder):
    for t in (1.0, 1.01, 0.01):
        recorder.sub.deliver(odom(t))
    assert stamps(recorder) == [0.01]
