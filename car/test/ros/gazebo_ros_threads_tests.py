#!/usr/bin/env python3
"""rostest gazebo_ros_threads: a Gazebo model plug-in that uses roscpp as upstream gazebo_plugins' drives do
(test/gazebo/plugins/ros_thread_probe.cc: its own callback-queue thread, stopped by nothing; ros::Time::now() and
World::SimTime() published at every WorldUpdateBegin) in car's node, which this test starts and stops itself
(car.testing's Sim on rostest's master), at rtf 0. docs/COMPAT-plugins.md "ROS time in car's node" and "Plug-ins'
threads"."""
import os
import unittest

import rospkg
import rostest

from car.testing.sim import Sim

URDF = os.path.join(rospkg.RosPack().get_path('car'), 'test', 'data', 'gazebo_ros_probe_box.urdf')
DT = 0.001  # [s] the empty world's step


# what the probe prints when it is deleted while its thread still serves (its thread then runs on freed memory)
LEFT_RUNNING = 'deleted while its queue thread still serves'


def node_log(sim):
    with open(os.path.join(sim.log_dir, 'sim_node.log')) as f:
        return f.read()


def start():
    return Sim(robot=URDF, name='probe_box', pose=(0.0, 0.0, 0.0), rtf=0.0, use_existing_master=True)


class GazeboRosThreads(unittest.TestCase):
    def test_ros_time_is_the_sim_time_in_every_world_update_begin(self):
        sim = start()
        try:
            rec = sim.record({'/probe_box/probe_time': 'sensor_msgs/TimeReference'})
            sim.run_for(0.3)
            msgs = rec['/probe_box/probe_time']
        finally:
            sim.close()
        # at rtf 0 the node publishes /clock every 10 steps and roscpp's own /clock subscriber (were it there) would set
        # the time in its own thread, steps later; ros::Time::now() must be SimTime() in every step's callback
        self.assertGreaterEqual(len(msgs), 250, 'fewer steps recorded than 0.3 s of 1 ms steps')
        wrong = [(m.header.stamp.to_nsec(), m.time_ref.to_nsec()) for m in msgs if m.header.stamp != m.time_ref]
        self.assertEqual(wrong, [], 'ros::Time::now() [ns] differs from World::SimTime() [ns] in these steps')
        # every step in between was recorded: consecutive sim times one step apart (the steps counted by hand)
        refs = [m.time_ref.to_nsec() for m in msgs]
        self.assertEqual(refs, list(range(refs[0], refs[0] + len(refs) * 1000000, 1000000)))

    def test_delete_model_leaves_the_node_running(self):
        sim = start()
        try:
            sim.run_for(0.05)
            sim.delete('probe_box')
            # the node goes on: 0.1 s more of sim time passes (a node aborted by the plug-in's thread would not)
            t = sim.now()
            self.assertGreaterEqual(sim.run_for(0.1), t + 0.1 - 1e-9)
            self.assertIsNone(sim.sim_proc.poll(), 'sim_node exited:\n' + sim.log_tail())
            self.assertNotIn(LEFT_RUNNING, node_log(sim))
        finally:
            sim.close()
        self.assertEqual(sim.sim_proc.returncode, 0, sim.log_tail())
        self.assertNotIn(LEFT_RUNNING, node_log(sim))

    def test_the_node_exits_clean_with_the_plugin_loaded(self):
        sim = start()
        try:
            sim.run_for(0.05)
        finally:
            sim.close()
        # SIGINT: roscpp shuts down, the plug-in's thread leaves its loop, then the world deletes the plug-in
        self.assertEqual(sim.sim_proc.returncode, 0, sim.log_tail())
        self.assertNotIn(LEFT_RUNNING, node_log(sim))


if __name__ == '__main__':
    rostest.rosrun('car', 'gazebo_ros_threads', GazeboRosThreads)
