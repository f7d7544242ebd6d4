"""Sim: one car simulator (sim_node) with a world and the user's robot, driven from a test in sim time.

The process-wide parts: one ROS master per test process (rospy allows one node per process, bound to one master),
started on a free port unless an existing one is to be used (rostest); the test's rospy node `car_testing_*`.
Per Sim: a sim_node named /gazebo (paused, rtf 0 by default, ~seed), the robot spawned from a URDF / xacro file,
and optionally a launch file (the user's nodes) started with roslaunch. Each Sim's processes end with close().
"""
import atexit
import math
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import threading
import time
from collections import namedtuple

from car.testing import waits

Pose = namedtuple('Pose', 'x y z roll pitch yaw')
Pose.__doc__ = 'A pose in the world frame: position [m], roll/pitch/yaw [rad] (ZYX Euler, as URDF and Gazebo).'
Recorded = namedtuple('Recorded', 'topic stamp msg')
Recorded.__doc__ = 'A recorded message: its topic, its sim time [s] (header stamp, else /clock at arrival), msg.'

# the process's master and node: rospy cannot move a node to another master
_master = {'uri': None, 'proc': None, 'owned': False}


def free_port():
    """A TCP port the OS says is free now (bound to port 0 and released)."""
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def master_up(uri):
    """True when a ROS master answers at uri (its getPid call returns)."""
    import rosgraph
    try:
        rosgraph.Master('/car_testing_probe', master_uri=uri).getPid()
        return True
    except Exception:
        return False


