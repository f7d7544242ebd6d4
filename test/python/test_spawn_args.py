"""spawn_model's gazebo_ros argument form."""
import math

import pytest

from car import spawn


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
    ('-urdf -model m', 'give exactly one of -param NAME and -file FILE'),
    ('-urdf -param p -model m -x one', "-x needs a number, got 'one'"),
    ('-urdf -param p -model m -bogus', "unknown argument '-bogus'"),
    ('-sdf -file m.sdf -model m', 'SDF robot models are not supported'),
])
def test_bad_arguments(args, message):
    with pytest.raises(spawn.UsageError, match=message):
        spawn.parse_args(args.split())


def test_robot_namespace_not_given_is_left_for_the_callers_namespace():
    # gazebo_ros: the default is rospy.get_namespace(), filled in by main() once the node knows its namespace
    o = spawn.parse_args('-urdf -param robot_description -model b'.split())
    assert o['robot_namespace'] is None
