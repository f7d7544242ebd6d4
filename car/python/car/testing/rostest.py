"""car.testing's waits for rostest test nodes: the simulator is started by the .test file (empty_world.launch or
sim.launch), and the test node only waits on it, in sim time.

    from car.testing import rostest as simtest
    simtest.init('my_test')                       # rospy node with /use_sim_time
    simtest.unpause()                             # if the launch file started it paused
    msg = simtest.wait_message('/odom', 'nav_msgs/Odometry', where=lambda m: m.pose.pose.position.x > 2, timeout=20)
    simtest.until(lambda: done[0], timeout=5, what='the dock signal')

Every timeout is sim seconds counted from the call (the /clock the simulator publishes). These waits do not pause
or unpause the simulation (the launch file's `paused` decides): while it is paused no sim time passes, and a wait
fails only after `hang_s` wall seconds with sim time standing still, saying so.
"""
import rospy

from car.testing import waits

_clock = {}
unpause = waits.unpause
pause = waits.pause
sim_now = waits.sim_now


def init(name='car_sim_check'):
    """Starts this process's rospy node (anonymous) once, and its /clock reader."""
    if not rospy.core.is_initialized():
        rospy.init_node(name, anonymous=True)
    if 'clock' not in _clock:
        _clock['clock'] = waits.SimClock()
    return _clock['clock']


def until(predicate, timeout=10.0, what=None, hang_s=60.0):
    """Waits until predicate() is truthy (returns its value) for at most `timeout` sim seconds; else
    AssertionError naming what it waited for."""
    return waits.wait_sim(init(), predicate, timeout, waits.describe(predicate, what), run=False, hang_s=hang_s)


def wait_message(topic, msg_type, where=None, timeout=10.0, what=None, hang_s=60.0):
    """The first message on topic after the call for which where(msg) is true, within `timeout` sim seconds."""
    return waits.wait_message(init(), topic, msg_type, where, timeout, what, run=False, hang_s=hang_s)


def run_for(seconds, hang_s=60.0):
    """Waits until `seconds` of sim time have passed (the simulation must be running)."""
    clock = init()
    target = sim_now() + seconds
    waits.wait_sim(clock, lambda: clock.now() >= target, seconds + 1.0, 'run_for(%g)' % seconds, run=False,
                   hang_s=hang_s)
    return clock.now()
