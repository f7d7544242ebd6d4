#!/usr/bin/env python3
"""rostest: gzserver --iters 2000 steps the empty world (1 ms steps) 2000 times, then the server exits: the last
/clock is 2.0 s of sim time and node /gazebo leaves the master."""
import time
import unittest

import rosgraph
import rospy
import rostest
from rosgraph_msgs.msg import Clock


class DropinIters(unittest.TestCase):
    def test_server_stops_after_iters_steps(self):
        rospy.init_node('dropin_iters')
        last = []
        rospy.Subscriber('/clock', Clock, lambda m: last.append(m.clock.to_sec()), queue_size=1000)
        master = rosgraph.Master('/dropin_iters')
        deadline = time.time() + 90
        seen = False
        while time.time() < deadline:
            nodes = {n for _, ns in master.getSystemState()[0] for n in ns}
            seen = seen or '/gazebo' in nodes
            if seen and '/gazebo' not in nodes:
                break
            time.sleep(0.1)
        self.assertTrue(seen and '/gazebo' not in nodes, 'node /gazebo did not exit')
        # 2000 steps x 0.001 s; /clock every 10 steps, the last one at step 2000 (flushed or not: within one period)
        self.assertAlmostEqual(max(last), 2.0, delta=0.0101)


if __name__ == '__main__':
    rostest.rosrun('car', 'dropin_iters', DropinIters)
