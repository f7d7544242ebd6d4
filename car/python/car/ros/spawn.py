"""spawn_model: gazebo_ros's spawn_model for car's simulator.

    spawn_model -urdf -param robot_description -model mycar [-x X -y Y -z Z -R R -P P -Y Y]
                [-robot_namespace NS] [-reference_frame F] [-gazebo_namespace /gazebo] [-timeout S] [-unpause]
    spawn_model -urdf -file car.urdf -model mycar ...
    spawn_model -urdf -stdin -model mycar ... < car.urdf
                [-J JOINT VALUE]... [-wait MODEL] [-package_to_model]
    spawn_model -sdf -file model.sdf | -param P | -stdin -model NAME ...
    spawn_model -sdf -database MODEL -model NAME ...   (model://MODEL through GAZEBO_MODEL_PATH and car's models/)
"""
from __future__ import annotations

import math
import sys

FLOAT_FLAGS = {'-x': 'x', '-y': 'y', '-z': 'z', '-R': 'roll', '-P': 'pitch', '-Y': 'yaw', '-timeout': 'timeout'}
STRING_FLAGS = {'-param': 'param', '-file': 'file', '-database': 'database', '-model': 'model', '-robot_namespace': 'robot_namespace',
                '-reference_frame': 'reference_frame', '-gazebo_namespace': 'gazebo_namespace'}


class UsageError(Exception):
    pass


def parse_args(argv: list) -> dict:
    """gazebo_ros's argument form, single-dash flags."""
    # robot_namespace None = not given: main() puts the caller's namespace, as gazebo_ros's spawn_model does
    opts = {'x': 0.0, 'y': 0.0, 'z': 0.0, 'roll': 0.0, 'pitch': 0.0, 'yaw': 0.0, 'timeout': 60.0,
            'robot_namespace': None, 'reference_frame': '', 'gazebo_namespace': '/gazebo', 'format': None,
            'unpause': False, 'param': None, 'file': None, 'database': None, 'model': None,
            'stdin': False, 'joints': [], 'wait': None, 'package_to_model': False}
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ('-urdf', '-sdf'):
            opts['format'] = a[1:]
            i += 1
        elif a in ('-unpause', '-stdin', '-package_to_model'):
            opts[a[1:]] = True
            i += 1
        elif a == '-J':
            # -J JOINT VALUE, repeatable: initial joint positions (set_model_configuration after the spawn)
            if i + 2 >= len(argv):
                raise UsageError('-J needs a joint name and a position')
            try:
                value = float(argv[i + 2])
            except ValueError:
                raise UsageError('-J %s needs a number, got %r' % (argv[i + 1], argv[i + 2]))
            if not math.isfinite(value):
                raise UsageError('-J %s needs a finite number, got %r' % (argv[i + 1], argv[i + 2]))
            opts['joints'].append((argv[i + 1], value))
            i += 3
        elif a == '-wait':
            if i + 1 >= len(argv):
                raise UsageError('-wait needs a model name')
            opts['wait'] = argv[i + 1]
            i += 2
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
        raise UsageError('say -urdf or -sdf')
    if [opts['param'] is not None, opts['file'] is not None, opts['database'] is not None,
            opts['stdin']].count(True) != 1:
        raise UsageError('give exactly one of -param NAME, -file FILE, -database MODEL and -stdin')
    return opts


# gazebo_ros spawn_model's -database document: the server includes model://NAME (docs/COMPAT-sdf.md 13)
MODEL_DATABASE_TEMPLATE = """\
<sdf version="1.4">
    <world name="default">
        <include>
            <uri>model://{}</uri>
        </include>
    </world>
</sdf>"""


def service_name(opts: dict) -> str:
    """The spawn service gazebo_ros's spawn_model calls: spawn_sdf_model for -sdf, spawn_urdf_model for -urdf."""
    return opts['gazebo_namespace'].rstrip('/') + ('/spawn_sdf_model' if opts['format'] == 'sdf'
                                                    else '/spawn_urdf_model')


def default_robot_namespace() -> str:
    """The caller's namespace, as gazebo_ros's spawn_model takes it: rospy.get_namespace()."""
    import rospy
    return rospy.get_namespace()


def package_to_model(xml: str) -> str:
    """gazebo_ros's -package_to_model: every <mesh filename="package://P/..."> becomes model://P/...; the rest of
    the document is unchanged."""
    import xml.etree.ElementTree as ET
    root = ET.fromstring(xml)
    for mesh in root.iter('mesh'):
        f = mesh.get('filename')
        if f is not None and f.startswith('package://'):
            mesh.set('filename', 'model://' + f[len('package://'):])
    return ET.tostring(root, encoding='unicode')


def check_xml(xml: str, source: str) -> None:
    """Raises UsageError naming the source, line and parser reason when xml is not well-formed."""
    import xml.etree.ElementTree as ET
    try:
        ET.fromstring(xml)
    except ET.ParseError as e:
        raise UsageError('%s: invalid XML: %s' % (source, e))


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
    from gazebo_msgs.msg import ModelStates
    from gazebo_msgs.srv import SetModelConfiguration, SpawnModel

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
    ns = o['gazebo_namespace'].rstrip('/')
    if o['wait']:
        # -wait MODEL: until MODEL is in /gazebo/model_states
        seen = []
        sub = rospy.Subscriber(ns + '/model_states', ModelStates, lambda m: seen.append(o['wait'] in m.name))
        rospy.loginfo('spawn_model: waiting for model %s before proceeding', o['wait'])
        rate = rospy.Rate(10)
        while not rospy.is_shutdown() and not any(seen):
            rate.sleep()
        sub.unregister()
        if rospy.is_shutdown():
            return 0
    if o['stdin']:
        xml = sys.stdin.read()
        if xml == '':
            rospy.logfatal('spawn_model: -stdin: standard input was empty')
            return 1
    elif o['database'] is not None:
        rospy.loginfo('spawn_model: loading model XML from the model database (model://%s)', o['database'])
        xml = MODEL_DATABASE_TEMPLATE.format(o['database'])
    elif o['param'] is not None:
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
    source = 'stdin' if o['stdin'] else (o['file'] or o['param'] or o['database'])
    try:
        check_xml(xml, source)
    except UsageError as e:
        rospy.logfatal('spawn_model: %s', e)
        return 1
    if o['package_to_model']:
        xml = package_to_model(xml)
    service = service_name(o)
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
    if o['joints']:
        # -J: one set_model_configuration call with every joint, as gazebo_ros's spawn_model
        rospy.wait_for_service(ns + '/set_model_configuration', timeout=o['timeout'])
        res = rospy.ServiceProxy(ns + '/set_model_configuration', SetModelConfiguration)(
            o['model'], '', [j for j, _ in o['joints']], [v for _, v in o['joints']])
        if not res.success:
            rospy.logfatal('spawn_model: -J: %s', res.status_message)
            return 1
    if o['unpause']:
        rospy.wait_for_service(ns + '/unpause_physics', timeout=o['timeout'])
        rospy.ServiceProxy(ns + '/unpause_physics', Empty)()
    return 0
