#!/usr/bin/env python3
"""Records every message of the given topics with stamp <= T sim seconds, after the scenario's scripted start, and
prints per-topic count and sha256 of the serialized messages in arrival order (for before/after byte identity).
Each wait is on an event or on sim time; one that runs past its limit exits 1 and names what it waited for."""
import hashlib, io, struct, sys, time
import rospy, actionlib
from control_msgs.msg import FollowJointTrajectoryActionResult
from controller_manager_msgs.srv import ListControllers
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty

argv = rospy.myargv(sys.argv)
scenario, T = argv[1], float(argv[2])
# TOPIC or TOPIC@FROM: FROM [s] is the first stamp that counts, for a topic advertised on its first message (/tf:
# sim_node's broadcaster), which the recorder can only join after the start
start = {a.split('@')[0]: float(a.split('@')[1]) if '@' in a else 0.0 for a in argv[3:]}
topics = list(start)
rospy.init_node('bytecheck')
data = {t: [] for t in topics}
past = {t: False for t in topics}  # a message stamped after T came: every earlier one on t has (TCP keeps order)


def wait(done, what, limit):
    """Polls done() until it holds; after `limit` wall seconds the recording fails, naming what it waited for."""
    end = time.monotonic() + limit
    while not done():
        if rospy.is_shutdown() or time.monotonic() > end:
            print('bytecheck %s: timed out after %.0f s waiting for %s' % (scenario, limit, what), file=sys.stderr,
                  flush=True)
            sys.exit(1)
        time.sleep(0.05)


def stamp_of(t, raw):
    """The stamp [s] of a serialized message: its header's, or for a TFMessage its first transform's (None if empty).
    Every recorded type but TFMessage opens with a std_msgs/Header: uint32 seq, uint32 secs, uint32 nsecs."""
    at = 4
    if t.rsplit('/', 1)[1] == 'tf':
        if struct.unpack_from('<I', raw, 0)[0] == 0: return None
        at = 8  # the array's length, then the first transform's header
    secs, nsecs = struct.unpack_from('<II', raw, at)
    return secs + nsecs * 1e-9


def cb_for(t):
    def cb(m):
        if isinstance(m, rospy.AnyMsg):
            raw = bytes(m._buff)  # as sent, not deserialised: a point cloud's 10 MB would hold the reader back
        else:
            b = io.BytesIO(); m.serialize(b); raw = b.getvalue()
        st = stamp_of(t, raw)
        if st is not None and st > T:
            past[t] = True
            return
        if st is not None and st < start[t]: return
        data[t].append(raw)
    return cb

# topics that publish once (the action's result): done when that one message came, not when a later one did
once = {t for t in topics if t.endswith('/result')}
subs = []
for t in topics:
    # the action's result typed: actionlib's client in this node shares the subscription and needs the message
    cls = FollowJointTrajectoryActionResult if t in once else rospy.AnyMsg
    subs.append(rospy.Subscriber(t, cls, cb_for(t), queue_size=1000000, tcp_nodelay=True, buff_size=2**26))


def wait_running(srv, names):
    rospy.wait_for_service(srv, timeout=60)
    lc = rospy.ServiceProxy(srv, ListControllers)
    wait(lambda: all(any(c.name == n and c.state == 'running' for c in lc().controller) for n in names),
         'controllers %s running (%s)' % (', '.join(names), srv), 60)


def drive(topic, x, z):
    """A fixed command, latched, sent while paused."""
    pub = rospy.Publisher(topic, Twist, queue_size=1, latch=True)
    wait(lambda: pub.get_num_connections() > 0, 'a subscriber on ' + topic, 60)
    tw = Twist(); tw.linear.x = x; tw.angular.z = z; pub.publish(tw)
    return pub


# the recorder is connected to a publisher of each topic before anything moves (the robot is spawned by then)
for t, s in zip(topics, subs):
    if t not in once and not start[t]: wait(lambda: s.get_num_connections() > 0, 'a publisher of ' + t, 60)
if scenario == 'rover':
    wait_running('/controller_manager/list_controllers', ['joint_state_controller', 'rover_velocity_controller'])
    pub = drive('/rover_velocity_controller/cmd_vel', 0.4, 0.5)
elif scenario in ('sensors', 'box_house'):
    pub = drive('/cmd_vel', 0.3, 0.4)
elif scenario == 'plugins':
    pub = drive('/r1/cmd_vel', 0.3, 0.4)
elif scenario == 'arm':
    from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal
    from trajectory_msgs.msg import JointTrajectoryPoint
    wait_running('/arm/controller_manager/list_controllers', ['joint_state_controller', 'arm_controller'])
    client = actionlib.SimpleActionClient('/arm/arm_controller/follow_joint_trajectory', FollowJointTrajectoryAction)
    if not client.wait_for_server(rospy.Duration(60)):
        wait(lambda: False, 'the follow_joint_trajectory action server', 0)
    g = FollowJointTrajectoryGoal(); g.trajectory.joint_names = ['shoulder', 'elbow']
    p = JointTrajectoryPoint(); p.positions = [0.3, -0.4]; p.time_from_start = rospy.Duration(1.0)
    g.trajectory.points = [p]
    client.send_goal(g)
else:
    wait(lambda: False, 'a known scenario (rover, arm, sensors, box_house, plugins), not ' + scenario, 0)
# the node takes the command or goal on its own thread and says nothing back: it has this long, paused
time.sleep(1.0)
rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()
wait(lambda: rospy.get_time() >= T + 1.0, 'sim time %.1f s' % (T + 1.0), 300)
rospy.ServiceProxy('/gazebo/pause_physics', Empty)()
for t in topics:
    if t in once: wait(lambda: len(data[t]) > 0, 'the message on ' + t, 30)
    else: wait(lambda: past[t], 'a message on %s stamped after %.1f s' % (t, T), 60)
for t in topics:
    h = hashlib.sha256(b''.join(data[t])).hexdigest()[:16]
    print('%s%s %d %s' % (t, '@%g' % start[t] if start[t] else '', len(data[t]), h), flush=True)
rospy.signal_shutdown('done')
