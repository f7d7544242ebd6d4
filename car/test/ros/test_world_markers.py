#!/usr/bin/env python3
"""rostest: the latched world markers of box_house, and a marker following its model when it moves; car's rospy
nodes that read the time only as they start (world_markers, the static transform) leave /clock."""
import math
import time
import unittest

import rosgraph
import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from visualization_msgs.msg import MarkerArray

import simtest
from simtest import call


class WorldMarkersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_world_markers')
        cls.latest = []
        cls.sub = None

    def wait_for(self, predicate, timeout=30):
        if WorldMarkersTest.sub is None:
            WorldMarkersTest.sub = rospy.Subscriber('/world_markers', MarkerArray, self.latest.append)
        deadline = time.time() + timeout
        while time.time() < deadline:
            if self.latest and predicate(self.latest[-1]):
                return self.latest[-1]
            time.sleep(0.05)
        self.fail('no matching MarkerArray within %d s' % timeout)

    def test_0_model_states_followed_only_while_the_markers_have_a_subscriber(self):
        master = rosgraph.Master(rospy.get_name())

        def nodes(side, topic):
            """The nodes on one side of topic (0: publishers, 1: subscribers), from the master."""
            return dict(master.getSystemState()[side]).get(topic, [])

        simtest.wait_for('world_markers up', lambda: '/world_markers' in nodes(0, '/world_markers'))
        self.assertNotIn('/world_markers', nodes(1, '/gazebo/model_states'))
        sub = rospy.Subscriber('/world_markers', MarkerArray, lambda m: None)
        simtest.wait_for('world_markers following model_states',
                         lambda: '/world_markers' in nodes(1, '/gazebo/model_states'))
        sub.unregister()
        simtest.wait_for('world_markers leaving model_states',
                         lambda: '/world_markers' not in nodes(1, '/gazebo/model_states'))

    def graph(self, side, topic):
        """The nodes on one side of topic (0: publishers, 1: subscribers), from the master."""
        return dict(rosgraph.Master(rospy.get_name()).getSystemState()[side]).get(topic, [])

    def leaves_clock(self, node, topic):
        """node, once it publishes topic, is no longer among /clock's subscribers."""
        simtest.wait_for('%s publishing %s' % (node, topic), lambda: node in self.graph(0, topic))
        simtest.wait_for('%s off /clock' % node, lambda: node not in self.graph(1, '/clock'))
        # the list is the master's: this test's own node takes /clock
        self.assertIn(rospy.get_name(), self.graph(1, '/clock'))

    def test_world_markers_leaves_clock(self):
        self.leaves_clock('/world_markers', '/world_markers')

    def test_static_transform_leaves_clock(self):
        self.leaves_clock('/support_depth_tf', '/tf_static')

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

    def test_marker_follows_a_moved_static_model(self):
        # a static model moves too (docs/COMPAT.md set_model_state): box_house's four walls shift 1 m along x
        walls = [m.pose.position for m in self.wait_for(lambda a: True).markers if m.ns == 'box_house']
        self.assertEqual(len(walls), 4)
        state = ModelState(model_name='box_house')
        state.pose.position.x, state.pose.position.y = -1.97643 + 1.0, 0.05996
        state.pose.orientation.w = 1.0
        self.assertTrue(call('/gazebo/set_model_state', SetModelState, state).success)
        call('/gazebo/unpause_physics')

        def moved(arr):
            now = [m.pose.position for m in arr.markers if m.ns == 'box_house']
            return all(abs(n.x - w.x - 1.0) < 0.01 and abs(n.y - w.y) < 0.01 for n, w in zip(now, walls))

        self.wait_for(moved)
        call('/gazebo/pause_physics')


if __name__ == '__main__':
    rostest.rosrun('car', 'test_world_markers', WorldMarkersTest)
