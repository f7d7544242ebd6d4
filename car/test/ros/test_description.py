#!/usr/bin/env python3
"""rostest: robot_description from launch/description.launch, checked through the core and /tf_static."""
import unittest

import rospy
import rostest
from tf2_msgs.msg import TFMessage

from car import _core


class DescriptionTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_description')
        cls.xml = rospy.get_param('/robot_description')

    def test_param_holds_the_nine_links(self):
        # as written (the core lumps fixed joints when it loads, as Gazebo does)
        import xml.etree.ElementTree as ET
        self.assertEqual(
            [l.get('name') for l in ET.fromstring(self.xml).findall('link')],
            ['base_footprint', 'base_link', 'left_wheel', 'right_wheel', 'front_wheel', 'back_wheel', 'camera',
             'support', 'laser'])

    def test_param_holds_the_three_plugins(self):
        model = _core.load_urdf_string(self.xml, 'robot_description')
        files = [p['filename'] for p in model['plugins']] + \
            [p['filename'] for s in model['sensors'] for p in s['plugins']]
        self.assertEqual(files, ['libgazebo_ros_diff_drive.so', 'libgazebo_ros_laser.so',
                                 'libgazebo_ros_openni_kinect.so'])

    def test_tf_static_places_the_laser_on_the_support(self):
        # laser2support: z = support_length/2 + laser_length/2 = 0.075 + 0.025
        found = {}
        deadline = rospy.Time.now() + rospy.Duration(30)
        while 'laser' not in found and rospy.Time.now() < deadline:
            msg = rospy.wait_for_message('/tf_static', TFMessage, timeout=30)
            for t in msg.transforms:
                found[t.child_frame_id] = t
        t = found['laser']
        self.assertEqual(t.header.frame_id, 'support')
        self.assertAlmostEqual(t.transform.translation.z, 0.1, places=9)


if __name__ == '__main__':
    rostest.rosrun('car', 'test_description', DescriptionTest)
