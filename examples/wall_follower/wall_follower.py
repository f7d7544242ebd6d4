#!/usr/bin/env python3
"""A right-hand wall follower, written as a user would: /scan in, /cmd_vel out.

Keeps `distance` [m] to the wall on its right; turns left when something is closer than `front_stop` [m] ahead.
"""
import math

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan


def sector_min(scan, lo, hi):
    """The nearest valid range [m] between angles lo and hi [rad] (robot frame, x forward, counter-clockwise)."""
    best = float('inf')
    for i, r in enumerate(scan.ranges):
        a = scan.angle_min + i * scan.angle_increment
        if lo <= a <= hi and scan.range_min <= r <= scan.range_max:
            best = min(best, r)
    return best


class WallFollower:
    def __init__(self):
        self.distance = rospy.get_param('~distance', 0.8)
        self.front_stop = rospy.get_param('~front_stop', 1.0)
        self.speed = rospy.get_param('~speed', 0.4)
        self.pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1)
        rospy.Subscriber('/scan', LaserScan, self.on_scan, queue_size=1)

    def on_scan(self, scan):
        front = sector_min(scan, -0.4, 0.4)
        right = sector_min(scan, -math.pi / 2 - 0.5, -math.pi / 2 + 0.5)
        cmd = Twist()
        if front < self.front_stop:
            cmd.linear.x, cmd.angular.z = 0.05, 0.8
        elif right == float('inf'):
            cmd.linear.x, cmd.angular.z = self.speed, -0.3  # no wall in sight: curve right to find one
        else:
            cmd.linear.x = self.speed
            cmd.angular.z = max(-0.8, min(0.8, 1.5 * (self.distance - right)))
        self.pub.publish(cmd)


if __name__ == '__main__':
    rospy.init_node('wall_follower')
    WallFollower()
    rospy.spin()
