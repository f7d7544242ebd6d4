#!/usr/bin/env python3
"""For tools/upstream_laser.sh (run on /usr/bin/python3, sim time): spawns the tutorial's car with its lidar
(car_camera_lidar03.xacro: libgazebo_ros_laser.so on /scan, 360 beams, 5.5 Hz, noise 0.01 m) into the paused world,
starts the world, and writes every /scan stamped in [1, 2] s of sim time to a JSON file: the same commands in the
same world give the same scans, so two runs (car's laser kind, upstream's library) can be compared message by
message. Usage: upstream_laser_probe.py OUT.json"""
import json
import subprocess
import sys
import time

import rospy
from geometry_msgs.msg import Pose
from sensor_msgs.msg import LaserScan
from gazebo_msgs.srv import SpawnModel
from std_srvs.srv import Empty

import probe_util

scans = []


def on_scan(m):
    t = m.header.stamp.to_sec()
    if 1.0 <= t <= 2.0:
        scans.append(dict(stamp=[m.header.stamp.secs, m.header.stamp.nsecs], frame=m.header.frame_id,
                          angle_min=m.angle_min, angle_max=m.angle_max, angle_increment=m.angle_increment,
                          time_increment=m.time_increment, scan_time=m.scan_time, range_min=m.range_min,
                          range_max=m.range_max, ranges=list(m.ranges), intensities=list(m.intensities)))


def main():
    rospy.init_node("upstream_laser_probe")
    rospy.Subscriber("/scan", LaserScan, on_scan, queue_size=100)
    rospy.wait_for_service("/gazebo/spawn_urdf_model", 60)
    urdf = subprocess.check_output(["rosrun", "car", "xacro", subprocess.check_output(
        ["rospack", "find", "car"]).decode().strip() + "/urdf/car_camera_lidar03.xacro"]).decode()
    pose = Pose()
    pose.orientation.w = 1.0
    rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)("mycar", urdf, "", pose, "world")
    # the publisher and this subscriber connected before the world runs (wall time: the world is paused)
    end = time.time() + 60
    while rospy.get_param("/use_sim_time", True) and time.time() < end:
        topics = dict(rospy.get_published_topics())
        if "/scan" in topics:
            break
        time.sleep(0.1)
    time.sleep(1.0)
    rospy.ServiceProxy("/gazebo/unpause_physics", Empty)()
    if not probe_util.wait_until("upstream_laser_probe", "2.1 s of sim time", lambda: rospy.get_time() >= 2.1,
                                 1e9, 120.0):
        return 1
    json.dump(scans, open(sys.argv[1], "w"))
    print("%d scans in [1, 2] s" % len(scans))
    return 0 if scans else 1


if __name__ == "__main__":
    sys.exit(main())
