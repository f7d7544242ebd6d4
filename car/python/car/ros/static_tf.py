"""static_transform_publisher: tf2_ros's program (Debian ships the library, not the program).

    static_transform_publisher x y z yaw pitch roll frame_id child_frame_id
    static_transform_publisher x y z qx qy qz qw frame_id child_frame_id

Publishes one latched message on /tf_static and stays alive. Leading '/' in frame names is dropped. The stamp is
the time at start (sim time under /use_sim_time); the node then reads no more time and leaves /clock.
"""
from __future__ import annotations

import math
import sys

USAGE = ('usage: static_transform_publisher x y z yaw pitch roll frame_id child_frame_id\n'
         '   or: static_transform_publisher x y z qx qy qz qw frame_id child_frame_id')


class UsageError(Exception):
    pass


def parse(args: list) -> tuple:
    """(translation, quaternion (x, y, z, w), frame_id, child_frame_id) from either argument form."""
    if len(args) not in (8, 9):
        raise UsageError('expected 8 or 9 arguments, got %d\n%s' % (len(args), USAGE))
    try:
        nums = [float(a) for a in args[:-2]]
    except ValueError as e:
        raise UsageError('%s\n%s' % (e, USAGE))
    if not all(math.isfinite(v) for v in nums):
        raise UsageError('values must be finite\n%s' % USAGE)
    frame, child = args[-2].lstrip('/'), args[-1].lstrip('/')
    if not frame or not child:
        raise UsageError('frame names must not be empty\n%s' % USAGE)
    if frame == child:
        raise UsageError("frame_id and child_frame_id are both '%s'" % frame)
    xyz = tuple(nums[:3])
    if len(nums) == 6:
        yaw, pitch, roll = nums[3:]
        cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
        cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
        cr, sr = math.cos(roll / 2), math.sin(roll / 2)
        q = (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
             cr * cp * cy + sr * sp * sy)
    else:
        n = math.sqrt(sum(v * v for v in nums[3:]))
        if n < 1e-9:
            raise UsageError('the quaternion has zero length')
        q = tuple(v / n for v in nums[3:])
    return xyz, q, frame, child


def main(argv=None) -> int:
    import rospy
    import tf2_ros
    from geometry_msgs.msg import TransformStamped

    args = rospy.myargv(sys.argv if argv is None else ['static_transform_publisher'] + list(argv))[1:]
    try:
        xyz, q, frame, child = parse(args)
    except UsageError as e:
        print('static_transform_publisher: %s' % e, file=sys.stderr)
        return 1
    rospy.init_node('static_transform_publisher', anonymous=True)
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id, t.child_frame_id = frame, child
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz
    t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = q
    broadcaster = tf2_ros.StaticTransformBroadcaster()
    broadcaster.sendTransform(t)
    rospy.loginfo('static_transform_publisher: %s -> %s at (%g %g %g), q (%g %g %g %g)', frame, child, *xyz, *q)
    # the latched message never changes: no more time to read
    from car.ros.rosclock import stop_clock
    stop_clock()
    rospy.spin()
    return 0
