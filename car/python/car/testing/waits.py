"""Waits in sim time, shared by the pytest plug-in (car.testing) and the rostest helpers (car.testing.rostest).

Every duration here is sim seconds: the simulator's /clock, never the wall clock. The only wall-clock bound is
`hang_s`, a guard against a simulator that died or stands still (it fails saying sim time did not move), never a
speed limit: a slow machine makes a wait take longer in wall time, never fail.
"""
import inspect
import threading
import time

import rospy
from rosgraph_msgs.msg import Clock


def describe(predicate, what=None):
    """A readable name for what a wait waits for: `what` when given, else the predicate's source line (a lambda)
    or its name."""
    if what:
        return what
    try:
        src = inspect.getsource(predicate).strip()
        if 'lambda' in src:
            src = src[src.index('lambda'):]
            # cut the call's trailing arguments off a one-line lambda (best effort)
            depth = 0
            for i, ch in enumerate(src):
                depth += ch in '([{'
                depth -= ch in ')]}'
                if depth < 0 or (depth == 0 and ch == ',' and i > 0):
                    src = src[:i]
                    break
        return src.splitlines()[0] if src else repr(predicate)
    except (OSError, TypeError):
        return getattr(predicate, '__name__', repr(predicate))


def message_class(msg_type):
    """A message class from a class or a 'pkg/Type' string."""
    if isinstance(msg_type, str):
        import roslib.message
        cls = roslib.message.get_message_class(msg_type)
        if cls is None:
            raise ValueError('unknown message type %r (is its package built and the workspace sourced?)' % msg_type)
        return cls
    return msg_type


def receive_all(sub):
    """Makes the rospy Subscriber sub receive every message of its topic, and returns it. rospy gives a node's
    subscribers of one topic one shared connection, bounded by the queue_size it was made with, and a later
    queue_size=None does not lift that bound. Under use_sim_time rospy's own /clock subscriber
    (rospy.impl.simtime) made /clock's connection with queue_size=1: messages read from the socket together
    (whenever this process is slow to read, a busy machine) are cut to the newest."""
    sub.impl.set_queue_size(None)
    for connection in list(sub.impl.connections):
        connection.protocol.queue_size = None
    return sub


def sent_to_us(publisher_uri, topic):
    """How many messages of `topic` the node at publisher_uri (its XML-RPC URI) has sent on its connection to this
    node, from the ROS slave API that rosnode info reads: getBusInfo names the connection (direction 'o', our
    caller id at the other end), getBusStats counts its messages. None when the node does not answer or lists no
    such connection. roscpp lists a publication's connections as [id, bytes, data bytes, messages, 0], rospy as
    [id, bytes, messages, connected] after the topic's data bytes."""
    import xmlrpc.client
    me = rospy.get_caller_id()
    try:
        api = xmlrpc.client.ServerProxy(publisher_uri)
        info = api.getBusInfo(me)
        stats = api.getBusStats(me)
    except (OSError, xmlrpc.client.Error):
        return None
    # [code, message, value]; roscpp's getBusStats gives the value alone: [publications, subscriptions]
    if len(info) != 3 or info[0] != 1:
        return None
    info = info[2]
    if len(stats) == 3 and isinstance(stats[0], int):
        stats = stats[2] if stats[0] == 1 else None
    ours = {c[0] for c in info if len(c) > 4 and c[1] == me and c[2] == 'o' and c[4] == topic}
    for entry in stats[0] if stats else []:
        if entry[0] != topic:
            continue
        roscpp = len(entry) == 2
        for c in entry[1] if roscpp else entry[2]:
            if c[0] in ours:
                return c[3] if roscpp else c[2]
    return None


def wait_connected(sub, hang_s=60.0):
    """Waits (wall time, a hang bound only) until someone publishes sub's topic to us: sim time stands still while
    the simulation is paused, and a lazy publisher sends nothing before the connection exists."""
    deadline = time.monotonic() + hang_s
    while sub.get_num_connections() == 0:
        if time.monotonic() > deadline:
            raise AssertionError('nobody publishes %s (waited %.0f s of wall time for a publisher)' % (sub.name, hang_s))
        time.sleep(0.01)


