#!/usr/bin/env python3
"""A node under test for test_lockstep.py: answers each /scan with a zero /cmd_vel after `delay` wall seconds,
and publishes on /echo_lag (std_msgs/Float64) how much sim time passed between the scan's stamp and its answer
[s] (the simulator's own time, asked of it just before answering). --mute: subscribes and advertises, never answers.
"""
import argparse
import time

import rospy
from gazebo_msgs.srv import GetWorldProperties
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Float64


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--delay', type=float, default=0.0, help='[s] wall time before each answer')
    ap.add_argument('--mute', action='store_true')
    args = ap.parse_args(rospy.myargv()[1:])
    rospy.init_node('lockstep_echo')
    cmd = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
    lag = rospy.Publisher('/echo_lag', Float64, queue_size=100)
    rospy.wait_for_service('/gazebo/get_world_properties')
    sim_time = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties, persistent=True)

    def on_scan(scan):
        if args.mute:
            return
        time.sleep(args.delay)
        lag.publish(Float64(sim_time().sim_time - scan.header.stamp.to_sec()))
        cmd.publish(Twist())

    rospy.Subscriber('/scan', LaserScan, on_scan, queue_size=1, tcp_nodelay=True)
    rospy.spin()


if __name__ == '__main__':
    main()
