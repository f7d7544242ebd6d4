"""spawn_model: gazebo_ros's spawn_model for car's simulator.

    spawn_model -urdf -param robot_description -model mycar [-x X -y Y -z Z -R R -P P -Y Y]
                [-robot_namespace NS] [-reference_frame F] [-gazebo_namespace /gazebo] [-timeout S] [-unpause]
    spawn_model -urdf -file car.urdf -model mycar ...
"""
from __future__ import annotations

import math
import sys

FLOAT_FLAGS = {'-x': 'x', '-y': 'y', '-z': 'z', '-R': 'roll', '-P': 'pitch', '-Y': 'yaw', '-timeout': 'timeout'}
STRING_FLAGS = {'-param': 'param', '-file': 'file', '-model': 'model', '-robot_namespace': 'robot_namespace',
                '-reference_frame': 'reference_frame', '-gazebo_namespace': 'gazebo_namespace'}


class UsageError(Exception):
    pass


def parse_args(argv: list) -> dict:
    """gazebo_ros's argument form, single-dash flags."""
    # robot_namespace None = not given: main() puts the caller's namespace, as gazebo_ros's spawn_model does
    opts = {'x': 0.0, 'y': 0.0, 'z': 0.0, 'roll': 0.0, 'pitch': 0.0, 'yaw': 0.0, 'timeout': 60.0,
            'robot_namespace': None, 'reference_frame': '', 'gazebo_namespace': '/gazebo', 'format': None,
            'unpause': False, 'param': None, 'file': None, 'model': None}
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ('-urdf', '-sdf'):
            opts['format'] = a[1:]
            i += 1
        elif a == '-unpause':
            opts['unpause'] = True
            i += 1
        elif a in FLOAT_FLAGS or a in STRING_FLAGS:
            if i + 1 >= len(argv):
                raise UsageError('%s needs a value' % a)
            value = argv[i + 1]
            if a in FLOAT_FLAGS:
                try:
                    opts[FLOAT_FLAGS[a]] = float(value)
                except ValueError:
                    raise UsageError('%s needs a number, got %r' % (a, value))
                if not math.isfinite(opts[FLOAT_FLAGS[a]]):
                    raise UsageError('%s needs a finite number, got %r' % (a, value))
            else:
                opts[STRING_FLAGS[a]] = value
            i += 2
        else:
            raise UsageError('unknown argument %r' % a)
    if opts['model'] is None:
        raise UsageError('-model NAME is required')
    if opts['format'] is None:
        raise UsageError('say -urdf (car simulates URDF robots)')
    if opts['format'] == 'sdf':
        raise UsageError('-sdf: SDF robot models are not supported by car yet; give a URDF with -urdf')
    if (opts['param'] is None) == (opts['file'] is None):
        raise UsageError('give exactly one of -param NAME and -file FILE')
    return opts


def default_robot_namespace() -> str:
    """The caller's namespace, as gazebo_ros's spawn_model takes it: rospy.get_namespace()."""
    import rospy
    return rospy.get_namespace()


def quaternion(roll: float, pitch: float, yaw: float):
    """(x, y, z, w) of R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def main(argv=None) -> int:
    import rospy
    from geometry_msgs.msg import Pose
    from std_srvs.srv import Empty
    from car.srv import SpawnModel

    argv = rospy.myargv(sys.argv if argv is None else argv)[1:]
    try:
        o = parse_args(argv)
    except UsageError as e:
        print('spawn_model: error: %s' % e, file=sys.stderr)
        return 2
    rospy.init_node('spawn_model', anonymous=True)
    if o['robot_namespace'] is None:
        # gazebo_ros spawn_model: -robot_namespace defaults to rospy.get_namespace() ("/" at the root, "/r1/" in
        # <group ns="r1">); the spawn service adds it to every plug-in without <robotNamespace>
        o['robot_namespace'] = default_robot_namespace()
    if o['param'] is not None:
        if not rospy.has_param(o['param']):
            rospy.logfatal('spawn_model: parameter %s is not set', o['param'])
            return 1
        xml = rospy.get_param(o['param'])
    else:
        try:
            with open(o['file'], encoding='utf-8') as f:
                xml = f.read()
        except OSError as e:
            rospy.logfatal('spawn_model: %s: %s', o['file'], e.strerror)
            return 1
    ns = o['gazebo_namespace'].rstrip('/')
    service = ns + '/spawn_urdf_model'
    try:
        rospy.wait_for_service(service, timeout=o['timeout'])
    except rospy.ROSException:
        rospy.logfatal('spawn_model: %s did not appear within %g s; is the simulator running?', service, o['timeout'])
        return 1
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = o['x'], o['y'], o['z']
    (pose.orientation.x, pose.orientation.y, pose.orientation.z,
     pose.orientation.w) = quaternion(o['roll'], o['pitch'], o['yaw'])
    res = rospy.ServiceProxy(service, SpawnModel)(o['model'], xml, o['robot_namespace'], pose, o['reference_frame'])
    if not res.success:
        rospy.logfatal('spawn_model: %s', res.status_message)
        return 1
    rospy.loginfo('spawn_model: %s: %s', o['model'], res.status_message)
    if o['unpause']:
        rospy.wait_for_service(ns + '/unpause_physics', timeout=o['timeout'])
        rospy.ServiceProxy(ns + '/unpause_physics', Empty)()
    return 0
