#!/usr/bin/env python3
"""rostest: Gazebo world plug-ins in the node (test/data/worlds/world_plugins.world). The events plug-in calls
World::SetPaused(true) in its first WorldUpdateBegin: the node, which paces by the same flag, stops after that one
step (sim time 0.001 s) and /gazebo/get_physics_properties says paused. The factory plug-in's three models were
inserted at the end of that step and are the node's models. unpause_physics runs the world again."""
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetModelState, GetPhysicsProperties, GetWorldProperties

from simtest import call, sim_now, wait_for


class GazeboWorldPlugin(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_gazebo_world_plugin')

    def test_1_the_plugin_paused_the_node_after_one_step(self):
        props = wait_for('the node paused by the plug-in',
                         lambda: (lambda p: p if p.pause else None)(
                             call('/gazebo/get_physics_properties', GetPhysicsProperties)))
        self.assertTrue(props.pause)
        self.assertAlmostEqual(sim_now(), 0.001, delta=1e-9)

    def test_2_the_factory_models_are_the_nodes(self):
        names = call('/gazebo/get_world_properties', GetWorldProperties).model_names
        for m in ('box', 'unique_sphere', 'cylinder'):
            self.assertIn(m, names)
        # the message's pose (1, -2, 0) replaces the file's (0, 0, 3); no gravity, paused: where it was put
        s = call('/gazebo/get_model_state', GetModelState, 'cylinder', '')
        self.assertTrue(s.success, s.status_message)
        self.assertAlmostEqual(s.pose.position.x, 1.0, delta=1e-9)
        self.assertAlmostEqual(s.pose.position.y, -2.0, delta=1e-9)

    def test_3_unpause_runs_the_world_again(self):
        call('/gazebo/unpause_physics')
        wait_for('0.1 s of sim time after unpause_physics', lambda: sim_now() > 0.1)


if __name__ == '__main__':
    rostest.rosrun('car', 'gazebo_world_plugin', GazeboWorldPlugin)
