#!/usr/bin/env python3
"""rostest: two robots in namespaces r1 and r2 (zoo19_two_robots.test) drive independently, and their topics and
TF frames land where gazebo_ros users expect them (docs/COMPAT-spawn.md rules 1-4).

two_bot (test/data/zoo19/two_bot.urdf.xacro) with prefix rN_: diff drive, commandTopic cmd_vel, odometryTopic
odom, no <robotNamespace>; odometryFrame rN_odom, robotBaseFrame rN_base_footprint, wheel joint states on.
spawn_model inside <group ns="rN"> gives the plug-in the namespace /rN/: /rN/cmd_vel, /rN/odom, /rN/joint_states.
"""
import unittest

import rospy
import rostest
import tf2_ros
import yaml
from nav_msgs.msg import Odometry

from simtest import Recorder, command, fit_circle, lookup, sim_now, wait_for, xy

# Commands and the circle each gives, radius = v / w [m]
V1, W1 = 0.2, 0.5    # r1: R = 0.4 m, counter-clockwise
V2, W2 = 0.3, -1.0   # r2: R = 0.3 m, clockwise


def publishers():
    return dict(rospy.get_published_topics())


def subscribers(topic):
    import rosgraph
    _, subs, _ = rosgraph.Master('/zoo19_two_robots').getSystemState()
    return dict(subs).get(topic, [])


class TwoRobots(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('zoo19_two_robots')
        for name in ('/r1/odom', '/r2/odom'):
            wait_for('a publisher of %s' % name, lambda: name in publishers())
        cls.odom = {r: Recorder('/%s/odom' % r, Odometry) for r in ('r1', 'r2')}
        for rec in cls.odom.values():
            rec.wait_connected()
        cls.tf = tf2_ros.Buffer(cache_time=rospy.Duration(600))
        cls.tf_listener = tf2_ros.TransformListener(cls.tf)

    def run_one(self, mover, v, w, still):
        """Commands (v, w) to MOVER and 0 to STILL; after 1 s of sim time to reach speed, 4 s recorded.
        Returns (mover's odometry, still's odometry) of the recorded span."""
        command(0.0, 0.0, '/%s/cmd_vel' % still)
        pub = command(v, w, '/%s/cmd_vel' % mover)
        t0 = sim_now()
        self.odom[mover].until(t0 + 5.0)
        self.odom[still].until(t0 + 5.0)
        span = lambda r: [m for m in self.odom[r].msgs if t0 + 1.0 <= m.header.stamp.to_sec() <= t0 + 5.0]
        moved, stayed = span(mover), span(still)
        command(0.0, 0.0, '/%s/cmd_vel' % mover)
        pub.unregister()
        return moved, stayed

    def check_circle(self, msgs, v, w):
        # 4 s at |w| >= 0.5 rad/s sweeps >= 2 rad of the circle: the fit pins its radius.
        # Two driven wheels that do not slip go exactly v / w. They do not slip: the turns ask v^2 / r = 0.1 and
        # 0.3 m/s^2 sideways, the tyres' mu 1 holds 9.8 m/s^2, and the caster has mu 0. What is left is the velocity
        # motors' solver residual, whose angle anchor keeps each wheel within 0.02 rad of its target angle, 1 mm at
        # the 0.05 m rim: so the radius to 1 mm (measured: 0.40002 and 0.29971 m). A 4 % wrong wheel separation
        # turns at 1.04 w: 0.3846 and 0.2885 m, 15 and 12 mm off.
        _, radius = fit_circle([xy(m) for m in msgs])
        self.assertAlmostEqual(radius, abs(v / w), delta=0.001)
        # The odometry (odometrySource world: the body's own velocity) at one instant: the motors hold each rim's
        # speed to their residual, measured within 1e-4 m/s and 1e-4 rad/s over the 4 s; the bands are 10 and 50 times
        # that, and still catch a 4 % wrong separation (w off by 0.02 and 0.04 rad/s) or wheel diameter (v off by 0.008
        # and 0.012 m/s), which the old 0.02 m/s and 0.05 rad/s let through.
        self.assertAlmostEqual(msgs[-1].twist.twist.linear.x, v, delta=0.001)
        self.assertAlmostEqual(msgs[-1].twist.twist.angular.z, w, delta=0.005)

    def check_still(self, msgs):
        # the other robot, commanded 0, has not moved (1 mm) while this one drove
        (x0, y0), (x1, y1) = xy(msgs[0]), xy(msgs[-1])
        self.assertLess(((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5, 0.001)

    def test_r1_drives_its_own_circle_while_r2_stands(self):
        moved, stayed = self.run_one('r1', V1, W1, 'r2')
        self.check_circle(moved, V1, W1)
        self.check_still(stayed)

    def test_r2_drives_its_own_circle_while_r1_stands(self):
        moved, stayed = self.run_one('r2', V2, W2, 'r1')
        self.check_circle(moved, V2, W2)
        self.check_still(stayed)

    def test_topics_under_each_namespace(self):
        pubs = publishers()
        for r in ('r1', 'r2'):
            self.assertEqual(pubs.get('/%s/odom' % r), 'nav_msgs/Odometry')
            self.assertEqual(pubs.get('/%s/joint_states' % r), 'sensor_msgs/JointState')
            self.assertIn('/gazebo', subscribers('/%s/cmd_vel' % r))
            # each namespace's robot_state_publisher reads its own robot's wheel joint states
            self.assertIn('/%s/robot_state_publisher' % r, subscribers('/%s/joint_states' % r))
        # nothing on the global names, nothing under the model names
        for name in ('/odom', '/joint_states', '/r1_bot/odom', '/r2_bot/odom'):
            self.assertNotIn(name, pubs)
        self.assertEqual(subscribers('/cmd_vel'), [])

    def test_odometry_frames_are_the_plugin_frames(self):
        for r in ('r1', 'r2'):
            m = self.odom[r].until(rospy.get_time())[-1]
            self.assertEqual(m.header.frame_id, '%s_odom' % r)
            self.assertEqual(m.child_frame_id, '%s_base_footprint' % r)

    def test_tf_tree_per_robot(self):
        for r in ('r1', 'r2'):
            # the drive's odom TF (frames as written in the plug-in, no tf_prefix) ...
            t = lookup(self.tf, '%s_odom' % r, '%s_base_footprint' % r, rospy.Time(0))
            # ... at the robot's place: r2 was spawned at y = 3 m (world odometry)
            if r == 'r2':
                self.assertGreater(t.transform.translation.y, 2.0)
            # ... and robot_state_publisher's wheels from /rN/joint_states, base_link from the fixed joint
            lookup(self.tf, '%s_base_footprint' % r, '%s_left_wheel' % r, rospy.Time(0))
            b = lookup(self.tf, '%s_base_footprint' % r, '%s_base_link' % r, rospy.Time(0))
            self.assertAlmostEqual(b.transform.translation.z, 0.05, delta=1e-9)
        tree = yaml.safe_load(self.tf.all_frames_as_yaml()) or {}
        frames = set(tree) | {v['parent'] for v in tree.values()}
        # no frame without a robot's prefix, as child or parent (a clash of the two robots would show here)
        self.assertEqual(sorted(f for f in frames if not f.startswith(('r1_', 'r2_'))), [])


if __name__ == '__main__':
    rostest.rosrun('car', 'zoo19_two_robots', TwoRobots)
