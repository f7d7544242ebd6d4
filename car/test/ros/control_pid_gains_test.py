#!/usr/bin/env python3
"""rostest: gazebo_ros_control/pid_gains from the parameter server, read when the arm is spawned. The shoulder's
position commands go through its PID (p 1000, d 50), so it sags by m g l / p as in Gazebo; the elbow, without gains,
is held by its motor."""
import unittest

import rospy
import rostest
from sensor_msgs.msg import JointState

from simtest import controller_states, Recorder, call, sim_now, wait_for


def states():
    return controller_states('/arm')


class ControlPidGainsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('control_pid_gains_test')
        wait_for('controllers running', lambda: states() == {'joint_state_controller': 'running',
                                                             'shoulder_hold': 'running',
                                                             'elbow_position_controller': 'running'})
        cls.joints = Recorder('/arm/joint_states', JointState)
        cls.joints.wait_connected()

    def test_shoulder_sags_by_its_pid_and_elbow_holds(self):
        # both commands 0 (the spawn pose). Link2 straight: the shoulder carries 1 kg at 0.5 m and 1 kg at 1.5 m,
        # 9.8 * 2.0 = 19.6 N m; p only in the steady state: e = 19.6 / 1000 = 0.0196 rad (a motor, as without
        # gains, holds 0 within 0.001). 5 s: settled (20 rad/s, damping ratio 0.5).
        call('/gazebo/unpause_physics')
        t = sim_now()
        m = self.joints.until(t + 5.0)[-1]
        self.assertAlmostEqual(m.position[m.name.index('shoulder')], 0.0196, delta=0.002)
        self.assertAlmostEqual(m.position[m.name.index('elbow')], 0.0, delta=0.002)


if __name__ == '__main__':
    rostest.rosrun('car', 'control_pid_gains', ControlPidGainsTest)
