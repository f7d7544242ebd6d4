#!/usr/bin/env python3
"""rostest: the simulator node's own periodic topics keep their rates in sim time (at real time, so that the test receives every message). /clock at the default
100 Hz: while running, every 0.01 s of sim time, none left out or repeated; joint_states of a spawned robot (the
car extra, ~joint_state_rate 50 Hz): every 0.02 s. (The periods are worked out once from the rates and the world's
1 ms step: 10 and 20 steps.)"""
import math
import os
import threading
import unittest

import rospy
import rostest
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose, Point, Quaternion
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState

import simtest
from simtest import call

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RUN = 1.0  # [s] of sim time run per test


class NodeRatesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('node_rates_test')
        with open(os.path.join(ROOT, 'test', 'data', 'floater.urdf')) as f:
            xml = f.read()
        res = call('/gazebo/spawn_urdf_model', SpawnModel, 'floater', xml, 'floater_ns',
                   Pose(position=Point(0, 0, 5), orientation=Quaternion(0, 0, 0, 1)), 'world')
        assert res.success, res.status_message

    def record(self, topic, msg_type, stamp):
        """The stamps [s] of topic over RUN s of sim time from a pause, received in full (no queue bound), and the
        sim time at the pause before and after."""
        stamps, lock = [], threading.Lock()

        def on(m):
            with lock:
                stamps.append(stamp(m))
        call('/gazebo/pause_physics')
        # every message: /clock shares rospy's own sim-time subscription, bounded at 1 (simtest.receive_all)
        sub = simtest.receive_all(rospy.Subscriber(topic, msg_type, on, queue_size=None))
        simtest.wait_publisher(sub)
        t0 = simtest.sim_now()
        call('/gazebo/unpause_physics')
        simtest.wait_for('%s run' % topic, lambda: simtest.sim_now() >= t0 + RUN)
        call('/gazebo/pause_physics')
        t1 = simtest.sim_now()
        # every message of the run reaches this node: the last period's is before t1
        simtest.wait_for('%s until the pause' % topic, lambda: any(s >= t1 - 0.0201 for s in list(stamps)))
        sub.unregister()
        with lock:
            return list(stamps), t0, t1

    def test_clock_every_10_ms_of_sim_time(self):
        stamps, t0, t1 = self.record('/clock', Clock, lambda m: m.clock.to_sec())
        # the running stamps (the paused times t0 and t1 repeat at 10 Hz of wall time: left out), each a whole number
        # of hundredths of a second
        inside = [s for s in stamps if t0 + 1e-9 < s < t1 - 1e-9]
        self.assertEqual([s for s in inside if abs(s * 100 - round(s * 100)) > 1e-6], [])
        running = [round(s * 100) for s in inside]
        first, end = math.floor(t0 * 100 + 1e-6) + 1, math.ceil(t1 * 100 - 1e-6)
        self.assertGreater(end - first, RUN * 100 - 2)
        self.assertEqual(running, list(range(first, end)))

    def test_joint_states_every_20_ms_of_sim_time(self):
        stamps, t0, t1 = self.record('/floater_ns/joint_states', JointState, lambda m: m.header.stamp.to_sec())
        self.assertEqual([s for s in stamps if abs(s * 50 - round(s * 50)) > 1e-6], [])
        running = [round(s * 50) for s in stamps if t0 + 1e-9 < s < t1 - 1e-9]
        # every 0.02 s strictly between the pauses [1/50 s]
        first, end = math.floor(t0 * 50 + 1e-6) + 1, math.ceil(t1 * 50 - 1e-6)
        self.assertGreater(end - first, RUN * 50 - 2)
        self.assertEqual(running, list(range(first, end)),
                         'run %.3f..%.3f s: missing %s, extra %s' % (
                             t0, t1, sorted(set(range(first, end)) - set(running)),
                             sorted(set(running) - set(range(first, end)))))


if __name__ == '__main__':
    rostest.rosrun('car', 'node_rates', NodeRatesTest)
