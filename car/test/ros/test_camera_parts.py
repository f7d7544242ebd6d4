#!/usr/bin/env python3
"""rostest: the Kinect's depth image with nobody on its colour image or cloud (the renderer then makes depth alone),
and its colour image once subscribed, facing box_house's Wall_2 (values as in test_sensors); and a lazy plug-in
switched on by its subscriber's connect callback before the next step."""
import unittest

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Image

import simtest
from simtest import Recorder, call

WALL2_X = 4.44857 - 0.075  # Wall_2's inner face [m]
Y = 0.059964               # [m] the car's y in front of the wall, as in test_sensors


class CameraPartsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_camera_parts')
        cls.depth = Recorder('/camera/depth/image_raw', Image)
        cls.depth.wait_connected()

    def run_at(self, x, until, recorders):
        """From t = 0 with the car at (x, Y) facing +x, records until sim time `until`."""
        call('/gazebo/pause_physics')
        call('/gazebo/reset_simulation')
        state = ModelState(model_name='mycar')
        state.pose.position.x, state.pose.position.y, state.pose.orientation.w = x, Y, 1.0
        self.assertTrue(call('/gazebo/set_model_state', SetModelState, state).success)
        for r in recorders:
            r.restart()
        simtest.wait_for('the clock back at 0', lambda: rospy.get_rostime().to_sec() == 0.0)
        call('/gazebo/unpause_physics')
        for r in recorders:
            r.until(until)
        call('/gazebo/pause_physics')

    def test_depth_image_alone_reads_the_wall(self):
        self.run_at(0.0, 0.5, [self.depth])
        m = self.depth.msgs[-1]
        self.assertEqual((m.encoding, m.height, m.width), ('32FC1', 480, 640))
        d = np.frombuffer(m.data, np.float32).reshape(m.height, m.width)
        self.assertAlmostEqual(float(d[240, 320]), WALL2_X, delta=1e-3)

    def test_image_comes_once_subscribed_beside_the_depth(self):
        image = Recorder('/camera/rgb/image_raw', Image)
        image.wait_connected()
        self.run_at(0.0, 0.5, [self.depth, image])
        m = image.msgs[-1]
        self.assertEqual((m.encoding, m.height, m.width), ('rgb8', 480, 640))
        px = np.frombuffer(m.data, np.uint8).reshape(m.height, m.width, 3)[240, 320]
        # Gazebo/Bricks (0.62 0.32 0.24) in the ambient light 0.4 (the face is turned away from the sun)
        self.assertEqual([int(c) for c in px], [round(0.62 * 0.4 * 255), round(0.32 * 0.4 * 255),
                                                round(0.24 * 0.4 * 255)])
        d = np.frombuffer(self.depth.msgs[-1].data, np.float32).reshape(480, 640)
        self.assertAlmostEqual(float(d[240, 320]), WALL2_X, delta=1e-3)

    def test_a_lazy_plugin_is_on_from_the_first_step_after_its_subscriber_came(self):
        """car's ground truth, a p3d at ~model_states_rate (100 Hz) that runs only while subscribed, subscribed while
        paused at t = 0: its first message is its grid's first, t = 0.01 s (`(t - last) < 1/rate` is false from
        t = 0.01 on). The node switched it on from roscpp's connect callback before the first step; a node that
        looked at its publishers every 50 steps sent the first at 0.06 s."""
        truth = Recorder('/gazebo/ground_truth/mycar', Odometry)
        truth.wait_connected()
        self.run_at(0.0, 0.1, [truth])
        self.assertEqual(truth.msgs[0].header.stamp, rospy.Time(0, 10000000))


if __name__ == '__main__':
    rostest.rosrun('car', 'camera_parts', CameraPartsTest)
