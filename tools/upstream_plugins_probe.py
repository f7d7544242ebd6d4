#!/usr/bin/env python3
"""The probe of tools/upstream_plugins.sh: in a running car node (paused), spawns one scenario's robot as `robot`,
sends its commands, runs it for its sim time and writes what came out as JSON: the topics, services and TF edges
the plug-ins advertise or publish, the frames of each recorded topic, and the trajectories (stamped samples). Sim time
only; every wait has a wall-clock limit and says what it waited for.

  upstream_plugins_probe.py SCENARIO OUT.json
"""
import json
import math
import os
import sys
import threading
import time

import rosgraph
import rospy
import tf2_ros
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose, TransformStamped, Twist, Wrench, WrenchStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from std_msgs.msg import Bool
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'car', 'test', 'data')


def twist(vx, vy, wz):
    t = Twist()
    t.linear.x, t.linear.y, t.angular.z = vx, vy, wz
    return t


def wrench(fx, fy, fz):
    w = Wrench()
    w.force.x, w.force.y, w.force.z = fx, fy, fz
    return w


def trajectory():
    t = JointTrajectory()
    t.header.frame_id = 'world'
    t.joint_names = ['shoulder', 'elbow']
    for k, (a, b) in enumerate([(0.2, -0.2), (0.4, -0.4), (0.6, -0.3)]):
        p = JointTrajectoryPoint()
        p.positions = [a, b]
        p.time_from_start = rospy.Duration(0.1)
        t.points.append(p)
    return t


# name -> robot file, sim seconds, commands (topic, type, message), topics recorded (topic, type), trajectory topic
SCENARIOS = {
    'diff_drive': ('car_camera_lidar04.urdf', 10.0, [('/cmd_vel', Twist, lambda: twist(0.5, 0, 0.5))],
                   [('/odom', Odometry), ('/joint_states', JointState)], '/odom'),
    'skid_steer_drive': ('upstream_plugins/skid.urdf', 10.0, [('/cmd_vel', Twist, lambda: twist(0.3, 0, 0.3))],
                         [('/odom', Odometry)], '/odom'),
    'planar_move': ('upstream_plugins/planar_box.urdf', 10.0, [('/cmd_vel', Twist, lambda: twist(0.3, 0.1, 0.2))],
                    [('/odom', Odometry), ('/truth', Odometry)], '/odom'),
    'p3d': ('upstream_plugins/planar_box.urdf', 10.0, [('/cmd_vel', Twist, lambda: twist(0.3, 0.1, 0.2))],
            [('/odom', Odometry), ('/truth', Odometry)], '/truth'),
    'tricycle_drive': ('upstream_plugins/tricycle.urdf', 10.0, [('/cmd_vel', Twist, lambda: twist(0.4, 0, 0.3))],
                       [('/odom', Odometry)], '/odom'),
    'force': ('upstream_plugins/force_box.urdf', 2.0, [('/force', Wrench, lambda: wrench(0.5, 0, 2 * 9.8 + 1))],
              [('/f3d', WrenchStamped), ('/gazebo/ground_truth/robot', Odometry)], '/gazebo/ground_truth/robot'),
    'f3d': ('upstream_plugins/force_box.urdf', 2.0, [('/force', Wrench, lambda: wrench(0.5, 0, 2 * 9.8 + 1))],
            [('/f3d', WrenchStamped), ('/gazebo/ground_truth/robot', Odometry)], '/f3d'),
    'joint_state_publisher': ('upstream_plugins/arm.urdf', 2.0, [], [('/robot/joint_states', JointState)],
                              '/robot/joint_states'),
    'joint_pose_trajectory': ('upstream_plugins/arm.urdf', 2.0,
                              [('/set_joint_trajectory', JointTrajectory, trajectory)],
                              [('/robot/joint_states', JointState)], '/robot/joint_states'),
    'hand_of_god': ('upstream_plugins/hog_box.urdf', 3.0, [],
                    [('/gazebo/ground_truth/robot', Odometry), ('/vacuum/grasping', Bool)],
                    '/gazebo/ground_truth/robot'),
}
# car's ground truth of every robot (its p3d, stamped with sim time): the drives' trajectories are compared on it, since
# upstream's drives stamp their odometry with ros::Time::now(), which in car's node lags sim time (docs/PLUGINS.md)
GROUND_TRUTH = ('/gazebo/ground_truth/robot', Odometry)
for _name, (_urdf, _sec, _cmds, _rec, _traj) in list(SCENARIOS.items()):
    if GROUND_TRUTH not in _rec:
        SCENARIOS[_name] = (_urdf, _sec, _cmds, _rec + [GROUND_TRUTH], _traj)
SCENARIOS['template'] = SCENARIOS['hand_of_god']
SCENARIOS['vacuum_gripper'] = SCENARIOS['hand_of_god']


def wait(what, cond, limit=120.0):
    start = time.monotonic()
    while not cond():
        if rospy.is_shutdown() or time.monotonic() - start > limit:
            raise RuntimeError('timed out waiting for ' + what)
        time.sleep(0.02)


