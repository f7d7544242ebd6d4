#!/usr/bin/env python3
"""The mimic-joint tutorial's checks for tools/mimic.sh (run on /usr/bin/python3, sim time): the gripper_controller
(position_controllers/JointTrajectoryController on right_finger_joint) moves the right finger, and the mimic joint
plug-in built unchanged moves left_finger_joint after it. Prints one line per check: CHECK | FIGURE | ok/FAIL.
Each wait is on sim time, with a wall-clock guard that fails naming what it waited for.

Tolerances: the fingers are 0.1 kg boxes 0.2 m long on horizontal x axes, their centre 0.1 m out, so gravity's torque
is at most m g l = 0.1 * 9.8 * 0.1 = 0.098 N m. With the PID (p 20, i 0.1, i_clamp 0.2, the tutorial's
gazebo_controller.yaml) the left finger holds within 0.098 / 20 = 0.0049 rad of the right one once settled (the
integral only shrinks it); without it (SetPosition every step) the two are equal to the step's motion, well under
0.01 rad. The right finger reaches its goal within the trajectory controller's goal tolerance (0.02 rad here)."""
import sys

import rospy
from control_msgs.msg import PidState
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

import probe_util

HAS_PID = len(sys.argv) > 1 and sys.argv[1] == "pid"
state = {"joints": None, "pid": 0, "pid_max": 0.0, "lag": 0.0}
results = probe_util.Results()
check = results.check


def on_joints(m):
    if "right_finger_joint" in m.name and "left_finger_joint" in m.name:
        right = m.position[m.name.index("right_finger_joint")]
        left = m.position[m.name.index("left_finger_joint")]
        state["joints"] = (right, left)
        state["lag"] = max(state["lag"], abs(right - left))


def on_pid(m):
    state["pid"] += 1
    state["pid_max"] = max(state["pid_max"], abs(m.output))


def wait_until(what, cond, sim_s, wall_s=120.0):
    return probe_util.wait_until("mimic_probe", what, cond, sim_s, wall_s)


def move(pub, goal, sim_s=1.0):
    t = JointTrajectory()
    t.joint_names = ["right_finger_joint"]
    p = JointTrajectoryPoint()
    p.positions = [goal]
    p.time_from_start = rospy.Duration(sim_s)
    t.points = [p]
    pub.publish(t)


def settle(goal, label):
    state["lag"] = 0.0
    end = rospy.get_time() + 3.0
    wait_until("3 s of sim time after the %.1f rad goal" % goal, lambda: rospy.get_time() >= end, 10.0)
    right, left = state["joints"]
    check("%s: right finger at its goal %.1f rad" % (label, goal), "%.4f rad" % right, abs(right - goal) < 0.02)
    check("%s: left finger follows (mimic)" % label, "left %.4f rad, |left - right| %.4f rad (largest while moving %.4f)"
          % (left, abs(left - right), state["lag"]), abs(left - right) < 0.01)


def main():
    rospy.init_node("mimic_probe")
    rospy.Subscriber("/joint_states", JointState, on_joints)
    rospy.Subscriber("/gazebo_ros_control/pid_gains/left_finger_joint/state", PidState, on_pid)
    cmd = rospy.Publisher("/gripper_controller/command", JointTrajectory, queue_size=1)
    if not wait_until("/joint_states from the joint_state_controller", lambda: state["joints"] is not None, 60.0):
        check("joint_states publish", "none", False)
        return
    if not wait_until("a subscriber on /gripper_controller/command", lambda: cmd.get_num_connections() > 0, 60.0):
        check("gripper_controller takes commands", "no subscriber", False)
        return
    move(cmd, 0.8)
    settle(0.8, "open")
    move(cmd, 0.3)
    settle(0.3, "close")
    if HAS_PID:
        check("the plug-in's control_toolbox::Pid publishes its state (publish_state)",
              "%d messages, |output| at most %.3f N m (before the plug-in's clamp to maxEffort 10)"
              % (state["pid"], state["pid_max"]), state["pid"] > 0)


if __name__ == "__main__":
    probe_util.run(main, results)
