#!/usr/bin/env python3
"""rostest: /odom from encoder odometry against ground truth, and bit-identical /odom on a replay."""
import math
import unittest

import rospy
import rostest

from simtest import Recorder, call, command, xy

LAP = 2 * math.pi


def run_lap(odom, truth):
    """From t = 0 (after a reset) drive the seed's circle for one lap; the messages of both topics."""
    call('/gazebo/pause_physics')
    call('/gazebo/reset_simulation')
    command(1.0, 1.0)
    for r in (odom, truth):
        r.restart()
    call('/gazebo/unpause_physics')
    o, t = odom.until(LAP + 0.05), truth.until(LAP + 0.05)
    call('/gazebo/pause_physics')
    return o, t


class OdometryTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_odometry')
        cls.odom = Recorder('/odom')
        cls.truth = Recorder('/gazebo/ground_truth/mycar')
        cls.odom.wait_connected()
        cls.truth.wait_connected()

    def test_encoder_odometry_follows_ground_truth_over_a_lap(self):
        odom, truth = run_lap(self.odom, self.truth)
        by_stamp = {m.header.stamp: m for m in truth}
        pairs = [(o, by_stamp[o.header.stamp]) for o in odom if o.header.stamp in by_stamp]
        self.assertGreater(len(pairs), 300)  # of 628 at 100 Hz, even if some were dropped on the way
        worst = max(math.dist(xy(o), xy(t)) for o, t in pairs)
        self.assertLess(worst, 0.05)

    def test_odom_header_frames_and_covariance(self):
        odom, _ = run_lap(self.odom, self.truth)
        m = odom[-1]
        self.assertEqual((m.header.frame_id, m.child_frame_id), ('odom', 'base_footprint'))
        self.assertEqual([m.pose.covariance[i * 7] for i in range(6)], [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3])
        self.assertGreater(m.twist.twist.linear.x, 0.9)  # the sign of v is kept (upstream reports |v|)

    def test_same_commands_give_bit_identical_odom(self):
        first, _ = run_lap(self.odom, self.truth)
        second, _ = run_lap(self.odom, self.truth)
        a = {m.header.stamp: (m.pose.pose, m.twist.twist) for m in first}
        b = {m.header.stamp: (m.pose.pose, m.twist.twist) for m in second}
        common = sorted(set(a) & set(b))
        self.assertGreater(len(common), 300)
        for stamp in common:
            self.assertEqual(a[stamp], b[stamp], 'odom differs at t = %s' % stamp.to_sec())


if __name__ == '__main__':
    rostest.rosrun('car', 'test_odometry', OdometryTest)
