#!/usr/bin/env python3
"""rostest: controllers started while the world is paused hold the joints where spawn_model -J put them, once the
world plays (each controller reads the joint at its first update, as ros_control's starting())."""
import math
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetJointProperties
from sensor_msgs.msg import JointState

from simtest import controller_states, Recorder, call, sim_now, wait_for


def states():
    return controller_states('/arm')


def joint_position(name):
    try:
        r = call('/gazebo/get_joint_properties', GetJointProperties, name)
    except rospy.ServiceException:
        return None
    return r.position[0] if r.success and r.position else None


class ControlPausedTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('control_paused_test')
        wait_for('three controllers running', lambda: states() == {'joint_state_controller': 'running',
                                                                    'shoulder_position_controller': 'running',
                                                                    'elbow_trajectory_controller': 'running'})
        # spawn_model sets -J after the spawn: play only once both joints are there
        wait_for('the -J positions (shoulder 0.3, elbow -0.4 rad)',
                 lambda: abs((joint_position('shoulder') or 9) - 0.3) < 1e-9 and abs((joint_position('elbow') or 9) + 0.4) < 1e-9)
        cls.joints = Recorder('/arm/joint_states', JointState)
        cls.joints.wait_connected()
        call('/gazebo/unpause_physics')
        cls.t = sim_now()

    def at(self, name, t):
        m = self.joints.until(t)[-1]
        return m.position[m.name.index(name)]

    def test_effort_pid_position_controller_holds_the_spawn_position_less_its_sag(self):
        # effort_controllers/JointPositionController, p 1000 N m/rad, i 0: set point 0.3 rad (the joint at its first
        # update), steady error e = tau / p with tau the gravity torque about the shoulder at q1 = 0.3 + e,
        # q2 = -0.4 (links of 1 kg with their centres 0.5 m out, link1 1 m long):
        # tau = 9.8 (0.5 cos q1 + 1.0 cos q1 + 0.5 cos(q1 + q2)) = 18.84 N m -> e = 0.0188 rad (iterated twice).
        # A controller that took 0 as its set point would sag to about 0.02 rad instead.
        self.assertAlmostEqual(self.at('shoulder', self.t + 5.0), 0.3 + 0.0188, delta=0.002)

    def test_trajectory_controller_holds_the_spawn_position(self):
        # position_controllers/JointTrajectoryController: holds the position at its first update, -0.4 rad,
        # through the position interface (no gains; the same 0.002 rad band as control_arm's elbow)
        self.assertAlmostEqual(self.at('elbow', self.t + 5.0), -0.4, delta=0.002)


if __name__ == '__main__':
    rostest.rosrun('car', 'control_paused', ControlPausedTest)
