#!/usr/bin/env python3
"""rostest (zoo19_dropped_link.test): flap_bot (test/data/zoo19/flap_bot.urdf) spawned with spawn_model. Gazebo
drops the massless link 'flap' on a revolute joint with 'flap_tip' below it, lumps the massless fixed link
'marker' into base_link, and spawns the rest (docs/COMPAT-spawn.md). Each is named in the simulator's log."""
import subprocess
import time
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetModelProperties, GetModelState
from rosgraph_msgs.msg import Log

from simtest import Recorder, call, sim_now, wait_for, wait_publisher


class DroppedLink(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('zoo19_dropped_link')
        cls.log = Recorder('/rosout', Log)  # rostest starts no rosout aggregator: every node publishes here
        # the simulator's own /rosout connection (what it logs before that is lost)
        wait_publisher(cls.log.sub)
        cls.spawn = subprocess.run(['rosrun', 'car', 'spawn_model', '-urdf', '-param', 'robot_description',
                                    '-model', 'flap_bot', '-z', '0.15'],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                   timeout=120)

    def logged(self, text, level):
        """The log message of LEVEL (rosgraph_msgs/Log) that contains text."""
        def find():
            with self.log.lock:
                return next((m for m in self.log.msgs if text in m.msg and m.level == level), None)
        return wait_for('a log line with %r' % text, find, 30.0)

    def test_spawned_not_refused(self):
        self.assertEqual(self.spawn.returncode, 0, self.spawn.stdout)
        self.logged("car: spawned 'flap_bot'", Log.INFO)

    def test_dropped_link_and_its_subtree_named_in_a_warning(self):
        m = self.logged("link 'flap' has no mass", Log.WARN)
        self.assertIn("revolute joint 'flap_joint'", m.msg)
        self.assertIn('(flap_tip)', m.msg)

    def test_lumped_link_named_in_the_log(self):
        m = self.logged("link 'marker' lumped into 'base_link'", Log.INFO)
        self.assertIn("fixed joint 'marker_joint'", m.msg)

    def test_only_base_link_is_simulated(self):
        props = call('/gazebo/get_model_properties', GetModelProperties, 'flap_bot')
        self.assertTrue(props.success, props.status_message)
        self.assertEqual(list(props.body_names), ['base_link'])
        self.assertEqual(list(props.joint_names), [])

    def test_rest_of_the_robot_rests_on_the_ground(self):
        # the 0.2 m cube dropped from 0.15 m: base_link at z = 0.1 m once settled (2 s of sim time)
        t0 = sim_now()
        wait_for('sim time %.1f' % (t0 + 2.0), lambda: sim_now() >= t0 + 2.0)
        s = call('/gazebo/get_model_state', GetModelState, 'flap_bot', '')
        self.assertTrue(s.success, s.status_message)
        self.assertAlmostEqual(s.pose.position.z, 0.1, delta=0.002)


if __name__ == '__main__':
    rostest.rosrun('car', 'zoo19_dropped_link', DroppedLink)
