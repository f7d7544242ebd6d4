#!/usr/bin/env python3
"""rostest: planar_move, force and bumper through their ROS topics (test/ros/motion.test), against hand-worked
values (derivations in test/plugins/planar_move and test/plugins/bumper)."""
import math
import time
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ContactsState
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist, Wrench
from nav_msgs.msg import Odometry

from simtest import Recorder, call


def publisher(topic, msg_type):
    """A latched publisher that has reached the simulator (synchronous: see simtest.command)."""
    pub = rospy.Publisher(topic, msg_type, queue_size=None, latch=True)
    deadline = time.time() + 30
    while pub.get_num_connections() == 0:
        if time.time() > deadline:  # a latched message would reach the simulator late, after the run began
            raise AssertionError('nobody subscribes to %s within 30 s' % topic)
        time.sleep(0.05)
    return pub


def yaw(msg):
    q = msg.pose.pose.orientation
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


class MotionTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_motion')
        deadline = time.time() + 60
        for model in ('mover', 'bumpy'):
            while not call('/gazebo/get_model_state', GetModelState, model, '').success:
                if time.time() > deadline:
                    raise AssertionError('model %s was not spawned' % model)
                time.sleep(0.1)
        cls.odom = Recorder('/odom', Odometry)
        cls.bumps = Recorder('/bumper_states', ContactsState)
        cls.odom.wait_connected()
        cls.bumps.wait_connected()
        cls.cmd = publisher('/cmd_vel', Twist)
        cls.push = publisher('/push', Wrench)

    def start(self, twist=None, wrench=None):
        """Pause, reset to t = 0, send the commands, clear the records, run."""
        call('/gazebo/pause_physics')
        call('/gazebo/reset_simulation')
        if twist is not None:
            self.cmd.publish(twist)
        if wrench is not None:
            self.push.publish(wrench)
        for r in (self.odom, self.bumps):
            r.restart()
        call('/gazebo/unpause_physics')

    def test_planar_move_twist_gives_the_arc(self):
        # body twist (vx, vy, w) = (0.5, 0.2, 0.5) from the origin: at time t, x = (vx sin wt + vy (cos wt - 1)) / w,
        # y = (vy sin wt + vx (1 - cos wt)) / w, yaw = wt; at t = 2 s: (0.657592, 0.796286, 1 rad)
        vx, vy, w = 0.5, 0.2, 0.5
        t = Twist()
        t.linear.x, t.linear.y, t.angular.z = vx, vy, w
        self.start(twist=t)
        # every message up to the first stamped at or after 2 s: which messages arrive depends on the machine (the
        # publisher's queue is 1, as upstream's, and rtf 0 runs as fast as it can; the count is tested in
        # test/plugins/planar_move), so each one that does is checked at its own stamp. odometryRate 20 by
        # upstream's clock: every 51 ms from 50 ms after the reset (docs/COMPAT-plugins.md). The mover's circle (centre
        # (-0.4, 1.0), radius 1.08 m) stays clear of the wall and of bumpy, so the arc holds at any stamp.
        msgs = self.odom.until(2.0)
        self.assertGreaterEqual(msgs[-1].header.stamp.to_sec(), 2.0)
        for m in msgs:
            s = m.header.stamp.to_sec()
            k = (s - 0.050) / 0.051
            self.assertAlmostEqual(k, round(k), places=6, msg='stamp %.4f s' % s)
            self.assertEqual(m.header.frame_id, 'odom')
            self.assertEqual(m.child_frame_id, 'base_footprint')
            x = (vx * math.sin(w * s) + vy * (math.cos(w * s) - 1)) / w
            y = (vy * math.sin(w * s) + vx * (1 - math.cos(w * s))) / w
            self.assertAlmostEqual(m.pose.pose.position.x, x, delta=2e-3, msg='x at t = %.2f s' % s)
            self.assertAlmostEqual(m.pose.pose.position.y, y, delta=2e-3, msg='y at t = %.2f s' % s)
            err = yaw(m) - w * s
            self.assertAlmostEqual(math.atan2(math.sin(err), math.cos(err)), 0.0, delta=2e-3,
                                   msg='yaw at t = %.2f s' % s)

    def test_bumper_resting_on_the_ground(self):
        # the ground carries m g = 98 N, pushing up (+z) into the box
        self.start(twist=Twist())
        m = self.bumps.until(0.5)[-1]
        ground = [s for s in m.states if s.collision2_name == 'ground_plane::link']
        self.assertEqual(len(ground), 1)
        s = ground[0]
        self.assertEqual(s.collision1_name, 'bumpy::body::body_collision')
        self.assertAlmostEqual(s.total_wrench.force.z, 98.0, delta=2.0)
        for n in s.contact_normals:
            self.assertAlmostEqual(n.z, 1.0, places=6)
        self.assertEqual(len(s.depths), len(s.contact_positions))
        self.assertEqual(m.header.frame_id, 'world')

    def test_bumper_pushed_against_the_wall(self):
        # 20 N along +x: the front face (x = 0.2 m) reaches the wall face (x = 1.0 m) after t = sqrt(2 * 0.8 / 2)
        # = 0.89 s; at rest against it the wall pushes back with 20 N along -x, the normal points out of the wall
        w = Wrench()
        w.force.x = 20.0
        self.start(twist=Twist(), wrench=w)
        m = self.bumps.until(3.0)[-1]
        wall = [s for s in m.states if s.collision2_name == 'wall::link']
        self.assertEqual(len(wall), 1)
        s = wall[0]
        self.assertAlmostEqual(s.total_wrench.force.x, -20.0, delta=1.0)
        for n in s.contact_normals:
            self.assertAlmostEqual(n.x, -1.0, places=6)
        for p in s.contact_positions:
            self.assertAlmostEqual(p.x, 1.0, delta=2e-3)


if __name__ == '__main__':
    rostest.rosrun('car', 'motion', MotionTest)
