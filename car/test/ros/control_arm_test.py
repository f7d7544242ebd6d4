#!/usr/bin/env python3
"""rostest: a world-anchored two-joint arm follows a FollowJointTrajectory goal, and an effort PID position
controller holds the shoulder against gravity with the hand-derived steady error m g l / p."""
import math
import unittest

import actionlib
import rospy
import rostest
from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal, FollowJointTrajectoryResult
from controller_manager_msgs.srv import SwitchController
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint

from simtest import controller_states, Recorder, call, sim_now, wait_for


def states():
    return controller_states('/arm')


class ControlArmTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('control_arm_test')
        wait_for('controllers loaded', lambda: states() == {'joint_state_controller': 'running',
                                                            'arm_controller': 'running',
                                                            'shoulder_position_controller': 'stopped',
                                                            'elbow_position_controller': 'stopped'})
        cls.joints = Recorder('/arm/joint_states', JointState)
        cls.joints.wait_connected()

    def position(self, name, t):
        msgs = self.joints.until(t)
        m = min(msgs, key=lambda m: abs(m.header.stamp.to_sec() - t))
        return m.position[m.name.index(name)]

    def test_1_trajectory_goal_reached_at_its_time(self):
        client = actionlib.SimpleActionClient('/arm/arm_controller/follow_joint_trajectory',
                                              FollowJointTrajectoryAction)
        wait_for('action server', lambda: client.wait_for_server(rospy.Duration(0.1)))
        goal = FollowJointTrajectoryGoal()
        goal.trajectory.joint_names = ['shoulder', 'elbow']
        # linear from (0, 0) to (0.5, -0.5) rad in 2 s (positions only): at 1 s half way
        goal.trajectory.points = [JointTrajectoryPoint(positions=[0.5, -0.5], time_from_start=rospy.Duration(2.0))]
        client.send_goal(goal)
        call('/gazebo/unpause_physics')
        # the result message, not only a terminal status (the status topic can say SUCCEEDED before it arrives)
        wait_for('goal result', lambda: client.get_result() is not None)
        self.assertEqual(client.get_result().error_code, FollowJointTrajectoryResult.SUCCESSFUL)
        # tolerance 0.02 rad (the goal tolerance in the YAML), at t >= 2 s (the goal can finish before the first
        # joint_states message of that time has reached this test: wait for it)
        end = self.joints.until(2.0)[-1]
        self.assertAlmostEqual(end.position[end.name.index('shoulder')], 0.5, delta=0.02)
        self.assertAlmostEqual(end.position[end.name.index('elbow')], -0.5, delta=0.02)

    def test_2_position_controller_holds_against_gravity(self):
        # the trajectory controller hands both joints to the stopped ones (one strict switch): the elbow holds
        # -0.5 rad (position interface), the shoulder's PID (p 1000) holds its set point 0.5 rad less the sag
        # e = torque / p. Torque about the shoulder at q1 = 0.5 + e, q2 = -0.5 (link2 horizontal):
        # 9.8 * (1 kg * 0.5 m * cos q1 + 1 kg * (1 m * cos q1 + 0.5 m * cos(q1 + q2))) = 17.67 N m -> e = 0.0177 rad
        ok = call('/arm/controller_manager/switch_controller', SwitchController,
                  ['shoulder_position_controller', 'elbow_position_controller'], ['arm_controller'], 2, False,
                  0.0).ok
        self.assertTrue(ok)
        self.assertEqual(states()['arm_controller'], 'stopped')
        t = sim_now()
        self.assertAlmostEqual(self.position('shoulder', t + 5.0), 0.5 + 0.0177, delta=0.002)
        self.assertAlmostEqual(self.position('elbow', t + 5.0), -0.5, delta=0.002)

if __name__ == '__main__':
    rostest.rosrun('car', 'control_arm', ControlArmTest)
