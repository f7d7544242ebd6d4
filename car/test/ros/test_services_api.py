#!/usr/bin/env python3
"""rostest: gazebo_ros's API services and topics (docs/COMPAT.md), one behaviour per test. The floater
(test/data/floater.urdf: cube 6 kg + fixed foot 2 kg, com 0.3 m below the cube's origin, Izz 1.01 together; a
spinner 1 kg, Izz 0.5, on a free joint 2 m above) floats at z = 5 in zero gravity, so only what a test applies
acts on it. dt = 0.001 s (box_house). A refused request must leave the world as it was."""
import math
import time
import unittest

import rospy
import rostest
from gazebo_msgs.msg import LinkState, LinkStates, ModelState
from gazebo_msgs.srv import (ApplyBodyWrench, ApplyJointEffort, BodyRequest, DeleteModel, GetJointProperties,
                             GetLinkProperties, GetLinkState, GetModelProperties, GetModelState,
                             GetPhysicsProperties, GetWorldProperties, JointRequest, SetLinkState,
                             SetModelConfiguration, SetModelState, SetPhysicsProperties, SpawnModel)
from geometry_msgs.msg import Point, Pose, Twist, Vector3, Wrench

from simtest import call

DT = 0.001
MASS = 9.0
# The robot's common com is 0.4 / 9 m below the cube's origin ((8 (-0.3) + 1 (2)) / 9); the cube's body com is
# 0.3 m below it. A world-frame wrench's reference_point is a lever arm from the body's com (gazebo_ros), so this
# one puts the force's line through the common com: the robot only translates.
THROUGH_COM = Point(0.0, 0.0, 0.3 - 0.4 / 9)


def rotate(q, v):
    """v rotated by the unit quaternion q (geometry_msgs)."""
    x, y, z, w = q.x, q.y, q.z, q.w
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz, v[2] + w * tz + x * ty - y * tx)


def pose(x, y, z):
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation.w = 1.0
    return p


def proxy(name, srv):
    rospy.wait_for_service('/gazebo/' + name, timeout=30)
    return rospy.ServiceProxy('/gazebo/' + name, srv)


class ServicesApiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_services_api')
        cls.spawn = proxy('spawn_urdf_model', SpawnModel)
        cls.delete = proxy('delete_model', DeleteModel)
        cls.model_state = proxy('get_model_state', GetModelState)
        cls.set_model_state = proxy('set_model_state', SetModelState)
        cls.world = proxy('get_world_properties', GetWorldProperties)
        cls.link_state = proxy('get_link_state', GetLinkState)
        cls.set_link_state = proxy('set_link_state', SetLinkState)
        cls.link_props = proxy('get_link_properties', GetLinkProperties)
        cls.model_props = proxy('get_model_properties', GetModelProperties)
        cls.joint_props = proxy('get_joint_properties', GetJointProperties)
        cls.configure = proxy('set_model_configuration', SetModelConfiguration)
        cls.wrench = proxy('apply_body_wrench', ApplyBodyWrench)
        cls.effort = proxy('apply_joint_effort', ApplyJointEffort)
        cls.clear_wrenches = proxy('clear_body_wrenches', BodyRequest)
        cls.clear_efforts = proxy('clear_joint_forces', JointRequest)
        cls.get_physics = proxy('get_physics_properties', GetPhysicsProperties)
        cls.set_physics = proxy('set_physics_properties', SetPhysicsProperties)
        cls.xml = rospy.get_param('/floater_description')

    def setUp(self):
        call('/gazebo/pause_physics')
        if 'f' in self.world().model_names:
            self.delete('f')
        call('/gazebo/reset_simulation')
        self.gravity(0.0)
        self.assertTrue(self.spawn('f', self.xml, '', pose(0.0, 0.0, 5.0), '').success)

    def gravity(self, gz):
        p = self.get_physics()
        res = self.set_physics(p.time_step, p.max_update_rate, Vector3(0.0, 0.0, gz), p.ode_config)
        self.assertTrue(res.success, res.status_message)

    def run_until(self, t):
        """Runs until sim time t [s] has passed, then pauses."""
        call('/gazebo/unpause_physics')
        # the bound is wall time against a hang; running out of it fails (a "nothing moved" check must not pass on a
        # simulator that never stepped)
        deadline = time.time() + 120
        while self.world().sim_time < t:
            if time.time() > deadline:
                raise AssertionError('sim time %.3f s not reached within 120 s (at %.3f s)' % (t, self.world().sim_time))
            time.sleep(0.01)
        call('/gazebo/pause_physics')

    def twist(self, name='f'):
        return self.model_state(name, '').twist

    def momentum(self):
        """Linear momentum [kg m/s] of the floater from its links: the cube's body (8 kg, com 0.3 m below the
        cube's origin) and the spinner (1 kg at its origin)."""
        cube = self.link_state('f::cube', '').link_state
        spin = self.link_state('f::spinner', '').link_state
        r = rotate(cube.pose.orientation, (0.0, 0.0, -0.3))
        w, v = cube.twist.angular, cube.twist.linear
        wxr = (w.y * r[2] - w.z * r[1], w.z * r[0] - w.x * r[2], w.x * r[1] - w.y * r[0])
        return tuple(8.0 * (a + b) + 1.0 * c for a, b, c in zip((v.x, v.y, v.z), wxr,
                                                                 (spin.twist.linear.x, spin.twist.linear.y,
                                                                  spin.twist.linear.z)))

    # ---- link state ---------------------------------------------------------------------------------------
    def test_root_link_state_is_the_model_state(self):
        self.set_model_state(ModelState('f', pose(1.0, 2.0, 5.0), Twist(), ''))
        p = self.link_state('f::cube', '').link_state.pose.position
        for got, want in zip((p.x, p.y, p.z), (1.0, 2.0, 5.0)):
            self.assertAlmostEqual(got, want, places=9)

    def test_link_state_relative_to_another_link(self):
        # the spinner's joint is 2 m above the cube
        res = self.link_state('spinner', 'f::cube')
        self.assertTrue(res.success, res.status_message)
        self.assertAlmostEqual(res.link_state.pose.position.z, 2.0, places=9)
        self.assertEqual(res.link_state.reference_frame, 'f::cube')

    def test_unknown_link_is_refused(self):
        res = self.link_state('f::wheel', '')
        self.assertFalse(res.success)
        self.assertIn("model 'f' has no link 'wheel'", res.status_message)

    def test_unknown_reference_frame_is_refused(self):
        res = self.link_state('f::cube', 'nowhere')
        self.assertFalse(res.success)
        self.assertIn('[nowhere]', res.status_message)

    def test_set_link_state_moves_the_model_rigidly(self):
        res = self.set_link_state(LinkState('f::spinner', pose(1.0, 1.0, 4.0), Twist(), 'world'))
        self.assertTrue(res.success, res.status_message)
        p = self.model_state('f', '').pose.position
        for got, want in zip((p.x, p.y, p.z), (1.0, 1.0, 2.0)):
            self.assertAlmostEqual(got, want, places=9)

    def test_set_link_state_with_nan_is_refused_and_nothing_moves(self):
        res = self.set_link_state(LinkState('f::spinner', pose(float('nan'), 1.0, 4.0), Twist(), ''))
        self.assertFalse(res.success)
        self.assertIn('finite', res.status_message)
        self.assertAlmostEqual(self.model_state('f', '').pose.position.z, 5.0, places=9)

    def test_set_model_state_with_nan_is_refused(self):
        res = self.set_model_state(ModelState('f', pose(0.0, float('inf'), 1.0), Twist(), ''))
        self.assertFalse(res.success)
        self.assertAlmostEqual(self.model_state('f', '').pose.position.z, 5.0, places=9)

    def test_set_model_state_in_a_reference_frame(self):
        # 1 m along x and 3 m above unit_box's frame; read back relative to it
        res = self.set_model_state(ModelState('f', pose(1.0, 0.0, 3.0), Twist(), 'unit_box'))
        self.assertTrue(res.success, res.status_message)
        rel = self.model_state('f', 'unit_box').pose.position
        for got, want in zip((rel.x, rel.y, rel.z), (1.0, 0.0, 3.0)):
            self.assertAlmostEqual(got, want, places=9)

    def test_set_link_state_topic(self):
        pub = rospy.Publisher('/gazebo/set_link_state', LinkState, queue_size=None, latch=True)
        pub.publish(LinkState('f::cube', pose(-3.0, 0.0, 5.0), Twist(), ''))
        deadline = time.time() + 30
        while self.model_state('f', '').pose.position.x > -2.9 and time.time() < deadline:
            time.sleep(0.05)
        self.assertAlmostEqual(self.model_state('f', '').pose.position.x, -3.0, places=9)
        pub.unregister()

    def test_set_model_state_topic(self):
        pub = rospy.Publisher('/gazebo/set_model_state', ModelState, queue_size=None, latch=True)
        pub.publish(ModelState('f', pose(0.0, 3.0, 5.0), Twist(), ''))
        deadline = time.time() + 30
        while self.model_state('f', '').pose.position.y < 2.9 and time.time() < deadline:
            time.sleep(0.05)
        self.assertAlmostEqual(self.model_state('f', '').pose.position.y, 3.0, places=9)
        pub.unregister()

    # ---- properties -----------------------------------------------------------------------------------------
    def test_link_properties_of_the_merged_body(self):
        res = self.link_props('f::cube')
        self.assertTrue(res.success, res.status_message)
        # cube 6 kg at 0 + foot 2 kg at z = -1.2: 8 kg, com z = -0.3, Izz = 1 + 0.01
        self.assertAlmostEqual(res.mass, 8.0)
        self.assertAlmostEqual(res.com.position.z, -0.3, places=12)
        self.assertAlmostEqual(res.izz, 1.01, places=12)

    def test_link_properties_of_an_unknown_link(self):
        res = self.link_props('nothing_here')
        self.assertFalse(res.success)
        self.assertIn('GetLinkProperties: link not found', res.status_message)

    def test_model_properties(self):
        res = self.model_props('f')
        self.assertEqual(res.body_names, ['cube', 'spinner'])
        self.assertEqual(res.joint_names, ['spin'])
        self.assertFalse(res.is_static)
        self.assertFalse(self.model_props('nobody').success)

    def test_joint_properties(self):
        res = self.joint_props('spin')
        self.assertEqual(res.type, GetJointProperties._response_class.CONTINUOUS)
        self.assertEqual(list(res.damping), [0.25])
        self.assertEqual(list(res.position), [0.0])
        self.assertFalse(self.joint_props('f::foot_joint').success)

    def test_set_model_configuration(self):
        res = self.configure('f', '', ['spin'], [0.7])
        self.assertTrue(res.success, res.status_message)
        self.assertAlmostEqual(self.joint_props('spin').position[0], 0.7, places=12)

    def test_bad_model_configuration_changes_nothing(self):
        self.assertFalse(self.configure('f', '', ['spin'], [0.7, 0.1]).success)
        res = self.configure('f', '', ['spin', 'nope'], [0.7, 0.1])
        self.assertFalse(res.success)
        self.assertIn("no moving joint 'nope'", res.status_message)
        self.assertFalse(self.configure('ghost', '', ['spin'], [0.7]).success)
        self.assertEqual(self.joint_props('spin').position[0], 0.0)

    # ---- wrenches and efforts -------------------------------------------------------------------------------
    def test_wrench_for_half_a_second(self):
        # 4.5 N along x through the common com on steps starting at t0 ... t0 + 0.5 s: 501 steps; v = F n dt / m
        res = self.wrench('f::cube', '', THROUGH_COM, Wrench(force=Vector3(4.5, 0, 0)), rospy.Time(0),
                          rospy.Duration(0.5))
        self.assertTrue(res.success, res.status_message)
        self.run_until(0.6)
        self.assertAlmostEqual(self.twist().linear.x, 4.5 * 501 * DT / MASS, places=9)

    def test_wrench_in_a_rotated_frame(self):
        # unit_box turned 0.6 rad about z; 9 N along its x for one step acts along its x in the world (fix)
        yaw = 0.6
        box = pose(-7.27142, 3.09748, 0.5)
        box.orientation.z, box.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        self.assertTrue(self.set_model_state(ModelState('unit_box', box, Twist(), '')).success)
        res = self.wrench('f::cube', 'unit_box', Point(), Wrench(force=Vector3(9.0, 0, 0)), rospy.Time(0),
                          rospy.Duration(0))
        self.assertTrue(res.success, res.status_message)
        self.run_until(0.01)
        # momentum F dt along the box's x. The force acts 8 m from the com (at the box's origin): the robot also
        # turns fast, and the integrator's rotation error shows in the momentum read back (2e-6 of 7.4e-3).
        p = self.momentum()
        self.assertAlmostEqual(p[0], 9.0 * DT * math.cos(yaw), delta=2e-6)
        self.assertAlmostEqual(p[1], 9.0 * DT * math.sin(yaw), delta=2e-6)

    def test_wrench_on_an_unknown_body_is_refused(self):
        res = self.wrench('f::ghost', '', Point(), Wrench(force=Vector3(1, 0, 0)), rospy.Time(0), rospy.Duration(1))
        self.assertFalse(res.success)
        self.assertIn('ApplyBodyWrench: body does not exist', res.status_message)

    def test_wrench_on_a_static_link_succeeds_and_moves_nothing(self):
        # upstream pushes the job; ODELink::AddForce has no body for a static link
        before = self.model_state('box_house', '').pose
        res = self.wrench('box_house::Wall_1', '', Point(), Wrench(force=Vector3(100, 0, 0)), rospy.Time(0),
                          rospy.Duration(1))
        self.assertTrue(res.success, res.status_message)
        self.assertEqual(res.status_message, '')
        self.run_until(0.05)
        self.assertEqual(self.model_state('box_house', '').pose, before)

    def test_nan_wrench_is_refused_and_nothing_moves(self):
        res = self.wrench('f::cube', '', Point(), Wrench(force=Vector3(float('nan'), 0, 0)), rospy.Time(0),
                          rospy.Duration(1))
        self.assertFalse(res.success)
        self.run_until(0.05)
        self.assertEqual(self.twist().linear.x, 0.0)

    def test_cleared_wrench_stops_pushing(self):
        self.wrench('f::cube', '', THROUGH_COM, Wrench(force=Vector3(9.0, 0, 0)), rospy.Time(0), rospy.Duration(-1))
        self.run_until(0.05)
        self.clear_wrenches('f::cube')
        v = self.twist().linear.x
        self.assertGreater(v, 0.0)
        self.run_until(0.1)
        self.assertEqual(self.twist().linear.x, v)

    def test_joint_effort_keeps_angular_momentum(self):
        res = self.effort('spin', 1.0, rospy.Time(0), rospy.Duration(0.099))
        self.assertTrue(res.success, res.status_message)
        self.run_until(0.2)
        rate = self.joint_props('spin').rate[0]
        w_cube = self.twist().angular.z
        self.assertGreater(rate, 0.0)
        # I_cube w_cube + I_spinner (w_cube + rate) = 0
        self.assertAlmostEqual(1.01 * w_cube + 0.5 * (w_cube + rate), 0.0, places=9)

    def test_effort_on_an_unknown_joint_is_refused(self):
        res = self.effort('f::ghost', 1.0, rospy.Time(0), rospy.Duration(1))
        self.assertFalse(res.success)
        self.assertIn('ApplyJointEffort: joint not found', res.status_message)

    def test_cleared_effort_stops(self):
        self.effort('spin', 1.0, rospy.Time(0), rospy.Duration(-1))
        self.clear_efforts('spin')
        self.run_until(0.05)
        self.assertEqual(self.joint_props('spin').rate[0], 0.0)

    # ---- physics --------------------------------------------------------------------------------------------
    def test_physics_properties(self):
        p = self.get_physics()
        self.assertTrue(p.success)
        self.assertAlmostEqual(p.time_step, DT)
        self.assertTrue(p.pause)
        self.assertEqual(p.max_update_rate, 1000.0)  # rtf 1 (services_api.test): 1000 steps of 1 ms per second
        self.assertEqual(p.ode_config.sor_pgs_iters, 10)

    def test_gravity_through_set_physics_properties(self):
        self.gravity(-2.0)
        t0 = self.world().sim_time
        self.run_until(0.05)
        t = self.world().sim_time - t0
        self.assertAlmostEqual(self.twist().linear.z, -2.0 * t, places=9)

    def test_another_time_step_is_refused(self):
        p = self.get_physics()
        res = self.set_physics(0.002, p.max_update_rate, Vector3(0, 0, -9.8), p.ode_config)
        self.assertFalse(res.success)
        self.assertIn('0.001', res.status_message)
        self.assertEqual(self.get_physics().gravity.z, 0.0)

    # ---- topics ---------------------------------------------------------------------------------------------
    def test_link_states_topic(self):
        got = []
        sub = rospy.Subscriber('/gazebo/link_states', LinkStates, got.append)
        call('/gazebo/unpause_physics')
        deadline = time.time() + 30
        while not got and time.time() < deadline:
            time.sleep(0.05)
        call('/gazebo/pause_physics')
        sub.unregister()
        msg = got[-1]
        self.assertIn('f::cube', msg.name)
        self.assertIn('f::spinner', msg.name)
        self.assertIn('unit_box::link', msg.name)
        spinner = msg.pose[msg.name.index('f::spinner')].position
        self.assertAlmostEqual(spinner.z, 7.0, places=6)


if __name__ == '__main__':
    rostest.rosrun('car', 'services_api', ServicesApiTest)
