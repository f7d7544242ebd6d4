#!/usr/bin/env python3
"""rostest: the /gazebo services with bad requests (NaN poses, unknown names, a taken name, delete while
driving) answer success false with a message and leave the node running; a robot that blows up pauses the node,
which publishes no NaN."""
import math
import os
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Pose
from rosgraph_msgs.msg import Log

from gazebo_services import (DeleteModel, GetModelState, GetWorldProperties, ModelState, ModelStates,
                             SetModelState, SpawnModel)
from simtest import call, command, wait_publisher

BAD = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'data', 'bad')


def pose(x=0.0, y=0.0, z=0.0):
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation.w = 1.0
    return p


class BadServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_bad_services')
        for s in ('spawn_urdf_model', 'delete_model', 'get_model_state', 'set_model_state', 'get_world_properties'):
            rospy.wait_for_service('/gazebo/' + s, timeout=60)
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

    def wait_sim_time(self, t, timeout=120.0):
        """Waits (wall time, bounded) until sim time reaches t [s]."""
        deadline = time.time() + timeout
        while self.props().sim_time < t:
            self.assertLess(time.time(), deadline, 'sim time stuck at %g' % self.props().sim_time)
            time.sleep(0.02)

    def test_spawn_at_a_nan_pose_is_refused(self):
        res = self.spawn('car_nan', self.xml, '', pose(float('nan')), '')
        self.assertFalse(res.success)
        self.assertIn("the pose to spawn 'car_nan' at is not finite", res.status_message)
        self.assertNotIn('car_nan', self.props().model_names)

    def test_spawn_of_a_taken_name_is_refused(self):
        self.assertTrue(self.spawn('car_a', self.xml, '', pose(), '').success)
        res = self.spawn('car_a', self.xml, '', pose(1.0), '')
        self.assertFalse(res.success)
        self.assertIn("model 'car_a' exists already", res.status_message)

    def test_set_state_to_nan_is_refused_and_the_model_stays(self):
        self.assertTrue(self.spawn('car_a', self.xml, '', pose(1.0, 2.0), '').success)
        s = ModelState()
        s.model_name = 'car_a'
        s.pose = pose(0.0, float('inf'))
        res = self.set(s)
        self.assertFalse(res.success)
        self.assertIn('SetModelState: pose and twist must be finite numbers', res.status_message)
        p = self.get('car_a', '').pose.position
        self.assertAlmostEqual(p.x, 1.0, places=9)
        self.assertAlmostEqual(p.y, 2.0, places=9)

    def test_unknown_names_are_refused(self):
        # upstream's wording for get_model_state
        self.assertIn('GetModelState: model [ghost] does not exist', self.get('ghost', '').status_message)
        s = ModelState()
        s.model_name = 'ghost'
        s.pose = pose()
        res = self.set(s)
        self.assertFalse(res.success)
        self.assertIn('SetModelState: model [ghost] does not exist', res.status_message)
        res = self.delete('ghost')
        self.assertFalse(res.success)
        self.assertIn("no model named 'ghost'", res.status_message)

    def test_delete_while_driving_keeps_the_world_running(self):
        self.assertTrue(self.spawn('car_a', self.xml, '', pose(), '').success)
        pub = command(1.0, 1.0)
        call('/gazebo/unpause_physics')
        self.wait_sim_time(0.5)
        res = self.delete('car_a')
        self.assertTrue(res.success, res.status_message)
        t = self.props().sim_time
        self.wait_sim_time(t + 0.5)  # the world steps on, with cmd_vel still latched for a robot that is gone
        self.assertNotIn('car_a', self.props().model_names)
        pub.unregister()

    def test_a_robot_that_blows_up_pauses_the_node_without_publishing_nan(self):
        # a 1e300 kg wheel: loads with a warning; the solver turns its state non-finite within the first steps
        with open(os.path.join(BAD, 'mass_huge.urdf'), encoding='utf-8') as f:
            xml = f.read()
        states, logs = [], []
        sub = rospy.Subscriber('/gazebo/model_states', ModelStates, states.append, queue_size=None)
        log_sub = rospy.Subscriber('/rosout', Log, logs.append, queue_size=None)
        # the simulator's own /rosout connection first: the error comes a few steps after unpausing
        wait_publisher(log_sub)
        self.assertTrue(self.spawn('car_huge', xml, '', pose(z=0.05), '').success)
        call('/gazebo/unpause_physics')
        # the node logs the body and pauses itself
        deadline = time.time() + 300
        while not [m for m in logs if 'is not finite; the world stops here' in m.msg]:
            self.assertLess(time.time(), deadline, 'no error logged')
            time.sleep(0.05)
        err = [m for m in logs if 'is not finite; the world stops here' in m.msg][0]
        self.assertEqual(err.level, Log.ERROR)
        self.assertIn('car_huge/', err.msg)
        self.assertIn('physics paused', err.msg)
        t0 = self.props().sim_time
        self.assertGreater(t0, 0.0)
        time.sleep(0.5)
        self.assertEqual(self.props().sim_time, t0)  # paused
        sub.unregister()
        log_sub.unregister()
        for m in states:
            for p in m.pose:
                self.assertTrue(all(math.isfinite(v) for v in (p.position.x, p.position.y, p.position.z)), m)
        # the node still answers, and runs on once the model is gone
        self.assertTrue(self.delete('car_huge').success)
        call('/gazebo/unpause_physics')
        self.wait_sim_time(t0 + 0.1)


if __name__ == '__main__':
    rostest.rosrun('car', 'bad_services', BadServicesTest)
