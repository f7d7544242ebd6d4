#!/usr/bin/env python3
"""rostest: a four-wheel skid-steer base as its gazebo package spawns it (spawn_model -urdf -z Z, controllers from
its control.yaml through controller_manager's spawner): it rests on its wheels, turns the commanded circle and
drives straight at the commanded speed (issue 29; car's fixtures test/data/skid/*_like.urdf carry Husky's and
Jackal's geometry, contact keys and wheel_separation_multiplier; docs/COMPAT-physics.md "Skid steering").

Parameters: ~model, ~controller, ~z (spawn height [m]), ~rest_z (base_link's rest height [m]: wheel radius less the
axle's offset), ~a and ~b (half wheelbase and half track [m]), ~multiplier, ~radius_min and ~radius_max (the band
of radii Gazebo 11 plausibly drives for v / w = 1 m [m]: docs/ROBOTS.md "Husky and Jackal")."""
import math
import unittest

import numpy as np
import rospy
import rostest
from controller_manager_msgs.srv import ListControllers

from simtest import Recorder, call, command, fit_circle, sim_now, wait_for, xy


class SkidSteerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('skid_steer_test')
        cls.controller = rospy.get_param('~controller')

        def running():
            try:
                cs = call('/controller_manager/list_controllers', ListControllers).controller
            except rospy.ServiceException:
                return False
            return any(c.name == cls.controller and c.state == 'running' for c in cs)
        wait_for('%s running' % cls.controller, running)
        cls.truth = Recorder('/ground_truth')
        cls.truth.wait_connected()

    def test_1_rests_on_its_wheels_within_2_s(self):
        z0, rest = rospy.get_param('~z'), rospy.get_param('~rest_z')
        call('/gazebo/unpause_physics')
        msgs = self.truth.until(2.5)
        z = np.array([m.pose.pose.position.z for m in msgs])
        t = np.array([m.header.stamp.to_sec() for m in msgs])
        # at rest from 2 s on: within 1 mm of base_link's rest height (wheel radius less the axle's offset)
        self.assertLess(np.abs(z[t >= 2.0] - rest).max(), 0.001)
        if z0 < rest:
            # spawned with its wheels in the ground: lifted out, never thrown (ODE's capped correction, at most
            # max_vel 0.01 m/s of rebound: far below the 0.05 m bound)
            self.assertLess(z.max(), rest + 0.05)

    def test_2_turns_the_commanded_circle(self):
        v, w = 0.5, 0.5
        a, b, m = rospy.get_param('~a'), rospy.get_param('~b'), rospy.get_param('~multiplier')
        command(v, w, '/%s/cmd_vel' % self.controller)
        t0 = sim_now()
        # Expected turn (test/plugins/ros_control/test_skid_steer.cpp): the controller asks wheel speeds v -+ w m b;
        # four contacts at (+-a, +-b) sliding under one friction law turn the base at W = w m b^2 / (a^2 + b^2).
        W = w * m * b * b / (a * a + b * b)
        lap = 2 * math.pi / W
        msgs = self.truth.until(t0 + 2.0 + lap)
        points = [xy(q) for q in msgs if t0 + 2.0 <= q.header.stamp.to_sec() <= t0 + 2.0 + lap]
        _, radius = fit_circle(points)
        # Judged against what Gazebo 11 plausibly drives, not against v / w: stock ODE set up as Gazebo 11 sets up its
        # fork brackets the radius for this base (docs/ROBOTS.md "Husky and Jackal"; ~radius_min, ~radius_max)
        lo, hi = rospy.get_param('~radius_min'), rospy.get_param('~radius_max')
        self.assertTrue(lo <= radius <= hi, 'radius %.3f m outside the Gazebo 11 band %.2f..%.2f m (v / W = %.3f m)' %
                        (radius, lo, hi, v / W))

    def test_3_drives_straight_at_the_commanded_speed(self):
        command(0.5, 0.0, '/%s/cmd_vel' % self.controller)
        t0 = sim_now()
        # past the turn's end (acceleration limits 3 m/s^2 and 6 rad/s^2: well under 1 s), over 2 s
        msgs = [q for q in self.truth.until(t0 + 3.0) if t0 + 1.0 <= q.header.stamp.to_sec() <= t0 + 3.0]
        first, last = msgs[0], msgs[-1]
        speed = math.dist(xy(first), xy(last)) / (last.header.stamp - first.header.stamp).to_sec()
        # the target: within 5 % of the command
        self.assertAlmostEqual(speed, 0.5, delta=0.025)


if __name__ == '__main__':
    rostest.rosrun('car', 'skid_steer', SkidSteerTest)
