"""Helpers shared by car's rostests: drive the simulator in sim time and record what it publishes."""
import math
import threading

import numpy as np
import rospy
from controller_manager_msgs.srv import ListControllers
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty

# the same rule car.testing gives users (one place for it)
from car.testing.waits import receive_all  # noqa: F401


class Recorder:
    """Keeps every message of a topic, in arrival order, with its header stamp in seconds."""

    def __init__(self, topic, msg_type=Odometry):
        self.topic, self.msg_type = topic, msg_type
        self.msgs = []
        self.lock = threading.Lock()
        # /rosout merges many nodes' lines whose stamps interleave (each node's clock lags differently): a stamp
        # going back there is no reset, so a log recorder keeps every message
        self.keep_all = topic == '/rosout'
        # each subscription's messages carry its number: restart() makes a new one and ignores the old
        self.generation = 0
        self.sub = self._subscribe()

    def _subscribe(self):
        return rospy.Subscriber(self.topic, self.msg_type, self._cb, callback_args=self.generation, queue_size=None,
                                tcp_nodelay=True)

    def _cb(self, msg, generation=0):
        with self.lock:
            if generation != self.generation:
                return  # read from a connection restart() closed
            # A stamp earlier than the last one starts a new run (a reset put sim time back to 0): drop the old
            # run's messages.
            header = getattr(msg, 'header', None)
            if (not self.keep_all and header is not None and self.msgs
                    and header.stamp < self.msgs[-1].header.stamp):
                self.msgs.clear()
            self.msgs.append(msg)

    def restart(self):
        """Forgets the records before a new run (call it while the simulation is paused) and subscribes again.

        Clearing the list alone is not enough: the previous run's last messages can still be in flight (sent before
        the pause, read late by this process on a busy machine), and one stamped late in the old run satisfies
        until() at once (rostest drive once measured 0 m driven that way). Nor can they be told from the new run's
        by their stamps, since messages can be dropped on the way (a connection's queue drops the oldest). A new
        connection carries only what is published after it was made, and the old connection's stragglers are
        ignored by their generation. The topic must have no other subscriber in this process: rospy would share
        the old connection with it."""
        with self.lock:
            self.generation += 1
            self.msgs.clear()
        self.sub.unregister()
        self.sub = self._subscribe()
        self.wait_connected()

    def wait_connected(self, timeout=30.0):
        """Waits (wall time) for the publisher to connect, since sim time stands still while paused."""
        import time
        deadline = time.time() + timeout
        while self.sub.get_num_connections() == 0:
            if time.time() > deadline:
                raise AssertionError('nobody publishes %s' % self.sub.name)
            time.sleep(0.05)

    def until(self, t, timeout=120.0):
        """Waits (wall time) until a message stamped at or after sim time t has arrived."""
        import time
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.lock:
                if self.msgs and self.msgs[-1].header.stamp.to_sec() >= t:
                    return list(self.msgs)
            time.sleep(0.01)
        raise AssertionError('no message at sim time %.3f within %.0f s' % (t, timeout))


def car_program(name):
    """The path of car's program NAME as rosrun finds it: lib/car/NAME (the devel space's relay, or the install
    space's copy) before the source's scripts/NAME, so a test runs what the space under test holds."""
    import roslib.packages
    found = roslib.packages.find_node('car', name)
    if not found:
        raise AssertionError('car has no program %s (is the workspace built and sourced?)' % name)
    return found[0]


def wait_publisher(sub, node='/gazebo', timeout=300.0):
    """Waits (wall time, a bound for a hang only) until node's publisher has connected to the rospy Subscriber
    sub: a topic with several publishers (/rosout) connects them one at a time, and what node sends before its
    own connection is lost."""
    import time
    deadline = time.time() + timeout
    while node not in [c.callerid_pub for c in sub.impl.connections]:
        if time.time() > deadline:
            raise AssertionError('%s has not connected to %s within %.0f s' % (node, sub.name, timeout))
        time.sleep(0.05)


