#!/usr/bin/env python3
"""rostest: Gazebo-style services under /gazebo, one behaviour per test, and two namespaced cars at once."""
import math
import time
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelState, ModelStates
from gazebo_msgs.srv import DeleteModel, GetModelState, GetWorldProperties, SetModelState, SpawnModel
from geometry_msgs.msg import Pose

import simtest
from simtest import Recorder, at_time, call, command


def pose(x, y, yaw=0.0):
    p = Pose()
    p.position.x, p.position.y = x, y
    p.orientation.z, p.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return p


class ServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_services')
        for s in ('spawn_urdf_model', 'delete_model', 'get_model_state', 'set_model_state', 'get_world_properties',
                  'reset_simulation', 'reset_world', 'pause_physics', 'unpause_physics'):
            rospy.wait_for_service('/gazebo/' + s, timeout=30)
        cls.spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        cls.delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        cls.get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.set = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)
        cls.props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        cls.xml = rospy.get_param('/robot_description')

    def setUp(self):
        call('/gazebo/pause_physics')
        for name in self.props().model_names:
            if name.startswith('car_'):
                self.delete(name)
        call('/gazebo/reset_simulation')

    def run_until(self, t):
        """Runs until the world's sim time has reached t [s], then pauses (waiting on sim time, not the machine)."""
        call('/gazebo/unpause_physics')
        simtest.wait_for('sim time %g' % t, lambda: self.props().sim_time >= t)
        call('/gazebo/pause_physics')

    def test_spawn_adds_the_model(self):
        res = self.spawn('car_a', self.xml, '', pose(1.0, 0.5), '')
        self.assertTrue(res.success, res.status_message)
        self.assertIn('car_a', self.props().model_names)
        p = self.get('car_a', '').pose.position
        self.assertAlmostEqual(p.x, 1.0, places=9)
        self.assertAlmostEqual(p.y, 0.5, places=9)

    def test_spawning_an_existing_name_fails_with_a_message(self):
        self.assertTrue(self.spawn('car_a', self.xml, '', pose(1, 0), '').success)
        res = self.spawn('car_a', self.xml, '', pose(2, 0), '')
        self.assertFalse(res.success)
        self.assertIn("model 'car_a' exists already", res.status_message)

    def test_spawning_a_broken_model_fails_with_the_reason(self):
        res = self.spawn('car_broken', '<robot name="x"><link name="a"></robot>', '', pose(0, 0), '')
        self.assertFalse(res.success)
        self.assertIn('car_broken:1: malformed XML', res.status_message)

    def test_delete_removes_the_model(self):
        self.spawn('car_a', self.xml, '', pose(1, 0), '')
        self.assertTrue(self.delete('car_a').success)
        self.assertNotIn('car_a', self.props().model_names)
        self.assertFalse(self.delete('car_a').success)

    def test_get_model_state_of_a_world_model(self):
        # unit_box_0 rests where the world's <state> puts it
        p = self.get('unit_box_0', 'world').pose.position
        self.assertAlmostEqual(p.x, -4.96407, delta=1e-3)
        self.assertAlmostEqual(p.y, -2.00353, delta=1e-3)

    def test_get_model_state_of_an_unknown_model_fails(self):
        res = self.get('nothing', '')
        self.assertFalse(res.success)
        self.assertIn('model [nothing] does not exist', res.status_message)

    def test_set_model_state_moves_a_box(self):
        state = ModelState(model_name='unit_box', pose=pose(0.0, 2.0))
        state.pose.position.z = 0.5
        self.assertTrue(self.set(state).success)
        p = self.get('unit_box', '').pose.position
        self.assertAlmostEqual(p.x, 0.0, places=9)
        self.assertAlmostEqual(p.y, 2.0, places=9)

    def test_set_model_state_moves_a_static_model_and_ignores_its_twist(self):
        # box_house is static: Gazebo 11 moves it (docs/COMPAT.md set_model_state); a static link takes no twist
        state = ModelState(model_name='box_house', pose=pose(1.0, -2.0, 0.5))
        state.twist.linear.x = 1.0
        state.twist.angular.z = 1.0
        res = self.set(state)
        self.assertTrue(res.success, res.status_message)
        self.run_until(0.05)
        got = self.get('box_house', '')
        self.assertAlmostEqual(got.pose.position.x, 1.0, places=9)
        self.assertAlmostEqual(got.pose.position.y, -2.0, places=9)
        self.assertAlmostEqual(got.pose.orientation.z, math.sin(0.25), places=9)
        self.assertEqual((got.twist.linear.x, got.twist.angular.z), (0.0, 0.0))

    def test_pause_stops_time_and_unpause_runs_it(self):
        t0 = self.props().sim_time
        time.sleep(0.3)
        self.assertEqual(self.props().sim_time, t0)
        self.run_until(t0 + 0.3)
        self.assertGreaterEqual(self.props().sim_time, t0 + 0.3)

    def test_reset_simulation_sets_time_to_zero(self):
        self.run_until(0.3)
        self.assertGreater(self.props().sim_time, 0.0)
        call('/gazebo/reset_simulation')
        self.assertEqual(self.props().sim_time, 0.0)

    def test_reset_world_puts_models_back_and_keeps_time(self):
        state = ModelState(model_name='unit_box', pose=pose(0.0, 2.0))
        state.pose.position.z = 0.5
        self.set(state)
        self.run_until(0.2)
        t = self.props().sim_time
        call('/gazebo/reset_world')
        self.assertAlmostEqual(self.get('unit_box', '').pose.position.x, -7.27142, delta=1e-3)
        self.assertEqual(self.props().sim_time, t)

    def test_model_states_lists_every_model(self):
        rec = Recorder('/gazebo/model_states', ModelStates)
        rec.wait_connected()
        self.run_until(0.3)
        simtest.wait_for('a model_states message', lambda: rec.msgs)
        self.assertIn('unit_cylinder_1', rec.msgs[-1].name)
        rec.sub.unregister()

    def test_two_namespaced_cars_drive_independently(self):
        # the seed's plug-ins say <robotNamespace>/</robotNamespace>, which the spawn namespace does not replace
        # (gazebo_ros adds it only where absent): the namespace-free form a multi-robot description uses
        import re
        xml = re.sub(r'<robotNamespace>[^<]*</robotNamespace>', '', self.xml)
        self.assertTrue(self.spawn('car_a', xml, 'a', pose(0.0, 1.0), '').success)
        self.assertTrue(self.spawn('car_b', xml, 'b', pose(0.0, -1.0), '').success)
        odom_a, odom_b = Recorder('/a/odom'), Recorder('/b/odom')
        odom_a.wait_connected()
        odom_b.wait_connected()
        command(0.5, 0.0, '/a/cmd_vel')
        command(0.0, 1.0, '/b/cmd_vel')
        call('/gazebo/unpause_physics')
        a, b = at_time(odom_a.until(2.0), 2.0), at_time(odom_b.until(2.0), 2.0)
        call('/gazebo/pause_physics')
        self.assertAlmostEqual(a.twist.twist.linear.x, 0.5, delta=0.01)   # a goes straight
        self.assertAlmostEqual(a.twist.twist.angular.z, 0.0, delta=0.01)
        self.assertAlmostEqual(b.twist.twist.linear.x, 0.0, delta=0.01)   # b turns on the spot
        self.assertAlmostEqual(b.twist.twist.angular.z, 1.0, delta=0.02)

if __name__ == '__main__':
    rostest.rosrun('car', 'test_services', ServicesTest)