class SimClock:
    """The latest /clock time [s], read from our own subscription (rospy's own /clock subscriber keeps one message,
    so it can lag). restart() drops the old connection: after reset_simulation its stragglers carry the old run's
    times."""

    def __init__(self):
        self.t = 0.0
        self.lock = threading.Lock()
        self.generation = 0
        self.sub = self._subscribe()

    def _subscribe(self):
        return rospy.Subscriber('/clock', Clock, self._cb, callback_args=self.generation, queue_size=None,
                                tcp_nodelay=True)

    def _cb(self, msg, generation):
        with self.lock:
            if generation != self.generation:
                return
            self.t = max(self.t, msg.clock.to_sec())

    def now(self):
        with self.lock:
            return self.t

    def restart(self, t=0.0):
        with self.lock:
            self.generation += 1
            self.t = t
        self.sub.unregister()
        self.sub = self._subscribe()

    def advance_to(self, t):
        """Records a time learnt another way (sim_now()) so now() never goes back below it."""
        with self.lock:
            self.t = max(self.t, t)


def sim_now():
    """The simulator's own time [s], asked of it; it answers after every message already sent to it."""
    from gazebo_msgs.srv import GetWorldProperties
    return call('/gazebo/get_world_properties', GetWorldProperties).sim_time


def call(name, srv_type, *args, hang_s=60.0):
    """Calls a service once it exists (wall-time bound against a hang)."""
    try:
        rospy.wait_for_service(name, timeout=hang_s)
    except rospy.ROSException:
        raise AssertionError('service %s did not appear within %.0f s of wall time (is the simulator running?)'
                             % (name, hang_s))
    return rospy.ServiceProxy(name, srv_type)(*args)


_proxies = {}


def _fast_call(name, hang_s=60.0):
    """Calls an std_srvs/Empty service through a persistent connection (a new connection per call costs a master
    lookup and a TCP handshake, during which a simulator at rtf 0 runs on); a broken connection (the simulator was
    restarted) is made again once."""
    from std_srvs.srv import Empty
    for attempt in (0, 1):
        proxy = _proxies.get(name)
        if proxy is None:
            call(name, Empty, hang_s=hang_s)  # waits for the service, and does the call itself this once
            _proxies[name] = rospy.ServiceProxy(name, Empty, persistent=True)
            return
        try:
            proxy()
            return
        except (rospy.ServiceException, OSError):
            proxy.close()
            _proxies.pop(name, None)
            if attempt:
                raise


def pause():
    _fast_call('/gazebo/pause_physics')


def unpause():
    _fast_call('/gazebo/unpause_physics')


class Pacer:
    """Sets the simulator's real-time factor through set_physics_properties (max_update_rate = rtf / time_step;
    0 = as fast as possible). Pacing lives outside the physics: the steps, and so the results, do not change."""

    def __init__(self):
        from gazebo_msgs.srv import GetPhysicsProperties
        self.props = call('/gazebo/get_physics_properties', GetPhysicsProperties)
        self.rtf0 = self.props.max_update_rate * self.props.time_step
        self.rtf = self.rtf0

    def set(self, rtf):
        from gazebo_msgs.srv import SetPhysicsProperties
        p = self.props
        call('/gazebo/set_physics_properties', SetPhysicsProperties, p.time_step, rtf / p.time_step, p.gravity,
             p.ode_config)
        self.rtf = rtf

    def restore(self):
        if self.rtf != self.rtf0:
            self.set(self.rtf0)


def _run_paced(clock, t0, deadline, predicate, what, seed, hang_s, lead_wall_s, poll_s=0.002, paced=True):
    """Unpauses, polls predicate() until it is truthy (returns its value) or sim time reaches deadline (returns
    None), and pauses. The simulator pauses itself at the deadline (~pause_at), so a wait that runs out stops at
    exactly its last step. A predicate that comes true is seen some wall milliseconds later, and a simulator at
    rtf 0 can run hundreds of sim seconds per wall second, so the run is paced as it nears the deadline: the
    real-time factor is set so that what is left takes about lead_wall_s of wall time (never above the run's own
    factor), and the predicate is looked at often enough (paced=False: no pacing, for a predicate that never comes
    true). The physics does not depend on pacing: the same steps happen either way."""
    import rospy
    pacer = Pacer()
    fast = pacer.rtf0 if pacer.rtf0 > 0 else float('inf')
    last_t, last_move = t0, time.monotonic()
    # paced from the first step: a factor set after unpausing would come while the simulator runs freely
    if paced and (deadline - t0) / lead_wall_s < fast:
        pacer.set(max((deadline - t0) / lead_wall_s, 0.05))
    # the deadline itself is exact: the simulator pauses itself there (~pause_at), whatever the load
    rospy.set_param('/gazebo/pause_at', deadline)
    unpause()
    try:
        while True:
            value = predicate()
            if value:
                return value
            now = sim_now()
            clock.advance_to(now)
            left = deadline - now
            # the simulator's pause step is the first at or after the deadline, to a nanosecond of rounding
            if left <= 1e-9:
                return None
            want = min(fast, max(left / lead_wall_s, 0.05))
            # change the factor only when it is far off (each change costs a service call)
            if paced and (want < pacer.rtf * 0.5 or (pacer.rtf == 0 and want != float('inf'))):
                pacer.set(want)
            if now != last_t:
                last_t, last_move = now, time.monotonic()
            elif time.monotonic() - last_move > hang_s:
                raise AssertionError('%s: sim time stood still at %.3f s for %.0f s of wall time (did the simulator '
                                     'die or get paused?)%s' % (what, now, hang_s, _seed_text(seed)))
            time.sleep(poll_s)
    finally:
        pause()
        pacer.restore()