def sample(msg):
    """A message as (stamp [ns], frame, child frame, numbers)."""
    stamp = msg.header.stamp.to_nsec() if hasattr(msg, 'header') else None
    frame = getattr(getattr(msg, 'header', None), 'frame_id', None)
    if isinstance(msg, Odometry):
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
        return stamp, frame, msg.child_frame_id, [p.x, p.y, p.z, yaw]
    if isinstance(msg, JointState):
        return stamp, frame, ','.join(msg.name), list(msg.position)
    if isinstance(msg, WrenchStamped):
        f, t = msg.wrench.force, msg.wrench.torque
        return stamp, frame, '', [f.x, f.y, f.z, t.x, t.y, t.z]
    if isinstance(msg, Bool):
        return None, None, '', [float(msg.data)]
    return stamp, frame, '', []


def main():
    name, out = sys.argv[1], sys.argv[2]
    urdf, seconds, commands, recorded, _ = SCENARIOS[name]
    # rospy takes sim time only when /use_sim_time is set as it starts: wait for the launch file to set it
    master = rosgraph.Master('/upstream_plugins_probe')
    start = time.monotonic()
    while True:
        try:
            if master.getParam('/use_sim_time'):
                break
        except Exception:
            pass
        if time.monotonic() - start > 120:
            raise RuntimeError('timed out waiting for the master and /use_sim_time')
        time.sleep(0.2)
    rospy.init_node('upstream_plugins_probe')
    lock = threading.Lock()
    samples = {topic: [] for topic, _ in recorded}
    tf_edges = set()

    def keep(topic):
        def cb(msg):
            with lock:
                samples[topic].append(sample(msg))
        return cb

    for topic, typ in recorded:
        rospy.Subscriber(topic, typ, keep(topic), queue_size=100000)

    def on_tf(msg):
        with lock:
            for t in msg.transforms:
                tf_edges.add((t.header.frame_id.lstrip('/'), t.child_frame_id.lstrip('/')))
    tf_sub = rospy.Subscriber('/tf', TFMessage, on_tf, queue_size=100000)
    rospy.Subscriber('/tf_static', TFMessage, on_tf, queue_size=100)
    if name in ('hand_of_god', 'template', 'vacuum_gripper'):
        # hand_of_god's target: 0.5 m along x, 1 m up
        static = tf2_ros.StaticTransformBroadcaster()
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id = 'world', 'hog_desired'
        t.transform.translation.x, t.transform.translation.z, t.transform.rotation.w = 0.5, 1.0, 1.0
        static.sendTransform(t)

    rospy.wait_for_service('/gazebo/spawn_urdf_model', timeout=120)
    with open(os.path.join(DATA, urdf)) as f:
        xml = f.read()
    pose = Pose()
    # at rest on the ground: the drives' base frames are at the wheels' contact (z 0), the box's at its centre (half
    # its 0.2 m side). (At 0.05 m the drives fell for 0.1 s and landed with their wheels already turning, and the box
    # began half in the ground.)
    pose.position.z = {'upstream_plugins/planar_box.urdf': 0.1, 'upstream_plugins/force_box.urdf': 1.0,
                       'upstream_plugins/hog_box.urdf': 1.0}.get(urdf, 0.0)
    pose.orientation.w = 1.0
    r = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)(model_name='robot', model_xml=xml,
                                                                   robot_namespace='', initial_pose=pose,
                                                                   reference_frame='world')
    if not r.success:
        raise RuntimeError('spawn failed: ' + r.status_message)
    pubs = []
    for topic, typ, make in commands:
        pub = rospy.Publisher(topic, typ, queue_size=1, latch=True)
        wait('a subscriber on ' + topic, lambda: pub.get_num_connections() > 0)
        pub.publish(make())
        pubs.append(pub)
    time.sleep(0.5)
    t0 = rospy.get_time()
    rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()
    wait('%.1f s of sim time' % seconds, lambda: rospy.get_time() >= t0 + seconds, limit=600.0)
    rospy.ServiceProxy('/gazebo/pause_physics', Empty)()
    # car's node advertises /tf at the first transform a plug-in sends (upstream's tf::TransformBroadcaster at Load):
    # at rtf 0 the run may end before this subscriber is connected to it. Once connected, 0.2 s more of sim time lets
    # the TF edges arrive (the trajectories are compared up to the scenario's end only)
    start = time.monotonic()
    while tf_sub.get_num_connections() == 0 and time.monotonic() - start < 5.0:
        time.sleep(0.05)
    if tf_sub.get_num_connections() > 0:
        t1 = rospy.get_time()
        rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()
        wait('0.2 s more of sim time', lambda: rospy.get_time() >= t1 + 0.2, limit=120.0)
        rospy.ServiceProxy('/gazebo/pause_physics', Empty)()
    time.sleep(1.0)
    # what the plug-ins advertise: every topic and service of the node (less the probe's and car's own /gazebo/ API)
    state = rosgraph.Master('/upstream_plugins_probe').getSystemState()
    mine = {t for t, _, _ in commands}

    def theirs(n, nodes):
        return '/gazebo' in nodes and not n.startswith('/gazebo/') and n not in mine and n not in ('/rosout', '/clock')
    topics = sorted(n for n, nodes in state[0] if theirs(n, nodes))
    services = sorted(n for n, nodes in state[2] if theirs(n, nodes))
    with lock:
        rec = {t: s for t, s in samples.items()}
        edges = sorted(tf_edges)
    with open(out, 'w') as f:
        json.dump({'topics': topics, 'services': services, 'tf': edges, 'samples': rec}, f)


if __name__ == '__main__':
    main()
