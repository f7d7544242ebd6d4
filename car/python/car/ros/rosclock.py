"""The /clock subscription of car's own rospy nodes that read the time only as they start."""
from __future__ import annotations


def stop_clock() -> bool:
    """Ends this rospy node's /clock subscription, which init_node makes under /use_sim_time.

    The simulator sends /clock at 100 Hz of sim time (gazebo_ros's pub_clock_frequency): thousands of messages a
    wall second when it runs faster than real time, each one a Python callback in every rospy node. rospy's time
    then stands still at the last clock it read, so only a node that no longer reads the time may call this.
    Returns whether there was a subscription to end."""
    from rospy.impl import simtime
    sub = getattr(simtime, '_clock_sub', None)
    if sub is None:
        return False
    sub.unregister()
    simtime._clock_sub = None
    return True
