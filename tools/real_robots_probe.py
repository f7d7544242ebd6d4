#!/usr/bin/env python3
"""The probe of tools/real_robots.sh: watches one robot's ground truth (/gazebo/model_states) while it rests, drives
a circle and drives straight, and prints one line of numbers per phase. Sim time only; every wait has a limit and
says what it waited for.

Phases (sim time, from the first model_states sample that holds the model):
  rest      5 s with no command: z of the model frame, its highest value in the first 2 s and at 2 s and 5 s
  circle    14 s at (v, w): from the last 10 s, the speed and the yaw rate averaged over the ground truth's twist,
            and the circle fitted to the positions (algebraic least squares); R = v/w is the target
  stop      2 s at (0, 0)
  straight  8 s at (v, 0): the speed, displacement over the last 5 s / 5 s
"""
import argparse
import math
import sys
import time

import numpy as np
import rospy
from gazebo_msgs.msg import ModelStates
from geometry_msgs.msg import Twist


class Probe:
    def __init__(self, model):
        self.model = model
        self.samples = []  # (t [s], x, y, z [m], yaw [rad], vx, vy [m/s], wz [rad/s]), world frame
        rospy.Subscriber("/gazebo/model_states", ModelStates, self.on_states, queue_size=100)

    def on_states(self, msg):
        if self.model not in msg.name:
            return
        i = msg.name.index(self.model)
        p, t = msg.pose[i], msg.twist[i]
        q = p.orientation
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
        self.samples.append((rospy.get_time(), p.position.x, p.position.y, p.position.z, yaw,
                             t.linear.x, t.linear.y, t.angular.z))

    def wait_sim(self, until, what, wall_limit=600.0):
        start = time.monotonic()
        while not rospy.is_shutdown() and rospy.get_time() < until:
            if time.monotonic() - start > wall_limit:
                raise RuntimeError("timed out waiting for sim time %.1f s (%s); sim time is %.2f s"
                                   % (until, what, rospy.get_time()))
            time.sleep(0.02)

    def window(self, t0, t1):
        return np.array([s for s in self.samples if t0 <= s[0] <= t1])


def fit_circle(x, y):
    """Algebraic (Kasa) least-squares circle: returns (cx, cy, R)."""
    a = np.column_stack([x, y, np.ones_like(x)])
    b = x * x + y * y
    c, *_ = np.linalg.lstsq(a, b, rcond=None)
    cx, cy = c[0] / 2, c[1] / 2
    return cx, cy, math.sqrt(c[2] + cx * cx + cy * cy)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--robot", required=True)
    ap.add_argument("--topic", required=True)
    ap.add_argument("--v", type=float, default=0.5)
    ap.add_argument("--w", type=float, default=0.5)
    args = ap.parse_args()
    rospy.init_node("real_robots_probe", anonymous=True)
    probe = Probe(args.robot)
    pub = rospy.Publisher(args.topic, Twist, queue_size=1)

    # the model's first ground-truth sample (spawned by the launch file)
    start = time.monotonic()
    while not probe.samples:
        if time.monotonic() - start > 300:
            raise RuntimeError("timed out (300 s wall) waiting for model '%s' in /gazebo/model_states" % args.robot)
        time.sleep(0.1)
    t0 = probe.samples[0][0]
    out = ["%s:" % args.robot]

    probe.wait_sim(t0 + 5.0, "rest")
    first2 = probe.window(t0, t0 + 2.0)
    z2 = first2[-1][3]  # the last sample at or before 2 s
    z5 = probe.samples[-1][3]
    out.append("rest: z0 %.4f m, max z in 2 s %.4f m, z(2 s) %.4f m, z(5 s) %.4f m;" % (
        first2[0][3], first2[:, 3].max(), z2, z5))

    def drive(v, w, seconds, what):
        msg = Twist()
        msg.linear.x, msg.angular.z = v, w
        t_start = rospy.get_time()
        while rospy.get_time() < t_start + seconds:
            pub.publish(msg)
            probe.wait_sim(min(rospy.get_time() + 0.05, t_start + seconds), what)
        return t_start, rospy.get_time()

    # wait for the controller's subscriber (the spawner loads it after the spawn)
    start = time.monotonic()
    while pub.get_num_connections() == 0:
        if time.monotonic() - start > 300:
            raise RuntimeError("timed out (300 s wall) waiting for a subscriber on " + args.topic)
        time.sleep(0.1)

    a, b = drive(args.v, args.w, 14.0, "circle")
    s = probe.window(b - 10.0, b)
    speed = np.hypot(s[:, 5], s[:, 6]).mean()
    yaw_rate = s[:, 7].mean()
    _, _, r_fit = fit_circle(s[:, 1], s[:, 2])
    target = args.v / args.w
    out.append("circle (%.2f, %.2f): speed %.4f m/s, yaw rate %.4f rad/s, R = v/w %.4f m, fitted R %.4f m "
               "(target %.3f m, %+.1f %%);" % (args.v, args.w, speed, yaw_rate, speed / yaw_rate, r_fit, target,
                                                100 * (r_fit - target) / target))
    drive(0.0, 0.0, 2.0, "stop")
    a, b = drive(args.v, 0.0, 8.0, "straight")
    s = probe.window(b - 5.0, b)
    v_line = math.hypot(s[-1][1] - s[0][1], s[-1][2] - s[0][2]) / (s[-1][0] - s[0][0])
    out.append("straight (%.2f, 0): speed %.4f m/s (%+.1f %%), yaw rate %.4f rad/s" % (
        args.v, v_line, 100 * (v_line - args.v) / args.v, s[:, 7].mean()))
    drive(0.0, 0.0, 0.5, "stop")
    print(" ".join(out))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
