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
        # The band, from the contact model (docs/COMPAT-physics.md "Surface keys": mu1 along fdir1 = the axle, mu2
        # along the rolling direction, each row limited on its own since mu1 != mu2). Wheels of radius R = 0.1 m at
        # (+-a, +-b), a = 0.15, b = 0.3; mass 12 kg, so N = 12 g / 4 = 29.4 N per wheel.
        # - Along: the turn needs a difference of 1.7 N between the sides' forces, far below mu2 N = 29 N: the wheels
        #   do not slip along, and the base moves at V = (u_l + u_r) / 2, W = (u_r - u_l) / (2 b), u = R * wheel
        #   speed. For the command: u = 0.4 -+ 0.5 * 0.3, V = 0.4, W = 0.5 exactly.
        # - Across: the circle needs m V W = 2.4 N inwards; a contact sliding sideways gives mu1 N = 1.47 N against
        #   its slip. If all four slid, the front pair's and the rear pair's forces (5.9 N together) would push the
        #   base inwards faster than the circle: in a steady turn the front contacts do not slide, only the rear
        #   ones (2.94 N, enough). So base_link (mid-axle, x = 0) moves sideways at between 0 and a W, and its
        #   path's radius is sqrt(V^2 + v_y^2) / W in [V / W, sqrt(V^2 + (a W)^2) / W] = [0.8, 0.8139] m.
        # The iterative solver (10 Gauss-Seidel sweeps a step) leaves each wheel's speed off its command by about
        # 0.1 %; the band is taken from the wheel speeds /joint_states reports over the lap, not the command.
        speeds = {}
        for js in self.joints.until(t0 + lap):
            if t0 <= js.header.stamp.to_sec() <= t0 + lap:
                for n, q in zip(js.name, js.velocity):
                    speeds.setdefault(n, []).append(q)
        mean = {n: sum(q) / len(q) for n, q in speeds.items()}
        u_l = 0.1 * (mean['front_left_joint'] + mean['rear_left_joint']) / 2
        u_r = 0.1 * (mean['front_right_joint'] + mean['rear_right_joint']) / 2
        V, W = (u_l + u_r) / 2, (u_r - u_l) / (2 * 0.3)
        low, high = V / W, math.hypot(V, 0.15 * W) / W
        self.assertTrue(low <= radius <= high, 'radius %.5f m outside [%.5f, %.5f] m' % (radius, low, high))
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
