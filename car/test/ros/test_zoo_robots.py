#!/usr/bin/env python3
"""rostest: a zoo robot (test/data/zoo/, chosen by the first argument) spawned with spawn_model the way gazebo_ros
users do. Checks: the robot is not refused, what the import lumped or anchored is named in the log, and per robot
a value worked out by hand. Surface physics (friction drag, joint limits) is tested elsewhere."""
import subprocess
import sys
import time
import unittest

import rosgraph
import rospy
import rostest
from gazebo_msgs.srv import GetModelState
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import Image

from simtest import Recorder, call, wait_publisher

# spawn_model arguments per robot: each rests on (or is fixed above) the ground plane at z = 0
SPAWN = {
    'sensor_bot': ['-z', '0.05'],   # 0.1 m box centred on base_link
    'mesh_bot': ['-z', '0.2'],      # dropped from 0.2 m
    'caster_bot': ['-z', '0.05'],   # wheel radius 0.05 m
    'arm': ['-z', '0.3'],           # the world link at z = 0.3 m, base 0.5 m above it
}


def wait_sim_time(t, timeout=120.0):
    """Waits (wall time) until sim time reaches t [s]."""
    deadline = time.time() + timeout
    while rospy.get_time() < t:
        if time.time() > deadline:
            raise AssertionError('sim time did not reach %.3f s' % t)
        time.sleep(0.01)


class ZooRobot(unittest.TestCase):
    robot = None

    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_zoo_' + cls.robot)
        cls.log = Recorder('/rosout', Log)  # every node publishes here; rostest starts no rosout aggregator
        cls.log.wait_connected()
        # /rosout has several publishers: wait for the simulator's own (the first to connect may be another node's,
        # and a line logged before the simulator's connection is lost)
        wait_publisher(cls.log.sub)
        cls.spawn = subprocess.run(['rosrun', 'car', 'spawn_model', '-urdf', '-param', 'robot_description',
                                    '-model', cls.robot] + SPAWN[cls.robot],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                                   timeout=120)

    def logged(self, text, timeout=120.0):
        """The simulator's log line that contains text (waits for it to arrive through /rosout)."""
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.log.lock:
                for m in self.log.msgs:
                    if text in m.msg:
                        return m.msg
            time.sleep(0.05)
        with self.log.lock:
            seen = [m.msg for m in self.log.msgs]
        raise AssertionError('no log line with %r; seen: %r' % (text, seen))

    def test_spawned_not_refused(self):
        self.assertEqual(self.spawn.returncode, 0, self.spawn.stdout)
        self.logged("car: spawned '%s'" % self.robot)


class SensorBot(ZooRobot):
    robot = 'sensor_bot'

    def test_massless_sensor_links_lumped_in_the_log(self):
        self.logged("car: sensor_bot: link 'camera_link' lumped into 'base_link' (fixed joint 'camera_joint'): "
                    "1 collision, 1 visual, 1 sensor, mass 0 kg")
        self.logged("car: sensor_bot: link 'imu_link' lumped into 'base_link' (fixed joint 'imu_joint'): "
                    "0 collisions, 0 visuals, 0 sensors, mass 0 kg")

    def test_camera_on_lumped_link_publishes(self):
        # spawned from the root: robotNamespace "/" + cameraName cam + imageTopicName image_raw
        rec = Recorder('/cam/image_raw', Image)
        rec.wait_connected()
        msgs = rec.until(0.0)
        # the sensor block's 32 x 24 image, stamped in the plug-in's frameName (a TF frame from
        # robot_state_publisher, kept although the link is lumped)
        self.assertEqual((msgs[-1].width, msgs[-1].height), (32, 24))
        self.assertEqual(msgs[-1].header.frame_id, 'camera_link')


class MeshBot(ZooRobot):
    robot = 'mesh_bot'

    def test_lumped_mesh_link_in_the_log(self):
        self.logged("car: mesh_bot: link 'top_link' lumped into 'base_link' (fixed joint 'top_joint'): "
                    "1 collision, 0 visuals, 0 sensors, mass 0 kg")

    def test_rests_at_the_height_its_mesh_gives(self):
        self.assertEqual(self.spawn.returncode, 0, self.spawn.stdout)
        wait_sim_time(2.0)  # dropped 0.15 m (0.17 s), settled by 2 s
        s = call('/gazebo/get_model_state', GetModelState, 'mesh_bot', '')
        self.assertTrue(s.success, s.status_message)
        # box.stl is 0.1 m high and centred on base_link: its bottom is 0.05 m below the origin, so base_link
        # rests at z = 0.05 m, plus Bullet's 0.0005 m convex-hull margin = 0.0505 m (+-2 mm)
        self.assertAlmostEqual(s.pose.position.z, 0.0505, delta=0.002)


class CasterBot(ZooRobot):
    robot = 'caster_bot'

    def test_caster_lumped_in_the_log(self):
        self.logged("car: caster_bot: link 'caster_link' lumped into 'base_link' (fixed joint 'caster_joint'): "
                    "1 collision, 0 visuals, 0 sensors, mass 0.05 kg")

    def test_drive_listens_in_its_explicit_namespace(self):
        # <robotNamespace>/caster_bot</robotNamespace> is kept: /caster_bot/cmd_vel (commandTopic default cmd_vel)
        deadline = time.time() + 30
        while time.time() < deadline:
            subs = dict(rosgraph.Master('/test').getSystemState()[1])
            if '/caster_bot/cmd_vel' in subs:
                break
            time.sleep(0.1)
        self.assertIn('/gazebo', subs.get('/caster_bot/cmd_vel', []))


class Arm(ZooRobot):
    robot = 'arm'

    def test_world_anchor_in_the_log(self):
        self.logged("car: arm: fixed joint 'world_fix' joins link 'base' to the world: the model is anchored")

    def test_stays_where_it_was_fixed(self):
        # the model's root is the `world` link at the spawn pose, z = 0.3 m; anchored it stays there (free, it would
        # have fallen 0.3 m + the base's 0.5 m in 1 s: 4.9 m of free fall)
        rec = Recorder('/gazebo/ground_truth/arm', Odometry)
        rec.wait_connected()
        msgs = rec.until(1.0)
        self.assertAlmostEqual(msgs[-1].pose.pose.position.z, 0.3, delta=1e-9)
        self.assertAlmostEqual(msgs[-1].twist.twist.linear.z, 0.0, delta=1e-9)


CASES = {c.robot: c for c in (SensorBot, MeshBot, CasterBot, Arm)}

if __name__ == '__main__':
    robot = rospy.myargv(sys.argv)[1]
    rostest.rosrun('car', 'zoo_' + robot, CASES[robot])
