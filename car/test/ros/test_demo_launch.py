#!/usr/bin/env python3
"""rostest: the tutorial's demo.launch spawns its box robot, which settles on the ground."""
import time
import unittest

import rospy
import rostest
from gazebo_msgs.srv import GetModelState


class DemoLaunchTest(unittest.TestCase):
    def test_box_robot_rests_on_the_ground(self):
        rospy.init_node('test_demo_launch')
        rospy.wait_for_service('/gazebo/get_model_state', timeout=30)
        get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        deadline = time.time() + 30
        while not get('mycar', '').success and time.time() < deadline:
            time.sleep(0.1)
        # Spawned at z = 0 half inside the ground, the box is pushed out and hops, as in Gazebo; wait until
        # it rests: z changes by < 0.1 mm over 0.5 s of sim time (judged on /clock, so a starved simulator that
        # did not step between two looks does not pass for a resting box). Then: demo.urdf's 0.5 x 0.2 x 0.1 m
        # box rests with its centre at z = 0.05.
        t_last, last = rospy.get_rostime().to_sec(), get('mycar', '').pose.position.z
        z = None
        while time.time() < deadline + 60:
            time.sleep(0.05)
            t = rospy.get_rostime().to_sec()
            if t - t_last < 0.5:
                continue
            z = get('mycar', '').pose.position.z
            if abs(z - last) < 1e-4:
                break
            t_last, last = t, z
        self.assertAlmostEqual(z, 0.05, delta=0.002)


if __name__ == '__main__':
    rostest.rosrun('car', 'test_demo_launch', DemoLaunchTest)
