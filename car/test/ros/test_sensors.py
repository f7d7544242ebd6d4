#!/usr/bin/env python3
"""rostest: /scan and the Kinect's topics in box_house, against values worked out from the world's geometry."""
import math
import os
import unittest

import numpy as np
import rospkg
import rospy
import rostest
import tf2_ros
from car import _core
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from sensor_msgs.msg import CameraInfo, Image, LaserScan, PointCloud2

import simtest
from simtest import Recorder, call

WALL2_X = 4.44857 - 0.075  # Wall_2's inner face [m]
STDDEV = 0.01              # lidar01.xacro's noise [m]


def analytic_range(desc, o, th, t_min=0.1, t_max=30.0):
    """Nearest upright box or cylinder of the world along a horizontal ray from o (x, y) at angle th."""
    d = np.array([math.cos(th), math.sin(th)])
    best = math.inf
    for m in desc['models']:
        Tm = np.eye(4)
        Tm[:3, :3], Tm[:3, 3] = m['pose']['rotation'], m['pose']['xyz']
        for l in m['links']:
            Tl = np.eye(4)
            Tl[:3, :3], Tl[:3, 3] = l['pose']['rotation'], l['pose']['xyz']
            for c in l['collisions']:
                Tc = np.eye(4)
                Tc[:3, :3], Tc[:3, 3] = c['origin']['rotation'], c['origin']['xyz']
                T = Tm @ Tl @ Tc
                R = T[:2, :2]
                p, v = R.T @ (np.array(o) - T[:2, 3]), R.T @ d
                t = math.inf
                if c['type'] == 'box':
                    lo, hi = -math.inf, math.inf
                    for k in range(2):
                        h = c['size'][k] / 2
                        if abs(v[k]) < 1e-15:
                            lo = lo if abs(p[k]) <= h else math.inf
                            continue
                        a, b = sorted(((-h - p[k]) / v[k], (h - p[k]) / v[k]))
                        lo, hi = max(lo, a), min(hi, b)
                    if lo <= hi and lo > t_min:
                        t = lo
                elif c['type'] == 'cylinder':
                    b, cc = p @ v, p @ p - c['radius'] ** 2
                    if b * b - cc >= 0 and -b - math.sqrt(b * b - cc) > t_min:
                        t = -b - math.sqrt(b * b - cc)
                best = min(best, t)
    return best if best <= t_max else math.inf


class SensorsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_sensors')
        cls.desc = _core.load_world_file(os.path.join(rospkg.RosPack().get_path('car'), 'worlds', 'box_house.world'))
        cls.scan = Recorder('/scan', LaserScan)
        cls.depth = Recorder('/camera/depth/image_raw', Image)
        cls.cloud = Recorder('/camera/depth/points', PointCloud2)
        cls.info = Recorder('/camera/rgb/camera_info', CameraInfo)
        for r in (cls.scan, cls.depth, cls.cloud, cls.info):
            r.wait_connected()
        cls.tf = tf2_ros.Buffer(rospy.Duration(120))
        cls.listener = tf2_ros.TransformListener(cls.tf)

    def run_at(self, x, y, yaw, until):
        """From t = 0 with the car at (x, y, yaw), records until sim time `until`."""
        call('/gazebo/pause_physics')
        call('/gazebo/reset_simulation')
        state = ModelState(model_name='mycar')
        state.pose.position.x, state.pose.position.y = x, y
        state.pose.orientation.z, state.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        self.assertTrue(call('/gazebo/set_model_state', SetModelState, state).success)
        for r in (self.scan, self.depth, self.cloud, self.info):
            r.restart()
        # the reset's /clock (t = 0, sent every 0.1 s of wall time while paused) must reach this node before the
        # run's first messages: a later jump back in time would make the TF listener clear its buffer
        simtest.wait_for('the clock back at 0', lambda: rospy.get_rostime().to_sec() == 0.0)
        call('/gazebo/unpause_physics')
        for r in (self.scan, self.depth, self.cloud):
            r.until(until)
        call('/gazebo/pause_physics')

    def test_scan_layout(self):
        self.run_at(0.0, 0.0, 0.0, 0.5)
        s = self.scan.msgs[-1]
        self.assertEqual(len(s.ranges), 360)
        self.assertAlmostEqual(s.angle_min, -3.0, places=6)
        self.assertAlmostEqual(s.angle_max, 3.0, places=6)
        self.assertAlmostEqual(s.angle_increment, 6.0 / 359.0, places=7)
        self.assertEqual(s.header.frame_id, 'laser')

    def test_scan_rate_is_5p5_hz_in_sim_time(self):
        self.run_at(0.0, 0.0, 0.0, 11.0)
        stamps = [m.header.stamp.to_sec() for m in self.scan.msgs if 1.0 < m.header.stamp.to_sec() <= 11.0]
        # every scan is stamped on the 5.5 Hz schedule, to the 1 ms step (a few may be dropped on the way at
        # rtf 0 while the Kinect's clouds fill the connection, so the count only has a floor)
        for t in stamps:
            self.assertLess(abs(t * 5.5 - round(t * 5.5)), 5.5 * 0.001 + 1e-9, 'scan at %.3f s' % t)
        self.assertGreater(len(stamps), 40)
        gaps = np.diff(stamps)
        self.assertAlmostEqual(float(gaps.min()), 1 / 5.5, delta=0.05 / 5.5)

    def test_every_beam_is_the_analytic_distance_plus_gaussian_noise(self):
        x, y, yaw = 0.5, -0.5, 0.3
        self.run_at(x, y, yaw, 0.5)
        s = self.scan.msgs[-1]
        errors = [r - analytic_range(self.desc, (x, y), yaw + s.angle_min + i * s.angle_increment)
                  for i, r in enumerate(s.ranges)]
        # Gaussian noise of stddev sigma = 0.01 m on n = 360 beams: 360 beams all fall within 4 sigma only 98 % of
        # the time, so every beam is held to 5 sigma (fails once in 5000 scans). The spread: the standard deviation
        # estimate's sigma is about sigma / sqrt(2 n) = 0.37 mm, the band 0.2 sigma = 2 mm is 5.4 of them (a spread
        # 30 % off fails). No bias: the mean's sigma is sigma / sqrt(n) = 0.53 mm, the band 4 of them (P 6e-5).
        for i, e in enumerate(errors):
            self.assertLessEqual(abs(e), 5 * STDDEV, 'beam %d off by %f m' % (i, e))
        self.assertAlmostEqual(float(np.std(errors)), STDDEV, delta=0.2 * STDDEV)
        self.assertLess(abs(float(np.mean(errors))), 4 * STDDEV / math.sqrt(360))

    def test_depth_of_the_centre_pixel_facing_a_wall(self):
        self.run_at(0.0, 0.059964, 0.0, 0.5)
        m = self.depth.msgs[-1]
        self.assertEqual(m.encoding, '32FC1')
        d = np.frombuffer(m.data, np.float32).reshape(m.height, m.width)
        # the support link (the camera) stands above the car's origin
        self.assertAlmostEqual(float(d[240, 320]), WALL2_X, delta=1e-3)

    def test_depth_nearer_than_the_cutoff_is_nan(self):
        self.run_at(WALL2_X - 0.3, 0.059964, 0.0, 0.5)
        m = self.depth.msgs[-1]
        self.assertTrue(math.isnan(np.frombuffer(m.data, np.float32).reshape(m.height, m.width)[240, 320]))

    def test_cloud_lies_on_the_wall_plane_and_has_its_colour(self):
        self.run_at(0.0, 0.059964, 0.0, 0.5)
        m = self.cloud.msgs[-1]
        self.assertEqual(m.point_step, 32)
        self.assertEqual([(f.name, f.offset) for f in m.fields], [('x', 0), ('y', 4), ('z', 8), ('rgb', 16)])
        self.assertEqual((m.height, m.width, m.is_dense), (480, 640, False))
        pts = np.frombuffer(m.data, np.dtype([('x', '<f4'), ('y', '<f4'), ('z', '<f4'), ('pad', '<f4'),
                                              ('rgb', '<u4'), ('pad2', '<u4', 3)]))
        xyz = np.stack([pts['x'], pts['y'], pts['z']], axis=1).astype(float)
        ok = np.isfinite(xyz[:, 2])
        # through TF (odom -> ... -> support -> support_depth, the static transform) into the world
        tf = simtest.lookup(self.tf, 'odom', m.header.frame_id, m.header.stamp)
        q, t = tf.transform.rotation, tf.transform.translation
        x, y, z, w = q.x, q.y, q.z, q.w
        R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                      [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                      [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        world = xyz[ok] @ R.T + np.array([t.x, t.y, t.z])
        on_wall = (world[:, 0] > 3.0) & (world[:, 2] > 0.01)  # the rest is the floor in front of the car
        self.assertGreater(on_wall.sum(), 10000)
        self.assertLess(np.abs(world[on_wall, 0] - WALL2_X).max(), 0.01)
        # Gazebo/Bricks (0.62 0.32 0.24) in the ambient light 0.4 (the face is turned away from the sun)
        rgb = pts['rgb'][ok][on_wall]
        expected = (round(0.62 * 0.4 * 255) << 16) | (round(0.32 * 0.4 * 255) << 8) | round(0.24 * 0.4 * 255)
        self.assertTrue((rgb == expected).all())

    def test_camera_info(self):
        self.run_at(0.0, 0.0, 0.0, 0.5)
        simtest.wait_for('a camera_info message', lambda: self.info.msgs)
        ci = self.info.msgs[-1]
        f = 640 / (2 * math.tan(math.radians(30)))
        self.assertAlmostEqual(ci.K[0], f, delta=0.01)  # 554.26
        self.assertAlmostEqual(ci.K[4], f, delta=0.01)
        self.assertEqual((ci.K[2], ci.K[5]), (319.5, 239.5))
        self.assertEqual(ci.distortion_model, 'plumb_bob')
        self.assertEqual(ci.header.frame_id, 'support_depth')


if __name__ == '__main__':
    rostest.rosrun('car', 'test_sensors', SensorsTest)
