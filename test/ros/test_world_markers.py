#!/usr/bin/env python3
"""rostest: the latched world markers of box_house, and a marker following its model when it moves."""
import math
import time
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from visualization_msgs.msg import MarkerArray

from simtest import call


class WorldMarkersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_world_markers')
        cls.latest = []
        rospy.Subscriber('/world_markers', MarkerArray, cls.latest.append)

    def wait_for(self, predicate, timeout=30):
        deadline = time.time() + timeout
        while time.time() < deadline:
            if self.latest and predicate(self.latest[-1]):
                return self.latest[-1]
            time.sleep(0.05)
        self.fail('no matching MarkerArray within %d s' % timeout)

    def test_latched_markers_of_every_visual(self):
        arr = self.wait_for(lambda a: True)
        self.assertEqual(len(arr.markers), 11)  # ground, 4 walls, 3 boxes, 3 cylinders
        self.assertEqual({m.header.frame_id for m in arr.markers}, {'odom'})

    def test_marker_follows_a_moved_box(self):
        self.wait_for(lambda a: True)
        state = ModelState(model_name='unit_box')
        state.pose.position.x, state.pose.position.y, state.pose.position.z = 1.5, 2.5, 0.5
        state.pose.orientation.w = 1.0
        self.assertTrue(call('/gazebo/set_model_state', SetModelState, state).success)
        call('/gazebo/unpause_physics')

        def moved(arr):
            box = [m for m in arr.markers if m.ns == 'unit_box'][0]
            return math.hypot(box.pose.position.x - 1.5, box.pose.position.y - 2.5) < 0.01

        self.wait_for(moved)
        call('/gazebo/pause_physics')


if __name__ == '__main__':
    rostest.rosrun('car', 'test_world_markers', WorldMarkersTest)