def command(v, w, topic='/cmd_vel'):
    """A latched cmd_vel publisher that has reached the simulator.

    queue_size=None publishes synchronously: publish() returns once the message is in the simulator's socket, so
    a service call made afterwards (unpause_physics) reaches the simulator's callback queue after it, and the
    simulator handles every queued callback before its next step. The command therefore holds from the first
    step, however busy the machine is."""
    import time
    pub = rospy.Publisher(topic, Twist, queue_size=None, latch=True)
    msg = Twist()
    msg.linear.x, msg.angular.z = v, w
    deadline = time.time() + 60
    while pub.get_num_connections() == 0:
        if time.time() > deadline:  # a latched message would reach it late, after the run began
            raise AssertionError('nobody subscribes to %s' % topic)
        time.sleep(0.05)
    pub.publish(msg)
    return pub


def call(name, srv_type=Empty, *args):
    rospy.wait_for_service(name, timeout=30)
    return rospy.ServiceProxy(name, srv_type)(*args)


def controller_states(ns):
    """name -> state ("running", "stopped") of each controller of <ns>/controller_manager; {} while it does not
    answer yet."""
    try:
        return {c.name: c.state for c in call(ns + '/controller_manager/list_controllers', ListControllers).controller}
    except rospy.ServiceException:
        return {}


def sim_now():
    """The simulator's own time [s], asked of it: it answers after every message already sent to it (a command
    published with simtest.command included). rospy.get_time() can lag it by seconds at rtf 0 on a busy machine
    (the test's /clock subscriber falls behind), so a start time taken from it may be before the command held."""
    from gazebo_msgs.srv import GetWorldProperties
    return call('/gazebo/get_world_properties', GetWorldProperties).sim_time


def wait_for(what, condition, timeout=120.0):
    """Polls condition() until it is true (returned). The bound is wall time against a hang, not a speed limit:
    tests wait on conditions, never for a while."""
    import time
    deadline = time.time() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.time() > deadline:
            raise AssertionError('%s: not within %.0f s' % (what, timeout))
        time.sleep(0.02)


def lookup(buf, target, source, stamp, timeout=120.0):
    """A transform from a tf2 buffer once it has arrived. lookup_transform's own timeout counts sim time, which
    stands still while the simulation is paused (a hang) and races ahead of the wall clock at rtf 0 (a spurious
    failure under load); this waits on the buffer in wall time instead."""
    wait_for('transform %s -> %s at %.3f' % (target, source, stamp.to_sec()),
             lambda: buf.can_transform(target, source, stamp), timeout)
    return buf.lookup_transform(target, source, stamp)


def xy(msg):
    return msg.pose.pose.position.x, msg.pose.pose.position.y


def at_time(msgs, t, within=None):
    """The message stamped nearest to sim time t. With within [s]: AssertionError when that message is farther
    from t than that, naming the stamps the recording holds (a connection's queue drops the oldest messages when
    a starved reader falls behind, so the one nearest t may be a later one)."""
    m = min(msgs, key=lambda m: abs(m.header.stamp.to_sec() - t))
    if within is not None and abs(m.header.stamp.to_sec() - t) > within:
        stamps = [x.header.stamp.to_sec() for x in msgs]
        raise AssertionError('no message within %.3f s of sim time %.3f: the nearest is stamped %.3f (%d messages '
                             'from %.3f to %.3f)' % (within, t, m.header.stamp.to_sec(), len(msgs), min(stamps),
                                                     max(stamps)))
    return m


def fit_circle(points):
    P = np.asarray(points)
    A = np.c_[2 * P, np.ones(len(P))]
    c = np.linalg.lstsq(A, (P ** 2).sum(1), rcond=None)[0]
    return c[:2], math.sqrt(c[2] + c[0] ** 2 + c[1] ** 2)
