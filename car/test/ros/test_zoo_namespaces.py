#!/usr/bin/env python3
"""rostest: gazebo_ros's spawn namespace rule (docs/COMPAT-spawn.md) on the zoo's ns_bot, one case per test."""
import time
import unittest

import rospy
import rostest
from nav_msgs.msg import Odometry

from simtest import Recorder, command, sim_now

# ns_bot's diff drive: commandTopic cmd_vel, odometryTopic odom, no <robotNamespace> unless ns:= is given
V = 0.2  # [m/s] commanded forward speed


def wait_for_topic(name, timeout=60.0):
    """Waits (wall time) until the master lists a publisher of `name`."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        if name in dict(rospy.get_published_topics()):
            return True
        time.sleep(0.1)
    return False


class ZooNamespaces(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_zoo_namespaces')

    def drives(self, prefix):
        """Commands V on PREFIX/cmd_vel; PREFIX/odom then reports V forward (world odometry of the base)."""
        self.assertTrue(wait_for_topic(prefix + '/odom'), 'nobody publishes %s/odom' % prefix)
        rec = Recorder(prefix + '/odom', Odometry)
        rec.wait_connected()
        command(V, 0.0, prefix + '/cmd_vel')
        t0 = sim_now()
        # 2 s of sim time: the wheels (5 N m each on a 2.4 kg robot) reach the commanded speed long before
        msgs = rec.until(t0 + 2.0)
        self.assertAlmostEqual(msgs[-1].twist.twist.linear.x, V, delta=0.02)
        return msgs

    def test_root_namespace_gives_global_topics(self):
        # spawn_model at the root: -robot_namespace = rospy.get_namespace() = "/" -> /cmd_vel and /odom
        self.drives('')
        self.assertNotIn('/ns_root/odom', dict(rospy.get_published_topics()))

    def test_group_namespace_prefixes_topics(self):
        # spawn_model in <group ns="r1">: "/r1/" -> /r1/cmd_vel and /r1/odom
        self.drives('/r1')
        self.assertNotIn('/ns_r1/odom', dict(rospy.get_published_topics()))

    def test_explicit_namespace_is_kept(self):
        # <robotNamespace>/explicit</robotNamespace> written in the plug-in wins over the spawn namespace "/"
        self.drives('/explicit')
        self.assertNotIn('/ns_explicit/odom', dict(rospy.get_published_topics()))


if __name__ == '__main__':
    rostest.rosrun('car', 'zoo_namespaces', ZooNamespaces)
