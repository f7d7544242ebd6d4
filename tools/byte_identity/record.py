#!/usr/bin/env python3
"""Records every message of the given topics with stamp <= T sim seconds, after an optional scripted start, and
prints per-topic count and sha256 of the serialized messages in arrival order (for before/after byte identity)."""
import hashlib, io, sys, time
import rospy, actionlib
from controller_manager_msgs.srv import ListControllers
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty

argv = rospy.myargv(sys.argv)
scenario, T = argv[1], float(argv[2])
topics = argv[3:]
rospy.init_node('bytecheck')
data = {t: [] for t in topics}

def cb_for(t):
    def cb(m):
        st = None
        if hasattr(m, 'header'): st = m.header.stamp.to_sec()
        elif hasattr(m, 'transforms') and m.transforms: st = m.transforms[0].header.stamp.to_sec()
        if st is not None and st > T: return
        b = io.BytesIO(); m.serialize(b); data[t].append(b.getvalue())
    return cb

from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage
from control_msgs.msg import JointTrajectoryControllerState, FollowJointTrajectoryActionResult
types = {'odom': Odometry, 'joint_states': JointState, 'tf': TFMessage, 'state': JointTrajectoryControllerState,
         'result': FollowJointTrajectoryActionResult}
for t in topics:
    cls = types[t.rsplit('/', 1)[1]]
    rospy.Subscriber(t, cls, cb_for(t), queue_size=1000000, tcp_nodelay=True)

def wait_running(srv, names):
    rospy.wait_for_service(srv)
    lc = rospy.ServiceProxy(srv, ListControllers)
    while True:
        cs = lc().controller
        if all(any(c.name == n and c.state == 'running' for c in cs) for n in names): return
        time.sleep(0.2)

time.sleep(2.0)  # connections
if scenario == 'rover':
    wait_running('/controller_manager/list_controllers', ['joint_state_controller', 'rover_velocity_controller'])
    pub = rospy.Publisher('/rover_velocity_controller/cmd_vel', Twist, queue_size=1, latch=True)
    while pub.get_num_connections() == 0: time.sleep(0.1)
    tw = Twist(); tw.linear.x = 0.4; tw.angular.z = 0.5; pub.publish(tw)
    time.sleep(1.0)
elif scenario == 'arm':
    from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal
    from trajectory_msgs.msg import JointTrajectoryPoint
    wait_running('/arm/controller_manager/list_controllers', ['joint_state_controller', 'arm_controller'])
    client = actionlib.SimpleActionClient('/arm/arm_controller/follow_joint_trajectory', FollowJointTrajectoryAction)
    client.wait_for_server()
    g = FollowJointTrajectoryGoal(); g.trajectory.joint_names = ['shoulder', 'elbow']
    p = JointTrajectoryPoint(); p.positions = [0.3, -0.4]; p.time_from_start = rospy.Duration(1.0)
    g.trajectory.points = [p]
    client.send_goal(g)
    time.sleep(1.0)
rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()
while rospy.get_time() < T + 1.0: time.sleep(0.1)
rospy.ServiceProxy('/gazebo/pause_physics', Empty)()
time.sleep(3.0)
for t in topics:
    h = hashlib.sha256(b''.join(data[t])).hexdigest()[:16]
    print('%s %d %s' % (t, len(data[t]), h), flush=True)
rospy.signal_shutdown('done')
