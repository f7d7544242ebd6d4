#!/usr/bin/env python3
"""rostest: libgazebo_ros_range.so and velodyne_simulator's plug-in through ROS topics, in a square room whose
walls' inner faces are x, y = +-3 m (test/data/ray_room.world), against values worked out from its geometry."""
import math
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField, Range

from simtest import Recorder, call



class RaySensorsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('ray_sensors_test')
        cls.sonar = Recorder('/sonar', Range)
        cls.sonar_slow = Recorder('/sonar_slow', Range)
        cls.velodyne = Recorder('/velodyne_points', PointCloud2)
        cls.left = Recorder('/stereo/left/image_raw', Image)
        cls.right = Recorder('/stereo/right/image_raw', Image)
        cls.right_info = Recorder('/stereo/right/camera_info', CameraInfo)
        for r in (cls.sonar, cls.sonar_slow, cls.velodyne, cls.left, cls.right, cls.right_info):
            r.wait_connected()
        call('/gazebo/unpause_physics')
        cls.sonar_msgs = cls.sonar.until(1.0)
        cls.sonar_slow_msgs = cls.sonar_slow.until(1.0)
        cls.velodyne_msgs = cls.velodyne.until(1.0)
        cls.left_msgs = cls.left.until(1.0)
        cls.right_msgs = cls.right.until(1.0)
        cls.right_info_msgs = cls.right_info.until(1.0)

    # The sonar sits 0.1 m ahead of the cube's centre (x = 0.1 m); its middle ray meets the wall x = 3 at
    # 2.9 m, every other ray of its +-0.15 rad cone further (the downward ones meet the floor at
    # 0.5 / sin 0.15 = 3.35 m).
    def test_range_is_the_distance_to_the_wall_in_its_cone(self):
        m = self.sonar_msgs[-1]
        self.assertEqual(m.header.frame_id, 'sonar_link')
        self.assertAlmostEqual(m.range, 2.9, delta=3e-3)
        self.assertEqual(m.radiation_type, Range.INFRARED)
        self.assertAlmostEqual(m.field_of_view, 0.3, places=6)
        self.assertAlmostEqual(m.min_range, 0.02, places=6)
        self.assertAlmostEqual(m.max_range, 5.0, places=6)

    # sonar_slow is the same 10 Hz sensor (updates every 0.1 s of sim time) with updateRate 4: gazebo_ros_range sends
    # at an update t when t - last >= 0.25 s, last starting at 0, so at 0.3, 0.6, 0.9 s and never at 0 or 0.1 (docs/
    # COMPAT-sensors.md "Throttled publishers"). A publisher queue of 1 at rtf 0 may drop one on a busy machine, so
    # every stamp that came is one of those, each once and in order.
    def test_range_update_rate_waits_a_period_then_throttles(self):
        got = [m.header.stamp.to_nsec() for m in self.sonar_slow_msgs if m.header.stamp.to_sec() <= 1.0]
        self.assertTrue(got, 'no /sonar_slow message stamped up to 1 s')
        self.assertTrue(set(got) <= {300000000, 600000000, 900000000}, 'stamps [ns] %s' % got)
        self.assertEqual(got, sorted(set(got)))

    # Exactly velodyne_simulator's fields; 361 x 16 points (every ray meets a wall or the floor within
    # 0.9 .. 130 m: the nearest, ring 0 along +x, is 3 / cos 15 deg = 3.1 m away); ring j at -15 + 2 j degrees.
    def test_velodyne_cloud_has_sixteen_rings_at_their_elevations(self):
        m = self.velodyne_msgs[-1]
        self.assertEqual(m.header.frame_id, 'velodyne')
        fields = [(f.name, f.offset, f.datatype, f.count) for f in m.fields]
        self.assertEqual(fields, [('x', 0, PointField.FLOAT32, 1), ('y', 4, PointField.FLOAT32, 1),
                                  ('z', 8, PointField.FLOAT32, 1), ('intensity', 16, PointField.FLOAT32, 1),
                                  ('ring', 20, PointField.UINT16, 1)])
        self.assertEqual((m.point_step, m.height, m.width), (32, 1, 361 * 16))
        self.assertEqual(m.row_step, 32 * 361 * 16)
        self.assertTrue(m.is_dense)
        dt = np.dtype({'names': ['x', 'y', 'z', 'intensity', 'ring'], 'formats': ['<f4', '<f4', '<f4', '<f4', '<u2'],
                       'offsets': [0, 4, 8, 16, 20], 'itemsize': 32})
        p = np.frombuffer(bytes(m.data), dtype=dt)
        self.assertEqual(sorted(set(p['ring'].tolist())), list(range(16)))
        for j in range(16):
            q = p[p['ring'] == j]
            self.assertEqual(len(q), 361)
            elevation = np.arctan2(q['z'], np.hypot(q['x'], q['y']))
            np.testing.assert_allclose(elevation, math.radians(-15 + 2 * j), atol=2e-6)


    # The stereo pair: one stamp per pair (both rendered at the same tick), the right camera's P[3] =
    # -f hackBaseline with f = 32 / (2 tan 0.5) = 29.27 px: -4.098.
    def test_stereo_pair_shares_stamps_and_the_right_info_carries_the_baseline(self):
        left = {m.header.stamp.to_nsec() for m in self.left_msgs}
        right = {m.header.stamp.to_nsec() for m in self.right_msgs}
        self.assertTrue(left & right)
        self.assertEqual(sorted(left)[:3], sorted(right)[:3])
        m = self.right_info_msgs[-1]
        f = 32 / (2 * math.tan(0.5))
        self.assertEqual(m.header.frame_id, 'stereo_optical')
        self.assertAlmostEqual(m.P[0], f, places=6)
        self.assertAlmostEqual(m.P[3], -f * 0.14, places=6)
        self.assertEqual((self.left_msgs[-1].width, self.left_msgs[-1].height), (32, 24))


if __name__ == '__main__':
    rostest.rosrun('car', 'ray_sensors', RaySensorsTest)
