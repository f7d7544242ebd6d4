#!/usr/bin/env python3
"""rostest: a Noetic-dialect (xacro 1.14) robot expanded into robot_description and spawned."""
import math
import time
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetWorldProperties

from car import _core
from simtest import Recorder, call

MODEL = 'robot14'


class Xacro14Test(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_xacro14')
        cls.xml = rospy.get_param('/robot_description')
        cls.model = _core.load_urdf_string(cls.xml, 'robot_description')

    def test_links_carry_the_prefix_given_as_xacro_arg(self):
        # prefix:=arm_ on the command line, read with xacro.arg('prefix')
        self.assertEqual([l['name'] for l in self.model['links']], ['arm_base_link', 'arm_mast'])

    def test_joint_limits_come_from_yaml_degrees(self):
        # robot14.yaml: min/max_position !degrees -90 / 90, max_velocity !degrees 180
        j = [j for j in self.model['joints'] if j['name'] == 'arm_pan'][0]['limits']
        self.assertAlmostEqual(j['lower'], -math.pi / 2, places=12)
        self.assertAlmostEqual(j['upper'], math.pi / 2, places=12)
        self.assertAlmostEqual(j['velocity'], math.pi, places=12)

    def test_spawned_box_rests_on_its_yaml_height(self):
        # base size_z !millimeters 200: spawned at z 0.3, the box comes to rest at z = 0.2 / 2 = 0.1 m
        deadline = time.time() + 60
        while MODEL not in call('/gazebo/get_world_properties', GetWorldProperties).model_names:
            self.assertLess(time.time(), deadline, 'robot14 was not spawned')
            time.sleep(0.1)
        truth = Recorder('/gazebo/ground_truth/' + MODEL)
        truth.wait_connected()
        call('/gazebo/unpause_physics')
        msgs = truth.until(2.0)
        call('/gazebo/pause_physics')
        z = msgs[-1].pose.pose.position.z
        self.assertAlmostEqual(z, 0.1, delta=0.005)


if __name__ == '__main__':
    rostest.rosrun('car', 'test_xacro14', Xacro14Test)
