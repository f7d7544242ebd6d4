"""A controller for car batch: drive forward, turn away when the lidar sees something closer than 0.6 m.

A controller is f(observation) -> (v [m/s], w [rad/s]); observation: time [s], x, y, yaw (world frame, ground
truth), v, w (measured), scan (the latest lidar ranges [m], or None before the first scan), scan_info (that scan's
angle_min, angle_increment [rad], range_min, range_max [m], as in sensor_msgs/LaserScan; None before it).
"""
import math


def wander(obs):
    scan = obs['scan']
    if scan:
        n = len(scan)
        front = [r for r in scan[n // 3: 2 * n // 3] if math.isfinite(r)]
        if front and min(front) < 0.6:
            return 0.0, 1.0
    return 0.4, 0.0