def run_for(clock, seconds, seed=None, hang_s=60.0, lead_wall_s=0.1):
    """Runs the simulation (unpaused, then paused) until its time has moved on by `seconds` from now; returns the
    sim time [s] it paused at: the first step at or after the target, whatever the machine's load. The simulator
    pauses itself there (its ~pause_at parameter, read when unpausing; docs/COMPAT-dropins.md "Pause at")."""
    t0 = sim_now()
    clock.advance_to(t0)
    _run_paced(clock, t0, t0 + seconds, lambda: False, 'run_for(%g)' % seconds, seed, hang_s, lead_wall_s,
               paced=False)
    t = sim_now()
    clock.advance_to(t)
    return t


def wait_sim(clock, predicate, timeout, what, seed=None, run=True, hang_s=60.0, lead_wall_s=0.1):
    """Lets the simulation run (run=True: unpause, and pause again before returning; run=False: someone else runs
    it, as in a rostest) until predicate() is truthy or `timeout` sim seconds have passed since the call. Returns
    predicate's value; on timeout raises AssertionError naming `what`, the sim times and the seed. A predicate
    that is already true returns at once.

    hang_s: wall seconds sim time may stand still before the wait fails as a hang (the simulator died or is
    paused by someone else)."""
    t0 = sim_now()
    clock.advance_to(t0)
    deadline = t0 + timeout
    value = predicate()
    if value:
        return value
    if run:
        value = _run_paced(clock, t0, deadline, predicate, what, seed, hang_s, lead_wall_s)
        if value:
            return value
    else:
        last_t, last_move = clock.now(), time.monotonic()
        while True:
            value = predicate()
            if value:
                return value
            t = clock.now()
            if t >= deadline:
                break
            if t != last_t:
                last_t, last_move = t, time.monotonic()
            elif time.monotonic() - last_move > hang_s:
                raise AssertionError('%s: sim time stood still at %.3f s for %.0f s of wall time (is the simulator '
                                     'paused?)%s' % (what, t, hang_s, _seed_text(seed)))
            time.sleep(0.005)
    # the last messages of the span may have arrived after the clock passed the deadline
    value = predicate()
    if value:
        return value
    raise AssertionError('timed out after %.3f sim s (sim time %.3f -> %.3f) waiting for: %s%s'
                         % (timeout, t0, sim_now(), what, _seed_text(seed)))


def _seed_text(seed):
    return '' if seed is None else ' [seed %d: rerun with --car-seed %d]' % (seed, seed)


class MessageWait:
    """A subscription that keeps the first message satisfying `where` (a callable msg -> bool, or None for any)."""

    def __init__(self, topic, msg_type, where=None):
        self.where = where
        self.found = None
        self.count = 0
        self.lock = threading.Lock()
        self.sub = receive_all(rospy.Subscriber(topic, message_class(msg_type), self._cb, queue_size=None,
                                                tcp_nodelay=True))

    def _cb(self, msg):
        with self.lock:
            self.count += 1
            if self.found is None and (self.where is None or self.where(msg)):
                self.found = msg

    def __call__(self):
        with self.lock:
            return self.found

    def close(self):
        self.sub.unregister()


def wait_message(clock, topic, msg_type, where=None, timeout=10.0, what=None, seed=None, run=True, hang_s=60.0):
    """The first message on topic (after the call) for which where(msg) is true, within `timeout` sim seconds."""
    w = MessageWait(topic, msg_type, where)
    try:
        wait_connected(w.sub, hang_s)
        receive_all(w.sub)
        label = what or ('a message on %s%s' % (topic, '' if where is None else ' where ' + describe(where)))
        try:
            return wait_sim(clock, w, timeout, label, seed=seed, run=run, hang_s=hang_s)
        except AssertionError as e:
            raise AssertionError('%s (%d messages received on %s, none matched)' % (e, w.count, topic)) from None
    finally:
        w.close()
