#!/usr/bin/env python3
"""rostest hand_of_god_tf: car's hand_of_god kind pulls its link to the frame world -> hog_desired that another node
puts on /tf_static, and sends world -> hog_actual on /tf (upstream's GazeboRosHandOfGod::GazeboUpdate looks the
desired frame up every update and sends the actual one once it has it). The box is test/data/upstream_plugins/
hog_box.urdf (1 kg, kl = ka = 200, critically damped by the kind: cl = 2 sqrt(kl m)), spawned at (0, 0, 1), the target
0.5 m along x: the error falls as (1 + w t) e^(-w t) with w = sqrt(200) = 14.1 rad/s, below 1e-10 m after 2 s."""
import os
import threading
import time
import unittest

import rospkg
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped
from tf2_msgs.msg import TFMessage

from car.testing.sim import Sim

URDF = os.path.join(rospkg.RosPack().get_path('car'), 'test', 'data', 'upstream_plugins', 'hog_box.urdf')


class HandOfGodTf(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sim = Sim(robot=URDF, name='hog_box', pose=(0.0, 0.0, 0.0), rtf=0.0, use_existing_master=True)
        cls.sim.set_pose('hog_box', 0.0, 0.0, 1.0)
        cls.static = tf2_ros.StaticTransformBroadcaster()
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id = 'world', 'hog_desired'
        t.header.stamp = rospy.Time(0)
        t.transform.translation.x, t.transform.translation.z, t.transform.rotation.w = 0.5, 1.0, 1.0
        cls.static.sendTransform(t)
        # latched: the node's TF listener gets it once connected (wall time, paused: a hang bound only)
        deadline = time.monotonic() + 60.0
        while cls.static.pub_tf.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        cls.lock = threading.Lock()
        cls.actual = []

        def on_tf(msg):
            with cls.lock:
                cls.actual += [t for t in msg.transforms
                               if t.header.frame_id.lstrip('/') == 'world' and t.child_frame_id == 'hog_actual']
        cls.tf_sub = rospy.Subscriber('/tf', TFMessage, on_tf, queue_size=100000)
        cls.sim.run_for(2.0)
        cls.pose = cls.sim.pose('hog_box')
        # the node advertises /tf at its first transform: at rtf 0 the 2 s may pass before this subscriber is
        # connected; once it is (wall time, paused: a hang bound only), 0.1 s more of sim time
        deadline = time.monotonic() + 60.0
        while cls.tf_sub.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        cls.sim.run_for(0.1)

    @classmethod
    def tearDownClass(cls):
        cls.sim.close()

    def test_the_link_goes_to_the_desired_frame_from_tf_static(self):
        p = self.pose
        # 1e-4 m: the spring's residual (below 1e-10 m) and the solver's, far below the 0.5 m it moved
        self.assertAlmostEqual(p.x, 0.5, delta=1e-4)
        self.assertAlmostEqual(p.y, 0.0, delta=1e-4)
        self.assertAlmostEqual(p.z, 1.0, delta=1e-4)

    def test_the_actual_pose_goes_out_on_tf(self):
        with self.lock:
            actual = list(self.actual)
        self.assertTrue(actual, 'no world -> hog_actual on /tf')
        self.assertAlmostEqual(actual[-1].transform.translation.x, 0.5, delta=1e-4)


if __name__ == '__main__':
    rostest.rosrun('car', 'hand_of_god_tf', HandOfGodTf)
