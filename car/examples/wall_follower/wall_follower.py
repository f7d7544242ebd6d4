#!/usr/bin/env python3
"""A right-hand wall follower, written as a user would: /scan in, /cmd_vel out.

Keeps `distance` [m] to the wall on its right; turns left when something is closer than `front_stop` [m] ahead.
The control law, `command()`, is a pure function of one scan, so the same law runs as this ROS node and, without
ROS, as a `car batch` controller (`batch_controller`, used by sweep.yaml).
"""
import math

# what the node does before its parameters are read, and what car batch uses
DISTANCE = 0.8    # [m] to the wall on the right
FRONT_STOP = 1.0  # [m] turn left when something ahead is closer
SPEED = 0.4       # [m/s]


def sector_min(ranges, angle_min, angle_increment, range_min, range_max, lo, hi):
    """The nearest valid range [m] between angles lo and hi [rad] (robot frame, x forward, counter-clockwise)."""
    best = float('inf')
    for i, r in enumerate(ranges):
        a = angle_min + i * angle_increment
        if lo <= a <= hi and range_min <= r <= range_max:
            best = min(best, r)
    return best


def command(ranges, angle_min, angle_increment, range_min, range_max, distance=DISTANCE, front_stop=FRONT_STOP,
            speed=SPEED):
    """One scan -> (v [m/s], w [rad/s]), the robot's forward speed and yaw rate."""
    scan = (ranges, angle_min, angle_increment, range_min, range_max)
    front = sector_min(*scan, -0.4, 0.4)
    right = sector_min(*scan, -math.pi / 2 - 0.5, -math.pi / 2 + 0.5)
    if front < front_stop:
        return 0.05, 0.8
    if right > 2 * distance:
        return speed, -0.3  # no wall near on the right: curve right (radius 1.3 m at 0.4 m/s) to find one
    return speed, max(-0.8, min(0.8, 1.5 * (distance - right)))


def batch_controller(obs):
    """car batch's controller (docs/BATCH.md): the same law on the latest scan; standing still before the first,
    as the node publishes nothing before it."""
    if obs['scan'] is None:
        return 0.0, 0.0
    i = obs['scan_info']
    return command(obs['scan'], i['angle_min'], i['angle_increment'], i['range_min'], i['range_max'])


class WallFollower:
    def __init__(self):
        import rospy
        from geometry_msgs.msg import Twist
        from sensor_msgs.msg import LaserScan
        self.Twist = Twist
        self.distance = rospy.get_param('~distance', DISTANCE)
        self.front_stop = rospy.get_param('~front_stop', FRONT_STOP)
        self.speed = rospy.get_param('~speed', SPEED)
        self.pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1)
        rospy.Subscriber('/scan', LaserScan, self.on_scan, queue_size=1)

    def on_scan(self, scan):
        cmd = self.Twist()
        cmd.linear.x, cmd.angular.z = command(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_min,
                                              scan.range_max, self.distance, self.front_stop, self.speed)
        self.pub.publish(cmd)


if __name__ == '__main__':
    import rospy
    rospy.init_node('wall_follower')
    WallFollower()
    rospy.spin()
