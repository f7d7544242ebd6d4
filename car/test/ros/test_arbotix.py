#!/usr/bin/env python3
"""rostest: the tutorial's rostopic pub makes arbotix_driver's odom trace a circle of radius v / w."""
import math
import os
import subprocess
import threading
import time
import unittest

import numpy as np

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState

from simtest import car_program, fit_circle


class ArbotixTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_arbotix')
        cls.odom, cls.joints = [], []
        rospy.Subscriber('/odom', Odometry, cls.odom.append, queue_size=None)
        rospy.Subscriber('/driver/joint_states', JointState, cls.joints.append, queue_size=None)
        cls.tf = tf2_ros.Buffer(rospy.Duration(60))
        tf2_ros.TransformListener(cls.tf)
        cls.pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1)
        rospy.wait_for_message('/odom', Odometry, timeout=60)

    def drive(self, v, w, seconds):
        """`rostopic pub -r 10 /cmd_vel ...` for a while; returns the odom messages of that time."""
        msg = Twist()
        msg.linear.x, msg.angular.z = v, w
        start = len(self.odom)
        t_end = time.time() + seconds
        while time.time() < t_end:
            self.pub.publish(msg)
            time.sleep(0.1)
        return self.odom[start:]

    def test_1_accel_limit_sets_the_time_to_full_speed(self):
        msgs = self.drive(1.0, 0.0, 2.0)
        # the speed ramps in 10 Hz steps of accel_limit * dt: fit the ramp, so the step size does not limit
        # the measurement; accel_limit 1.0 m/s^2 takes the car from rest to 1 m/s in 1 s
        ramp = [(m.header.stamp.to_sec(), m.twist.twist.linear.x) for m in msgs
                if 0.0 < m.twist.twist.linear.x < 1.0 - 1e-9]
        self.assertGreaterEqual(len(ramp), 5)
        slope, _ = np.polyfit([t for t, _ in ramp], [v for _, v in ramp], 1)
        self.assertAlmostEqual(1.0 / slope, 1.0, delta=0.1)
        self.assertAlmostEqual(msgs[-1].twist.twist.linear.x, 1.0, places=9)

    def test_2_seed_command_traces_a_circle_of_radius_v_over_w(self):
        msgs = self.drive(1.0, 1.0, 2 * math.pi + 2.0)
        reached = [m for m in msgs if abs(m.twist.twist.angular.z - 1.0) < 1e-9 and abs(m.twist.twist.linear.x - 1.0) < 1e-9]
        self.assertGreater(len(reached), 50)
        _, r = fit_circle([(m.pose.pose.position.x, m.pose.pose.position.y) for m in reached])
        self.assertAlmostEqual(r, 1.0, delta=0.02)
        # TF agrees with odom
        m = reached[-1]
        tf = self.tf.lookup_transform('odom', 'base_footprint', m.header.stamp, rospy.Duration(5))
        self.assertAlmostEqual(tf.transform.translation.x, m.pose.pose.position.x, places=9)
        self.assertAlmostEqual(tf.transform.translation.y, m.pose.pose.position.y, places=9)
        # wheel joints advance at their surface speed / r: (v -+ w b / 2) / 0.0325
        a, b = self.joints[-20], self.joints[-1]
        dt = (b.header.stamp - a.header.stamp).to_sec()
        left = (b.position[0] - a.position[0]) / dt
        right = (b.position[1] - a.position[1]) / dt
        self.assertAlmostEqual(left, 0.9 / 0.0325, delta=0.5)
        self.assertAlmostEqual(right, 1.1 / 0.0325, delta=0.5)

    def test_3_bad_config_exits_nonzero_naming_the_key(self):
        rospy.set_param('/bad_driver/controllers', {'base_controller': {'type': 'diff_controller', 'ticks_meter': 2000}})
        rospy.set_param('/bad_driver/sim', True)
        r = subprocess.run([car_program('arbotix_driver'), '__name:=bad_driver'], capture_output=True,
                           text=True, timeout=60)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn('~controllers/base_controller/base_width is required', r.stderr + r.stdout)


if __name__ == '__main__':
    rostest.rosrun('car', 'test_arbotix', ArbotixTest)
