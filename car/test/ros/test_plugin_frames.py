#!/usr/bin/env python3
"""rostest (plugin_frames.test): the frames and positions the node writes for p3d and planar_move, as upstream.

- p3d: header.frame_id = tf::resolve(getParam("tf_prefix") in the plug-in's own namespace, frameName); the child
  frame as written. In /r1 (tf_prefix "pre"): "pre/world". In /r2, which has none, the global /tf_prefix ("glob")
  is not searched for: "world".
- planar_move: publishOdometry fills position x and y only, so the message's z is 0; the TF odom -> base carries
  the box's height (0.1 m: its link frame is at its centre).
"""
import unittest

import rospy
import rostest
import tf2_ros
from nav_msgs.msg import Odometry

from simtest import Recorder, lookup, sim_now, wait_for


class PluginFrames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('plugin_frames')
        topics = lambda: dict(rospy.get_published_topics())
        for name in ('/r1/truth', '/r2/truth', '/r1/odom'):
            wait_for('a publisher of %s' % name, lambda: name in topics())
        cls.truth = {r: Recorder('/%s/truth' % r) for r in ('r1', 'r2')}
        cls.odom = Recorder('/r1/odom')
        for rec in list(cls.truth.values()) + [cls.odom]:
            rec.wait_connected()
        cls.tf = tf2_ros.Buffer(cache_time=rospy.Duration(600))
        cls.tf_listener = tf2_ros.TransformListener(cls.tf)
        t = sim_now() + 1.0
        for rec in list(cls.truth.values()) + [cls.odom]:
            rec.until(t)

    def test_p3d_frame_takes_the_tf_prefix_of_its_namespace(self):
        m = self.truth['r1'].msgs[-1]
        self.assertEqual(m.header.frame_id, 'pre/world')
        self.assertEqual(m.child_frame_id, 'base')

    def test_p3d_does_not_search_tf_prefix_upwards(self):
        self.assertEqual(self.truth['r2'].msgs[-1].header.frame_id, 'world')

    def test_planar_move_odometry_message_has_no_height(self):
        self.assertEqual(self.odom.msgs[-1].pose.pose.position.z, 0.0)

    def test_planar_move_odometry_tf_has_the_height(self):
        m = self.odom.msgs[-1]
        t = lookup(self.tf, m.header.frame_id, m.child_frame_id, m.header.stamp)
        self.assertAlmostEqual(t.transform.translation.z, 0.1, delta=0.002)


if __name__ == '__main__':
    rostest.rosrun('car', 'plugin_frames', PluginFrames)
