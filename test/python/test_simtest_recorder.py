"""simtest.Recorder's rules for runs after a reset (test/ros/simtest.py), fed messages by hand in arrival order."""
import os
import sys

import pytest

rospy = pytest.importorskip('rospy')
from nav_msgs.msg import Odometry  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'ros'))
import simtest  # noqa: E402


@pytest.fixture
def recorder(monkeypatch):
    # no master: the subscriber is never made, messages go to the callback directly
    monkeypatch.setattr(simtest.rospy, 'Subscriber', lambda *a, **k: None)
    return simtest.Recorder('/gazebo/ground_truth/mycar')


def odom(t):
    m = Odometry()
    m.header.stamp = rospy.Time.from_sec(t)
    return m


def stamps(r):
    return [round(m.header.stamp.to_sec(), 3) for m in r.msgs]


def test_old_runs_message_read_after_restart_is_dropped(recorder):
    recorder._cb(odom(7.37))
    recorder.restart()
    # published at 7.38 s before the pause, read after the records were cleared
    recorder._cb(odom(7.38))
    assert stamps(recorder) == []


def test_new_runs_first_message_is_kept_and_later_ones_follow(recorder):
    recorder.restart()
    for t in (7.38, 0.01, 0.02, 4.05):
        recorder._cb(odom(t))
    assert stamps(recorder) == [0.01, 0.02, 4.05]


def test_until_waits_for_the_new_run_not_a_stale_late_stamp(recorder):
    recorder.restart()
    recorder._cb(odom(7.38))
    with pytest.raises(AssertionError, match='no message at sim time 4.050'):
        recorder.until(4.05, timeout=0.05)


def test_stamp_going_back_without_restart_starts_a_new_run(recorder):
    for t in (1.0, 1.01, 0.01):
        recorder._cb(odom(t))
    assert stamps(recorder) == [0.01]
