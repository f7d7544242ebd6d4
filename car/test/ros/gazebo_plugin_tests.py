#!/usr/bin/env python3
"""rostest: a model plug-in built against car's Gazebo 11 API (test/gazebo/plugins/model_push.cc) runs inside the
node (docs/PLUGINS.md): spawned 5 m up on a box, it sets the box's linear velocity to (0.3, 0, 0) at every
WorldUpdateBegin, so after every step the box moves at 0.3 m/s along x and falls at only g dt = 0.0098 m/s (the
plug-in zeroes the vertical speed each step, as Gazebo's SetLinearVel does)."""
import os
import subprocess
import unittest

import rospkg
import rospy
import rostest
from gazebo_msgs.srv import GetModelState

from simtest import call, sim_now, wait_for

URDF = os.path.join(rospkg.RosPack().get_path('car'), 'test', 'data', 'gazebo_push_box.urdf')


class GazeboPlugin(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_gazebo_plugin')
        cls.spawned = subprocess.run(['rosrun', 'car', 'spawn_model', '-urdf', '-file', URDF, '-model', 'push_box',
                                      '-z', '5'], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     universal_newlines=True, timeout=120)

    def test_the_plugin_pushes_the_box_at_its_velocity(self):
        self.assertEqual(self.spawned.returncode, 0, self.spawned.stdout)
        t0 = sim_now()
        wait_for('0.5 s of sim time', lambda: sim_now() > t0 + 0.5)
        s = call('/gazebo/get_model_state', GetModelState, 'push_box', '')
        self.assertTrue(s.success, s.status_message)
        # still in the air, so no friction has touched its speed (it lands after 510 s of sim time)
        self.assertGreater(s.pose.position.z, 1.0, 'the box landed before it was read')
        self.assertAlmostEqual(s.twist.linear.x, 0.3, delta=1e-9)
        self.assertAlmostEqual(s.twist.linear.y, 0.0, delta=1e-9)
        self.assertAlmostEqual(s.twist.linear.z, -9.8 * 0.001, delta=1e-9)
        self.assertGreater(s.pose.position.x, 0.3 * 0.5)


if __name__ == '__main__':
    rostest.rosrun('car', 'gazebo_plugin', GazeboPlugin)
