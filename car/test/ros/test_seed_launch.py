#!/usr/bin/env python3
"""rostest: the tutorial's 三.1 launch file drives the car from /cmd_vel, as in the tutorial."""
import math
import unittest

import rospy
import rostest

from simtest import Recorder, call, command, sim_now, xy


class SeedLaunchTest(unittest.TestCase):
    def test_cmd_vel_moves_the_car_and_odom_follows(self):
        rospy.init_node('test_seed_launch')
        odom = Recorder('/odom')
        odom.wait_connected()
        # The launch file runs the simulator from the start (rtf 0). The command is given while it is paused, as the
        # other drive tests give theirs: commanded while running, the car stood still in 2 of 4 loaded runs (a lost
        # first command under investigation, docs/RELIABILITY.md), which this test is not about.
        call('/gazebo/pause_physics')
        odom.restart()
        command(0.2, 0.0)
        # Past the ramp (0.2 / 1.98 = 0.10 s) it goes 0.2 m/s: between any two messages of [t0 + 1, t0 + 3] the
        # distance over the time between their stamps (messages can be dropped on the way on a busy machine).
        t0 = sim_now()
        call('/gazebo/unpause_physics')
        msgs = [m for m in odom.until(t0 + 3.0) if t0 + 1.0 <= m.header.stamp.to_sec() <= t0 + 3.0]
        self.assertGreaterEqual(len(msgs), 2, 'odometry between sim times %.2f and %.2f s' % (t0 + 1.0, t0 + 3.0))
        a, b = msgs[0], msgs[-1]
        dt = (b.header.stamp - a.header.stamp).to_sec()
        self.assertGreater(dt, 1.0, 'odometry too sparse to time: %d messages' % len(msgs))
        self.assertAlmostEqual(math.dist(xy(a), xy(b)) / dt, 0.2, delta=0.005)

if __name__ == '__main__':
    rostest.rosrun('car', 'test_seed_launch', SeedLaunchTest)
