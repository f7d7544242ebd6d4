"""spawn_model's gazebo_ros argument form."""
import math

import pytest

from car.ros import spawn


def test_urdf_param_and_pose():
    o = spawn.parse_args('-urdf -param robot_description -model mycar -x 1 -y -2 -Y 1.5'.split())
    assert (o['format'], o['param'], o['model']) == ('urdf', 'robot_description', 'mycar')
    assert (o['x'], o['y'], o['z'], o['yaw']) == (1.0, -2.0, 0.0, 1.5)


def test_robot_namespace_and_file():
    o = spawn.parse_args('-urdf -file car.urdf -model b -robot_namespace b'.split())
    assert (o['file'], o['robot_namespace']) == ('car.urdf', 'b')


def test_yaw_quaternion():
    x, y, z, w = spawn.quaternion(0.0, 0.0, math.pi / 2)
    assert (x, y, z, w) == pytest.approx((0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)))


@pytest.mark.parametrize('args, message', [
    ('-urdf -param robot_description', '-model NAME is required'),
    ('-param robot_description -model m', 'say -urdf'),
    ('-urdf -model m', 'give exactly one of -param NAME, -file FILE, -database MODEL and -stdin'),
    ('-urdf -stdin -file f -model m', 'give exactly one of -param NAME, -file FILE, -database MODEL and -stdin'),
    ('-urdf -stdin -model m -J spin', '-J needs a joint name and a position'),
    ('-urdf -stdin -model m -J spin half', "-J spin needs a number, got 'half'"),
    ('-urdf -stdin -model m -J spin nan', "-J spin needs a finite number"),
    ('-urdf -stdin -model m -wait', '-wait needs a model name'),
    ('-urdf -param p -model m -x one', "-x needs a number, got 'one'"),
    ('-urdf -param p -model m -bogus', "unknown argument '-bogus'"),
    ('-sdf -database m -file m.sdf -model m', 'give exactly one of'),
])
def test_bad_arguments(args, message):
    with pytest.raises(spawn.UsageError, match=message):
        spawn.parse_args(args.split())


def test_robot_namespace_not_given_is_left_for_the_callers_namespace():
    # gazebo_ros: the default is rospy.get_namespace(), filled in by main() once the node knows its namespace
    o = spawn.parse_args('-urdf -param robot_description -model b'.split())
    assert o['robot_namespace'] is None


def test_stdin_joints_wait_and_package_to_model():
    o = spawn.parse_args('-urdf -stdin -model m -J a 0.5 -J b -1 -wait other -package_to_model'.split())
    assert o['stdin'] and o['package_to_model']
    assert o['joints'] == [('a', 0.5), ('b', -1.0)]
    assert o['wait'] == 'other'


def test_package_to_model_rewrites_mesh_uris_only():
    xml = ('<robot name="r"><link name="l"><visual><geometry><mesh filename="package://my_pkg/meshes/a.stl"/>'
           '</geometry></visual><collision><geometry><mesh filename="file:///tmp/b.stl"/></geometry></collision>'
           '</link><gazebo><plugin filename="package://not_a_mesh"/></gazebo></robot>')
    out = spawn.package_to_model(xml)
    assert 'filename="model://my_pkg/meshes/a.stl"' in out
    assert 'filename="file:///tmp/b.stl"' in out
    assert 'filename="package://not_a_mesh"' in out


def test_malformed_xml_names_the_source():
    with pytest.raises(spawn.UsageError, match=r'stdin: invalid XML: mismatched tag: line 1'):
        spawn.check_xml('<robot><link></robot>', 'stdin')
