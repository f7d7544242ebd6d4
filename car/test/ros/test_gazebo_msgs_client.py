#!/usr/bin/env python3
"""rostest: code written against upstream gazebo_msgs runs unchanged on car (spawn, get/set model state, pause,
reset), the services carry upstream's types, and empty_world.launch / spawn_model behave as gazebo_ros's
(docs/COMPAT.md). The simulator starts paused, at real time, in test/data/worlds/exported_model.world."""
import os
import subprocess
import sys
import time
import unittest

import rospy
import rostest
import rosservice
from rosgraph_msgs.msg import Clock

# ---- the client, as a gazebo_ros user writes it ---------------------------------------------------------------
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import (DeleteModel, GetJointProperties, GetModelState, GetPhysicsProperties, GetWorldProperties,
                             SetModelState, SpawnModel)
from geometry_msgs.msg import Pose, Point, Quaternion
from std_srvs.srv import Empty

import simtest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

BOX_URDF = """<robot name="box">
  <link name="box_link">
    <inertial><mass value="2.0"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
    <visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual>
  </link>
</robot>"""


class GazeboClient:
    """What an RL environment or a test script typically does with gazebo_ros."""

    def __init__(self):
        for name in ('/gazebo/spawn_urdf_model', '/gazebo/get_model_state', '/gazebo/set_model_state',
                     '/gazebo/pause_physics', '/gazebo/unpause_physics', '/gazebo/reset_simulation'):
            rospy.wait_for_service(name, timeout=30)
        self.spawn_model = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        self.delete_model = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        self.get_model_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        self.set_model_state = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)
        self.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        self.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        self.reset_simulation = rospy.ServiceProxy('/gazebo/reset_simulation', Empty)
        self.world = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        self.physics = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)

    def spawn_box(self, name, x, y, z):
        pose = Pose(position=Point(x, y, z), orientation=Quaternion(0, 0, 0, 1))
        return self.spawn_model(model_name=name, model_xml=BOX_URDF, robot_namespace='/' + name,
                                initial_pose=pose, reference_frame='world')

    def teleport(self, name, x, y, z):
        state = ModelState()
        state.model_name = name
        state.pose.position.x, state.pose.position.y, state.pose.position.z = x, y, z
        state.pose.orientation.w = 1.0
        state.reference_frame = 'world'
        return self.set_model_state(model_state=state)

    def position(self, name):
        return self.get_model_state(model_name=name, relative_entity_name='world').pose.position

    def step_until(self, t):
        """Runs to sim time t and pauses there. car's ~pause_at (docs/COMPAT-dropins.md "Pause at") makes the
        simulator pause itself after the first step at or after t, however late this process would see t go by; a
        client of Gazebo itself would pause after seeing it on /clock, late by its own reaction time."""
        rospy.set_param('/gazebo/pause_at', t)
        self.unpause()
        # the bound is wall time against a hang; running out of it fails
        deadline = time.time() + 120
        while not (self.physics().pause and self.world().sim_time >= t):
            if time.time() > deadline:
                raise AssertionError('paused at sim time %.3f s: not within 120 s (at %.3f s)' % (t, self.world().sim_time))
            time.sleep(0.01)


def subscriber_connected(node, topic, prefix):
    """Whether NODE has a connection that sends TOPIC to a subscriber whose name starts with PREFIX (the node's
    getBusInfo, ROS's slave API: [id, peer, direction, transport, topic, connected, ...] per connection)."""
    import xmlrpc.client

    import rosgraph
    import rosnode
    uri = rosnode.get_api_uri(rosgraph.Master(rospy.get_name()), node)
    _, _, info = xmlrpc.client.ServerProxy(uri).getBusInfo(rospy.get_name())
    return any(c[2] == 'o' and c[4] == topic and c[1].startswith(prefix) and c[5] for c in info)


class GazeboMsgsClientTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('gazebo_msgs_client')
        cls.gz = GazeboClient()

    def setUp(self):
        self.gz.pause()
        for name in self.gz.world().model_names:
            if name in ('box', 'late', 'jfloat'):
                self.gz.delete_model(model_name=name)
        self.gz.reset_simulation()

    def test_services_have_upstream_types(self):
        for name, kind in (('/gazebo/spawn_urdf_model', 'gazebo_msgs/SpawnModel'),
                           ('/gazebo/get_model_state', 'gazebo_msgs/GetModelState'),
                           ('/gazebo/set_model_state', 'gazebo_msgs/SetModelState'),
                           ('/gazebo/apply_body_wrench', 'gazebo_msgs/ApplyBodyWrench'),
                           ('/gazebo/get_physics_properties', 'gazebo_msgs/GetPhysicsProperties')):
            self.assertEqual(rosservice.get_service_type(name), kind)

    def test_spawn_get_set_pause_reset(self):
        self.assertTrue(self.gz.spawn_box('box', 0.5, 0.0, 10.0).success)
        self.assertAlmostEqual(self.gz.position('box').z, 10.0, places=9)
        # falls freely while running (it would reach the ground after 1.4 s): z = 10 - g dt^2 n (n + 1) / 2 at
        # step n (symplectic Euler), g = 9.8, dt = 0.001; paused by ~pause_at after step 100 exactly
        self.gz.step_until(0.1)
        n = round(self.gz.world().sim_time / 0.001)
        self.assertEqual(n, 100)
        self.assertAlmostEqual(self.gz.position('box').z, 10.0 - 9.8 * 1e-6 * n * (n + 1) / 2, places=6)
        self.assertTrue(self.gz.teleport('box', 2.0, 0.0, 0.1).success)
        self.assertAlmostEqual(self.gz.position('box').x, 2.0, places=9)
        # paused: time stands still. The event, not a while: while paused car repeats the paused time on /clock at
        # 10 Hz of wall time (docs/COMPAT.md), so three /clock messages sent after this subscription connected span
        # 0.2 s or more of wall time, at rtf 1 as many ms of sim time had the world been running
        t = self.gz.world().sim_time
        clocks = []
        sub = simtest.receive_all(rospy.Subscriber('/clock', Clock, lambda m: clocks.append(m.clock.to_sec())))
        simtest.wait_publisher(sub)
        simtest.wait_for('three /clock messages while paused', lambda: len(clocks) >= 3)
        sub.unregister()
        self.assertEqual(set(clocks), {t})
        self.assertEqual(self.gz.world().sim_time, t)
        # reset_simulation: time 0, the box back where it was spawned
        self.gz.reset_simulation()
        self.assertEqual(self.gz.world().sim_time, 0.0)
        self.assertAlmostEqual(self.gz.position('box').z, 10.0, places=9)

    def test_unknown_model_says_so(self):
        res = self.gz.get_model_state(model_name='nothing', relative_entity_name='')
        self.assertFalse(res.success)
        self.assertIn('GetModelState: model [nothing] does not exist', res.status_message)

    # ---- empty_world.launch and spawn_model ------------------------------------------------------------------
    def test_exported_model_path_finds_the_world_model(self):
        # model://export_box is only in test/data/export_pkg/models, exported by that package's package.xml
        res = self.gz.get_model_state(model_name='export_box', relative_entity_name='')
        self.assertTrue(res.success, res.status_message)
        self.assertAlmostEqual(res.pose.position.x, 2.0, places=9)

    def test_pub_clock_frequency_sets_the_clock_step(self):
        # 50 Hz in sim time: successive /clock stamps 0.02 s apart
        stamps = []
        # every message (rospy's own sim-time /clock subscription would bound it at 1: simtest.receive_all)
        sub = simtest.receive_all(rospy.Subscriber('/clock', Clock, lambda m: stamps.append(m.clock.to_sec())))
        # connected before the run (a wall-time sleep here was a guess: a busy machine connects later)
        simtest.wait_publisher(sub)
        self.gz.step_until(0.5)
        paused_at = self.gz.world().sim_time
        sub.unregister()
        # every stamp while running is a whole number of 0.02 s periods, and most follow each other by one (while
        # paused, car repeats the paused time at 10 Hz of wall time, docs/COMPAT.md: that one is left out)
        running = sorted(set(s for s in stamps if 0.0 < s and abs(s - paused_at) > 1e-9))
        self.assertGreater(len(running), 5)
        self.assertEqual([s for s in running if abs(s * 50 - round(s * 50)) > 1e-9], [])
        steps = [round(b - a, 6) for a, b in zip(running, running[1:])]
        self.assertEqual(min(steps), 0.02)

    def test_spawn_model_J_sets_the_joint(self):
        with open(os.path.join(ROOT, 'test', 'data', 'floater.urdf')) as f:
            xml = f.read()
        out = subprocess.run([sys.executable, self.script(), '-urdf', '-stdin', '-model', 'jfloat', '-z', '5',
                              '-J', 'spin', '0.8'], input=xml, capture_output=True, text=True, timeout=120)
        self.assertEqual(out.returncode, 0, out.stderr)
        props = rospy.ServiceProxy('/gazebo/get_joint_properties', GetJointProperties)
        self.assertAlmostEqual(props('jfloat::spin').position[0], 0.8, places=12)

    def test_spawn_model_J_unknown_joint_fails(self):
        out = subprocess.run([sys.executable, self.script(), '-urdf', '-stdin', '-model', 'box', '-J', 'nope', '1'],
                             input=BOX_URDF, capture_output=True, text=True, timeout=120)
        self.assertEqual(out.returncode, 1)
        self.assertIn("no moving joint 'nope'", out.stderr + out.stdout)

    def test_spawn_model_stdin(self):
        xml = BOX_URDF
        out = subprocess.run([sys.executable, self.script(), '-urdf', '-stdin', '-model', 'box', '-z', '0.7'],
                             input=xml, capture_output=True, text=True, timeout=120)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertAlmostEqual(self.gz.position('box').z, 0.7, places=9)

    def test_spawn_model_empty_stdin_fails(self):
        out = subprocess.run([sys.executable, self.script(), '-urdf', '-stdin', '-model', 'box'],
                             input='', capture_output=True, text=True, timeout=120)
        self.assertEqual(out.returncode, 1)
        self.assertNotIn('box', self.gz.world().model_names)

    def test_spawn_model_wait(self):
        # waits for 'late' in /gazebo/model_states before spawning box
        proc = subprocess.Popen([sys.executable, self.script(), '-urdf', '-stdin', '-model', 'box', '-wait', 'late'],
                                stdin=subprocess.PIPE, text=True)
        proc.stdin.write(BOX_URDF)
        proc.stdin.close()
        # events, not a while: the simulator has connected to this spawn_model's /gazebo/model_states subscription
        # (its name: spawn_model_PID_..., rospy's anonymous name), and then sent it 1 s of sim time of model states
        # (100 Hz: 100 messages, none naming 'late'): still waiting, nothing spawned
        simtest.wait_for('/gazebo connected to spawn_model (pid %d) on /gazebo/model_states' % proc.pid,
                         lambda: proc.poll() is not None or subscriber_connected(
                             '/gazebo', '/gazebo/model_states', '/spawn_model_%d_' % proc.pid))
        self.assertIsNone(proc.poll())
        self.gz.step_until(self.gz.world().sim_time + 1.0)
        self.assertNotIn('box', self.gz.world().model_names)
        self.assertIsNone(proc.poll())
        self.gz.unpause()
        self.assertTrue(self.gz.spawn_box('late', 3.0, 3.0, 0.1).success)
        self.assertEqual(proc.wait(timeout=60), 0)
        self.gz.pause()
        self.assertIn('box', self.gz.world().model_names)

    @staticmethod
    def script():
        return simtest.car_program('spawn_model')


if __name__ == '__main__':
    rostest.rosrun('car', 'gazebo_msgs_client', GazeboMsgsClientTest)
