#!/usr/bin/env python3
"""rostest: teleop_twist_keyboard in a pseudo-terminal: keys in, the expected Twist out, terminal restored."""
import os
import subprocess
import tempfile
import termios
import time
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
import simtest


class TeleopTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_teleop')
        cls.msgs = []
        cls.sub = rospy.Subscriber('/cmd_vel', Twist, cls.msgs.append, queue_size=None)

    def start(self):
        self.master, self.slave = os.openpty()
        self.saved = termios.tcgetattr(self.slave)
        # stderr to a file: a pipe nobody reads could fill and block the node's exit
        self.err = tempfile.TemporaryFile()
        self.proc = subprocess.Popen([simtest.car_program('teleop_twist_keyboard.py'), '_key_timeout:=0'],
                                     stdin=self.slave, stdout=self.slave, stderr=self.err)
        # wait until it has put the terminal in raw mode and connected to us (a hang guard, not a speed limit: a
        # python node can take tens of seconds to start on a loaded machine)
        deadline = time.time() + 180
        while time.time() < deadline and (termios.tcgetattr(self.slave) == self.saved or
                                          not self.msgs_pub_connected()):
            time.sleep(0.05)
        self.assertTrue(termios.tcgetattr(self.slave) != self.saved and self.msgs_pub_connected(),
                        'teleop_twist_keyboard did not put the terminal in raw mode and advertise /cmd_vel in 180 s')

    def teleop_sends_to_us(self):
        master = rosgraph.Master(rospy.get_name())
        for node in next((n for t, n in master.getSystemState()[0] if t == '/cmd_vel'), []):
            info = xmlrpc.client.ServerProxy(master.lookupNode(node)).getBusInfo(rospy.get_name())[2]
            if any(c[1] == rospy.get_name() and c[2] == 'o' and c[4] == '/cmd_vel' for c in info):
                return True
        return False

    def msgs_pub_connected(self):
        return any(n for n in rospy.get_published_topics() if n[0] == '/cmd_vel')

    def send(self, keys, expect):
        n = len(self.msgs)
        os.write(self.master, keys.encode())
        deadline = time.time() + 60
        while len(self.msgs) < n + expect and time.time() < deadline:
            time.sleep(0.02)
        return self.msgs[n:]

    def stderr_tail(self):
        self.err.seek(0)
        return self.err.read()[-2000:].decode(errors='replace')

    def wait_exit(self, why):
        try:
            self.proc.wait(timeout=120)
        except subprocess.TimeoutExpired:
            self.fail('teleop_twist_keyboard did not exit within 120 s of %s; its stderr:\n%s' % (why, self.stderr_tail()))

    def stop(self):
        os.write(self.master, b'\x03')
        self.wait_exit('Ctrl-C')

    def tearDown(self):
        if self.proc.poll() is None:
            self.proc.kill()
        os.close(self.master)
        os.close(self.slave)
        self.err.close()

    def wait_connected(self):
        # the teleop's publisher has added its connection to us (its own bus info says so)
        deadline = time.time() + 60
        while not self.teleop_sends_to_us() and time.time() < deadline:
            time.sleep(0.05)
        self.assertTrue(self.teleop_sends_to_us(), "teleop's /cmd_vel publisher did not connect to us in 60 s")

    def test_keys_publish_twists_and_the_terminal_is_restored(self):
        self.start()
        # a key sent before the connection is published to nobody
        self.wait_connected()
        (fwd,) = self.send('i', 1)
        self.assertEqual((fwd.linear.x, fwd.angular.z), (0.5, 0.0))
        (left,) = self.send('j', 1)
        self.assertEqual((left.linear.x, left.angular.z), (0.0, 1.0))
        faster = self.send('qi', 2)[-1]
        self.assertAlmostEqual(faster.linear.x, 0.55)
        (stop,) = self.send('k', 1)
        self.assertEqual((stop.linear.x, stop.angular.z), (0.0, 0.0))
        self.stop()
        self.assertEqual(self.proc.returncode, 0)
        self.assertEqual(termios.tcgetattr(self.slave), self.saved)

    def test_sigterm_restores_the_terminal(self):
        self.start()
        self.assertNotEqual(termios.tcgetattr(self.slave), self.saved)  # raw while running
        # with a subscriber connected (as the simulator always is): rospy's queued publisher thread then exists, and
        # a node that leaves without rospy's shutdown waits for it forever
        self.wait_connected()
        self.proc.terminate()
        self.wait_exit('SIGTERM')
        self.assertEqual(termios.tcgetattr(self.slave), self.saved)


if __name__ == '__main__':
    rostest.rosrun('car', 'test_teleop', TeleopTest)