def ensure_master(use_existing=False, hang_s=60.0):
    """The master URI this process uses, starting `rosmaster --core` on a free port the first time unless
    use_existing (then ROS_MASTER_URI must name a running master, e.g. rostest's). Sets ROS_MASTER_URI in
    os.environ, so every process a test starts talks to the same master."""
    if _master['uri']:
        return _master['uri']
    if use_existing:
        uri = os.environ.get('ROS_MASTER_URI')
        if not uri or not master_up(uri):
            raise RuntimeError('car.testing: --car-use-master: no master answers at ROS_MASTER_URI=%r' % uri)
        _master.update(uri=uri, owned=False)
        return uri
    for _ in range(5):
        port = free_port()
        uri = 'http://127.0.0.1:%d/' % port
        proc = subprocess.Popen(['rosmaster', '--core', '-p', str(port)], stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
        deadline = time.monotonic() + hang_s
        while time.monotonic() < deadline and proc.poll() is None and not master_up(uri):
            time.sleep(0.05)
        if proc.poll() is None and master_up(uri):
            _master.update(uri=uri, proc=proc, owned=True)
            os.environ['ROS_MASTER_URI'] = uri
            atexit.register(shutdown_master)
            return uri
        _stop(proc)  # the port was taken between free_port() and the bind: try another
    raise RuntimeError('car.testing: could not start rosmaster')


def shutdown_master():
    if _master['owned'] and _master['proc'] is not None:
        import rospy
        if rospy.core.is_initialized():
            rospy.signal_shutdown('car.testing done')
        _stop(_master['proc'])
        _master['proc'] = None


def rospy_name():
    import rospy
    return rospy.get_name() if rospy.core.is_initialized() else '/car_testing'


def ensure_node():
    """Initialises this process's rospy node (once), with /use_sim_time set so rospy.get_time() is sim time."""
    import rosgraph
    import rospy
    if rospy.core.is_initialized():
        return
    rosgraph.Master('/car_testing').setParam('/use_sim_time', True)
    rospy.init_node('car_testing', anonymous=True, disable_signals=True)


def shutdown_signal():
    """The signal that asks a process this one started to shut down: SIGINT, as Ctrl-C (roslaunch and ROS nodes shut
    down cleanly); SIGTERM when this process ignores SIGINT. A background job of a non-interactive shell (`cmd &` in a
    script) starts with SIGINT ignored, and its children inherit that, so SIGINT would not reach them."""
    return signal.SIGTERM if signal.getsignal(signal.SIGINT) == signal.SIG_IGN else signal.SIGINT


def _stop(proc, grace_s=10.0):
    """Ends a process group we started: shutdown_signal() (a clean shutdown), then SIGKILL."""
    if proc is None or proc.poll() is not None:
        return
    try:
        os.killpg(proc.pid, shutdown_signal())
        proc.wait(grace_s)
    except (subprocess.TimeoutExpired, ProcessLookupError):
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait()


def _quaternion(roll, pitch, yaw):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def _pose_of(p):
    q = p.orientation
    roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
    yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
    return Pose(p.position.x, p.position.y, p.position.z, roll, pitch, yaw)


def _model_xml(source):
    """(xml, is_sdf) from a path (.urdf, .xacro, .sdf/.world) or an XML string."""
    if source.lstrip().startswith('<'):
        xml = source
    elif source.endswith('.xacro'):
        from car import xacro_tool
        xml = xacro_tool.expand(source)
    else:
        with open(source) as f:
            xml = f.read()
    return xml, '<sdf' in xml[:2000]


def _unread(connection):
    """Bytes waiting on a rospy connection's socket, not yet read (FIONREAD); -1 when it cannot say."""
    import fcntl
    import struct
    import termios
    try:
        waiting = struct.unpack('i', fcntl.ioctl(connection.socket.fileno(), termios.FIONREAD, b'\0' * 4))[0]
    except (AttributeError, OSError, ValueError):
        return -1
    return waiting


class Recording:
    """Messages of some topics from the moment record() was called (reset() empties it and subscribes again).
    messages: list of Recorded in arrival order; rec['/odom'] gives that topic's messages."""

    def __init__(self, sim, topics):
        self.sim = sim
        self.topics = topics  # {topic: message class}
        self.messages = []
        self.lock = threading.Lock()
        self.generation = 0
        self.subs = []
        # messages recorded per (topic, publisher's caller id), and those its connection had carried before we
        # subscribed (rospy shares one connection among a process's subscribers of a topic)
        self.received = {}
        self.before = {}
        self._subscribe()

    def _subscribe(self):
        import rospy
        self.subs = [waits.receive_all(rospy.Subscriber(t, cls, self._cb, callback_args=(t, self.generation),
                                                        queue_size=None, tcp_nodelay=True))
                     for t, cls in self.topics.items()]
        with self.lock:
            self.received = {}
            self.before = {(s.resolved_name, (c.header or {}).get('callerid')): c.stat_num_msg
                           for s in self.subs for c in list(s.impl.connections)}

    def _cb(self, msg, args):
        topic, generation = args
        header = getattr(msg, 'header', None)
        stamp = header.stamp.to_sec() if header is not None and hasattr(header, 'stamp') else self.sim.clock.now()
        publisher = (getattr(msg, '_connection_header', None) or {}).get('callerid')
        with self.lock:
            if generation == self.generation:
                self.messages.append(Recorded(topic, stamp, msg))
                self.received[(topic, publisher)] = self.received.get((topic, publisher), 0) + 1

    def settle(self, hang_s=60.0):
        """Returns once the recording holds every message its publishers had sent to this process when it was
        called (the simulator paused after a wait: everything up to the pause). A publisher's count of messages
        for its connection to us (waits.sent_to_us, the ROS slave API) is the target. roscpp counts a message when
        it queues it, and a full queue (the publisher's queue_size) drops the oldest, so the wait also ends once
        nothing is unread on the connection's socket and nothing new has come for 0.25 s of wall time. At rtf 0 the
        simulator runs ahead of a slow reader by seconds of sim time: without this, a recording read right after
        run_for could end early. A wall-clock bound only: AssertionError after hang_s, naming the topic and the
        counts."""
        import time
        targets = []
        for s in self.subs:
            for c in list(s.impl.connections):
                n = waits.sent_to_us(c.endpoint_id, s.resolved_name)
                if n is not None:
                    targets.append((s.resolved_name, c, n))
        deadline = time.monotonic() + hang_s
        for topic, c, n in targets:
            key = (topic, (c.header or {}).get('callerid'))
            last, since = -1, time.monotonic()
            while True:
                with self.lock:
                    got = self.received.get(key, 0) + self.before.get(key, 0)
                if got >= n or c.done:
                    break
                now = time.monotonic()
                if got != last:
                    last, since = got, now
                # roscpp counts a message when it queues it for us, and its queue (the publisher's queue_size)
                # drops the oldest when it is full: nothing unread on the socket and nothing new for 0.25 s of
                # wall time means the rest were dropped there
                elif now - since > 0.25 and _unread(c) == 0:
                    break
                if now > deadline:
                    raise AssertionError('recording: %d of the %d messages %s sent on %s arrived within %.0f s of '
                                         'wall time' % (got, n, key[1], topic, hang_s))
                time.sleep(0.002)

    def __getitem__(self, topic):
        with self.lock:
            return [r.msg for r in self.messages if r.topic == topic]

    def __len__(self):
        with self.lock:
            return len(self.messages)

    def snapshot(self):
        with self.lock:
            return list(self.messages)

    def wait_connected(self, hang_s=60.0):
        for s in self.subs:
            waits.wait_connected(s, hang_s)
            waits.receive_all(s)

    def restart(self):
        with self.lock:
            self.generation += 1
            self.messages.clear()
        for s in self.subs:
            s.unregister()
        self._subscribe()

    def close(self):
        for s in self.subs:
            s.unregister()
        self.subs = []


class _Trajectories:
    """Ground truth of every model from /gazebo/model_states, one sample per `period` sim seconds, for the plot.
    samples: {model: [(t, x, y)]}."""

    def __init__(self, clock, period=0.05):
        import rospy
        from gazebo_msgs.msg import ModelStates
        self.clock, self.period = clock, period
        self.samples = {}
        self.lock = threading.Lock()
        self.generation = 0
        self._last = -1.0
        self._mk = lambda: rospy.Subscriber('/gazebo/model_states', ModelStates, self._cb,
                                            callback_args=self.generation, queue_size=None)
        self.sub = self._mk()

    def _cb(self, msg, generation):
        t = self.clock.now()
        with self.lock:
            if generation != self.generation or t < self._last + self.period:
                return
            self._last = t
            for name, p in zip(msg.name, msg.pose):
                self.samples.setdefault(name, []).append((t, p.position.x, p.position.y))

    def restart(self):
        with self.lock:
            self.generation += 1
            self.samples, self._last = {}, -1.0
        self.sub.unregister()
        self.sub = self._mk()

    def snapshot(self):
        with self.lock:
            return {k: list(v) for k, v in self.samples.items()}


class Sim:
    """One simulator for tests. Durations are sim seconds; poses world frame, [m] and [rad].

    world: a .world file (None: car's empty world). robot: a URDF, xacro or SDF file (or XML), spawned as
    `name` at `pose` (x, y, yaw). launch: a launch file started after the robot is spawned (the user's nodes),
    with launch_args {name: value}. nodes: command lines (lists) of more processes to start (the user's nodes).
    rtf: real-time factor (0 = as fast as possible). seed: the noise seed. lockstep: {trigger topic: response
    topic}: after a step that publishes the trigger the simulator waits for the node under test's answer on the
    response (docs/TESTING.md "Lockstep"); lockstep_timeout: [s of wall time] how long one such wait may last."""

    def __init__(self, world=None, robot=None, name='robot', pose=(0.0, 0.0, 0.0), launch=None, launch_args=None,
                 rtf=0.0, seed=0, use_existing_master=False, log_dir=None, hang_s=60.0, trajectory_rate=20.0, nodes=(),
                 lockstep=None, lockstep_timeout=5.0):
        self.lockstep = dict(lockstep or {})
        self.lockstep_timeout = float(lockstep_timeout)
        for trigger, response in self.lockstep.items():
            if not (isinstance(trigger, str) and isinstance(response, str) and trigger and response
                    and ':' not in trigger + response and ' ' not in trigger + response):
                raise ValueError('lockstep: {trigger: response} of topic names, got %r: %r' % (trigger, response))
        self.world, self.robot, self.name, self.start_pose = world, robot, name, tuple(pose)
        self.launch, self.launch_args = launch, dict(launch_args or {})
        self.nodes = [list(n) for n in nodes]
        self.rtf, self.seed, self.hang_s = float(rtf), int(seed), hang_s
        self.trajectory_rate = float(trajectory_rate)
        self.log_dir = log_dir or tempfile.mkdtemp(prefix='car-testing-')
        self._procs = []
        self._spawned = []
        self._publishers = {}
        self.recordings = []
        self.master_uri = ensure_master(use_existing_master, hang_s)
        ensure_node()
        try:
            self._start()
        except BaseException:
            self.close()
            raise

    # ---- processes ------------------------------------------------------------------------------------------
    def _popen(self, argv, log_name):
        log = open(os.path.join(self.log_dir, log_name), 'w')
        proc = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        log.close()
        self._procs.append((proc, log_name))
        return proc

    def _start(self):
        import rospy
        sim_node = shutil.which('sim_node') or self._find_sim_node()
        args = [sim_node, '__name:=gazebo', '_paused:=true', '_rtf:=%r' % self.rtf, '_seed:=%d' % self.seed,
                '_world_name:=%s' % (os.path.abspath(self.world) if self.world else ''),
                # ground truth for the failure plot at 20 Hz of sim time: at rtf 0 every message costs this
                # process CPU time, and 100 Hz of ModelStates would slow the run it records
                '_model_states_rate:=%g' % self.trajectory_rate]
        if self.lockstep:
            args += ['_lockstep:=%s' % ','.join('%s:%s' % kv for kv in self.lockstep.items()),
                     '_lockstep_timeout:=%r' % self.lockstep_timeout]
        self.sim_proc = self._popen(args, 'sim_node.log')
        from gazebo_msgs.srv import GetWorldProperties
        deadline = time.monotonic() + self.hang_s
        while True:
            if self.sim_proc.poll() is not None:
                raise RuntimeError('car.testing: sim_node exited (%s) while starting:\n%s'
                                   % (self.sim_proc.returncode, self.log_tail('sim_node.log')))
            try:
                rospy.wait_for_service('/gazebo/get_world_properties', timeout=0.5)
                break
            except rospy.ROSException:
                if time.monotonic() > deadline:
                    raise RuntimeError('car.testing: sim_node did not offer its services within %.0f s' % self.hang_s)
        self.clock = waits.SimClock()
        self.trajectories = _Trajectories(self.clock, 1.0 / self.trajectory_rate * 0.999)
        if self.robot:
            x, y, yaw = (list(self.start_pose) + [0.0, 0.0, 0.0])[:3]
            xml, _ = _model_xml(self.robot)
            rospy.set_param('/robot_description', xml)
            self.spawn(self.name, self.robot, x=x, y=y, yaw=yaw, _track=False)
        if self.launch:
            self._popen(['roslaunch', self.launch] + ['%s:=%s' % kv for kv in self.launch_args.items()],
                        'launch.log')
        for i, argv in enumerate(self.nodes):
            self._popen(argv, 'node%d.log' % i)
        self.call(GetWorldProperties)
        if self.lockstep:
            self._wait_lockstep_peers()

    def _wait_lockstep_peers(self):
        """Waits (wall time, paused; the hang guard bounds it) until, for each lockstep pair, some node subscribes
        to the trigger and publishes the response, and the simulator is connected to it both ways: else the first
        triggers would go out before the node under test listens, unanswered."""
        import rosgraph
        from xmlrpc.client import ServerProxy
        master = rosgraph.Master(rospy_name())
        sim_uri = None
        deadline = time.monotonic() + self.hang_s
        missing = dict(self.lockstep)
        while missing:
            if time.monotonic() > deadline:
                raise AssertionError('lockstep: no node subscribes to %s and publishes %s, connected to the simulator '
                                     '(waited %.0f s of wall time)' % (', '.join(missing), ', '.join(missing.values()),
                                                                       self.hang_s))
            if self.sim_proc.poll() is not None:
                raise RuntimeError('car.testing: sim_node exited (%s):\n%s'
                                   % (self.sim_proc.returncode, self.log_tail('sim_node.log')))
            try:
                pubs, subs, _ = master.getSystemState()
                if sim_uri is None:
                    sim_uri = master.lookupNode('/gazebo')
                bus = ServerProxy(sim_uri).getBusInfo(rospy_name())[2]
            except Exception:
                time.sleep(0.05)
                continue
            publishers = {t: set(n) for t, n in pubs}
            subscribers = {t: set(n) for t, n in subs}
            # (direction, topic, peer): peer is the subscriber's name (out) or the publisher's URI (in)
            links = {(c[2], c[4], c[1]) for c in bus if len(c) > 4}
            for trigger, response in list(missing.items()):
                for peer in (publishers.get(response, set()) & subscribers.get(trigger, set())) - {'/gazebo'}:
                    try:
                        peer_uri = master.lookupNode(peer)
                    except Exception:
                        continue
                    if ('o', trigger, peer) in links and ('i', response, peer_uri) in links:
                        del missing[trigger]
                        break
            if missing:
                time.sleep(0.05)

    @staticmethod
    def _find_sim_node():
        import rospkg
        for d in os.environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep):
            p = os.path.join(d, 'lib', 'car', 'sim_node')
            if os.access(p, os.X_OK):
                return p
        raise RuntimeError('car.testing: sim_node not found: source the workspace (devel/setup.bash) first')

    def log_tail(self, name='sim_node.log', lines=30):
        try:
            with open(os.path.join(self.log_dir, name)) as f:
                return ''.join(f.readlines()[-lines:])
        except OSError:
            return ''

    def close(self):
        """Stops the launch file's nodes and the simulator (the master stays for the process's next Sim)."""
        for rec in self.recordings:
            rec.close()
        for proc, _ in reversed(self._procs):
            _stop(proc)
        self._procs = []

    # ---- services -------------------------------------------------------------------------------------------
    def call(self, srv_type, *args, name=None):
        """Calls /gazebo/<service> (the name from the type: GetModelState -> get_model_state) and returns the
        response; a response with success false raises AssertionError with its status_message."""
        import re
        if name is None:
            name = '/gazebo/' + re.sub(r'(?<!^)(?=[A-Z])', '_', srv_type.__name__).lower()
        resp = waits.call(name, srv_type, *args, hang_s=self.hang_s)
        if getattr(resp, 'success', True) is False:
            raise AssertionError('%s: %s' % (name, resp.status_message))
        return resp

    def now(self):
        """The simulator's time [s], asked of it."""
        t = waits.sim_now()
        self.clock.advance_to(t)
        return t

    # ---- waits (sim time) -----------------------------------------------------------------------------------
    def run_for(self, seconds):
        """Runs the simulation for `seconds` of sim time (it pauses at the first /clock tick at or after the
        target, so it may run a little longer) and returns the sim time [s] it stopped at."""
        t = waits.run_for(self.clock, seconds, seed=self.seed, hang_s=self.hang_s)
        self._settle()
        return t

    def until(self, predicate, timeout=10.0, what=None):
        """Runs the simulation until predicate() is truthy and returns its value; fails (AssertionError naming
        `what` or the predicate's source, and the seed) when `timeout` sim seconds pass first."""
        value = waits.wait_sim(self.clock, predicate, timeout, waits.describe(predicate, what), seed=self.seed,
                               hang_s=self.hang_s)
        self._settle()
        return value

    def wait_message(self, topic, msg_type, where=None, timeout=10.0, what=None):
        """Runs the simulation until a message on topic (msg_type: class or 'pkg/Type') for which where(msg) is
        true arrives, within `timeout` sim seconds; returns it."""
        msg = waits.wait_message(self.clock, topic, msg_type, where, timeout, what, seed=self.seed,
                                 hang_s=self.hang_s)
        self._settle()
        return msg

    def _settle(self):
        # after a wait the recordings hold what was sent up to it, however far the simulator ran ahead of them
        for rec in self.recordings:
            rec.settle(self.hang_s)

    # ---- the world ------------------------------------------------------------------------------------------
    def pose(self, model, link=None):
        """The world-frame Pose of a model (or of one of its links)."""
        if link is None:
            from gazebo_msgs.srv import GetModelState
            return _pose_of(self.call(GetModelState, model, '').pose)
        from gazebo_msgs.srv import GetLinkState
        scoped = link if '::' in link else '%s::%s' % (model, link)
        return _pose_of(self.call(GetLinkState, scoped, '').link_state.pose)

    def set_pose(self, model, x, y, z=None, roll=0.0, pitch=0.0, yaw=0.0):
        """Puts a model at a world pose with zero velocity (z None: keep its height)."""
        from gazebo_msgs.msg import ModelState
        from gazebo_msgs.srv import SetModelState
        if z is None:
            z = self.pose(model).z
        s = ModelState(model_name=model, reference_frame='world')
        s.pose.position.x, s.pose.position.y, s.pose.position.z = x, y, z
        q = s.pose.orientation
        q.x, q.y, q.z, q.w = _quaternion(roll, pitch, yaw)
        self.call(SetModelState, s)

    def spawn(self, name, model, x=0.0, y=0.0, z=0.0, yaw=0.0, _track=True):
        """Adds a model from a URDF / xacro / SDF file or XML string at (x, y, z, yaw); reset() deletes it."""
        from geometry_msgs.msg import Pose as PoseMsg
        from gazebo_msgs.srv import SpawnModel
        xml, is_sdf = _model_xml(model)
        p = PoseMsg()
        p.position.x, p.position.y, p.position.z = x, y, z
        q = _quaternion(0.0, 0.0, yaw)
        p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = q
        self.call(SpawnModel, name, xml, '', p, 'world',
                  name='/gazebo/spawn_sdf_model' if is_sdf else '/gazebo/spawn_urdf_model')
        if _track:
            self._spawned.append(name)

    def delete(self, name):
        """Removes a model."""
        from gazebo_msgs.srv import DeleteModel
        self.call(DeleteModel, name)
        if name in self._spawned:
            self._spawned.remove(name)

    def publish(self, topic, msg, hang_s=None):
        """Publishes msg on topic from a latched publisher once the subscribers are connected (waiting in wall
        time, with the simulation paused, so no sim time passes), synchronously (queue_size None: publish()
        returns once the message is in each subscriber's socket). A command published between two waits thus
        holds from the next wait's first step. Returns the publisher (publish on it again for a new command)."""
        import rospy
        pub = self._publishers.get(topic)
        if pub is None:
            pub = rospy.Publisher(topic, type(msg), queue_size=None, latch=True)
            self._publishers[topic] = pub
        deadline = time.monotonic() + (hang_s or self.hang_s)
        while pub.get_num_connections() == 0:
            if time.monotonic() > deadline:
                raise AssertionError('publish: nobody subscribes to %s (waited %.0f s of wall time, paused)'
                                     % (topic, hang_s or self.hang_s))
            time.sleep(0.01)
        pub.publish(msg)
        return pub

    # ---- recording ------------------------------------------------------------------------------------------
    def record(self, topics):
        """Records topics from now on: a list of names already advertised, or {name: class or 'pkg/Type'}.
        Returns a Recording (messages with sim stamps); the failure report's bag holds every recording."""
        if not isinstance(topics, dict):
            import rosgraph
            published = dict(rosgraph.Master('/car_testing').getTopicTypes())
            missing = [t for t in topics if t not in published]
            if missing:
                raise ValueError('record: nobody advertises %s yet; give its type: sim.record({%r: "pkg/Type"})'
                                 % (', '.join(missing), missing[0]))
            topics = {t: published[t] for t in topics}
        rec = Recording(self, {t: waits.message_class(c) for t, c in topics.items()})
        rec.wait_connected(self.hang_s)
        self.recordings.append(rec)
        return rec

    # ---- reset ----------------------------------------------------------------------------------------------
    def reset(self):
        """Back to the start: paused, spawned models deleted, reset_simulation (sim time 0, every model at its
        first pose, wrenches ended), recordings emptied and subscribed again (so the last run's messages still in
        flight are not read as the new run's), trajectories cleared."""
        from std_srvs.srv import Empty
        waits.pause()
        for name in list(self._spawned):
            self.delete(name)
        waits.call('/gazebo/reset_simulation', Empty, hang_s=self.hang_s)
        self.clock.restart(self.now())
        self.trajectories.restart()
        for rec in self.recordings:
            rec.restart()
        for rec in self.recordings:
            rec.wait_connected(self.hang_s)

    def forget_recordings(self):
        for rec in self.recordings:
            rec.close()
        self.recordings = []
