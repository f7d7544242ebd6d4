#!/usr/bin/env python3
"""rostest: a four-wheel robot with diff_drive_controller (two wheels per side) and joint_state_controller loaded by
spawner from a YAML: drives the commanded circle and publishes joint_states and odom."""
import math
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from sensor_msgs.msg import JointState

from simtest import Recorder, call, command, fit_circle, wait_for, xy


class ControlRoverTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('control_rover_test')
        # the spawner has loaded and started both controllers
        def running():
            try:
                cs = call('/controller_manager/list_controllers', ListControllers).controller
            except rospy.ServiceException:
                return False
            return sorted((c.name, c.state) for c in cs) == [('joint_state_controller', 'running'),
                                                             ('rover_velocity_controller', 'running')]
        wait_for('both controllers running', running)
        cls.truth = Recorder('/ground_truth')
        cls.odom = Recorder('/rover_velocity_controller/odom')
        cls.joints = Recorder('/joint_states', JointState)
        cls.truth.wait_connected()
        cls.odom.wait_connected()
        cls.joints.wait_connected()

    def test_commanded_circle_has_radius_v_over_w(self):
        # v = 0.4 m/s, w = 0.5 rad/s: r = v / w = 0.8 m (the YAML's cmd_vel_timeout is long: one command holds)
        command(0.4, 0.5, '/rover_velocity_controller/cmd_vel')
        call('/gazebo/unpause_physics')
        t0, lap = 1.0, 2 * math.pi / 0.5
        msgs = self.truth.until(t0 + lap)
        points = [xy(m) for m in msgs if t0 <= m.header.stamp.to_sec() <= t0 + lap]
        _, radius = fit_circle(points)
        # tolerance 10 %: a skid-steered base slips sideways on its four wheels (measured in this test)
        self.assertAlmostEqual(radius, 0.8, delta=0.08)
        odom = self.odom.until(t0 + lap)
        self.assertEqual(odom[-1].header.frame_id, 'odom')
        self.assertEqual(odom[-1].child_frame_id, 'base_link')
        self.assertAlmostEqual(odom[-1].twist.twist.linear.x, 0.4, delta=0.02)
        js = self.joints.msgs[-1]
        self.assertEqual(sorted(js.name), ['front_left_joint', 'front_right_joint', 'rear_left_joint',
                                           'rear_right_joint'])
        # left wheels (0.4 - 0.5 * 0.3) / 0.1 = 2.5 rad/s
        self.assertAlmostEqual(js.velocity[js.name.index('front_left_joint')], 2.5, delta=0.1)


if __name__ == '__main__':
    rostest.rosrun('car', 'control_rover', ControlRoverTest)
