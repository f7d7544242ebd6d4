#!/usr/bin/env python3
"""rostest: the tutorial's 三.1 launch file drives the car from /cmd_vel, as in the tutorial."""
import math
import time
import unittest

import rospy
import rostest

from simtest import Recorder, at_time, command, xy


class SeedLaunchTest(unittest.TestCase):
    def test_cmd_vel_moves_the_car_and_odom_follows(self):
        rospy.init_node('test_seed_launch')
        odom = Recorder('/odom')
        odom.wait_connected()
        command(0.2, 0.0)
        # from when the car starts moving, past the ramp (0.2 / 1.8 = 0.11 s), two seconds at 0.2 m/s
        deadline = time.time() + 60
        while time.time() < deadline:
            with odom.lock:
                moving = next((m for m in odom.msgs if m.twist.twist.linear.x > 0.01), None)
            if moving:
                break
            time.sleep(0.05)
        t0 = moving.header.stamp.to_sec()
        msgs = odom.until(t0 + 3.0)
        d = math.dist(xy(at_time(msgs, t0 + 1.0)), xy(at_time(msgs, t0 + 3.0)))
        self.assertAlmostEqual(d, 0.4, delta=0.01)


if __name__ == '__main__':
    rostest.rosrun('car', 'test_seed_launch', SeedLaunchTest)
