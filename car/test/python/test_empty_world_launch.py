"""launch/empty_world.launch takes every argument of gazebo_ros's Noetic empty_world.launch, and each does what
docs/COMPAT.md says: the launch file is loaded with roslaunch's own loader and the resulting node and parameters
are checked, one argument per test."""
import os
import xml.etree.ElementTree as ET

import pytest

from conftest import ROOT

LAUNCH = os.path.join(ROOT, 'launch', 'empty_world.launch')

# The <arg> names of gazebo_ros noetic-devel gazebo_ros/launch/empty_world.launch (f9e1a46), in its order.
UPSTREAM_ARGS = ['paused', 'use_sim_time', 'extra_gazebo_args', 'gui', 'recording', 'headless', 'debug', 'physics',
                 'verbose', 'output', 'world_name', 'respawn_gazebo', 'use_clock_frequency', 'pub_clock_frequency',
                 'enable_ros_network', 'server_required', 'gui_required']


def load(*args):
    """(the sim node, {param: value}) of empty_world.launch with NAME:=VALUE arguments."""
    import roslaunch.config
    import roslaunch.xmlloader
    cfg = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(LAUNCH, cfg, argv=['roslaunch'] + list(args), verbose=False)
    [node] = cfg.nodes
    return node, {k: p.value for k, p in cfg.params.items()}


def test_every_upstream_argument_is_declared():
    declared = [a.get('name') for a in ET.parse(LAUNCH).getroot().findall('arg')]
    assert [a for a in UPSTREAM_ARGS if a not in declared] == []


def test_defaults_are_upstreams():
    node, params = load()
    assert (node.package, node.type, node.name) == ('car', 'sim_node', 'gazebo')
    assert (node.respawn, node.required, node.output) == (False, False, 'screen')
    assert params['/use_sim_time'] is True
    assert params['/gazebo/paused'] is False
    assert params['/gazebo/enable_ros_network'] is True
    assert '/gazebo/pub_clock_frequency' not in params


def test_upstream_default_world_is_the_built_in_empty_world():
    _, params = load()
    assert params['/gazebo/world_name'] == ''


def test_world_name():
    _, params = load('world_name:=/tmp/some.world')
    assert params['/gazebo/world_name'] == '/tmp/some.world'


def test_paused():
    _, params = load('paused:=true')
    assert params['/gazebo/paused'] is True


def test_use_sim_time():
    _, params = load('use_sim_time:=false')
    assert params['/use_sim_time'] is False


def test_output():
    node, _ = load('output:=log')
    assert node.output == 'log'


def test_respawn_gazebo():
    node, _ = load('respawn_gazebo:=true')
    assert node.respawn is True


def test_server_required():
    node, _ = load('server_required:=true')
    assert node.required is True


def test_pub_clock_frequency_needs_use_clock_frequency():
    _, params = load('pub_clock_frequency:=25')
    assert '/gazebo/pub_clock_frequency' not in params
    _, params = load('use_clock_frequency:=true', 'pub_clock_frequency:=25')
    assert params['/gazebo/pub_clock_frequency'] == 25


def test_enable_ros_network():
    _, params = load('enable_ros_network:=false')
    assert params['/gazebo/enable_ros_network'] is False


@pytest.mark.parametrize('arg, value', [('gui', 'false'), ('gui_required', 'true'), ('headless', 'true'),
                                        ('debug', 'true'), ('verbose', 'true'), ('recording', 'true'),
                                        ('physics', 'bullet'), ('extra_gazebo_args', '--lockstep')])
def test_gazebo_only_arguments_are_named_for_the_log(arg, value):
    _, params = load('%s:=%s' % (arg, value))
    assert ('%s:=%s' % (arg, value)) in params['/gazebo/ignored_launch_args'] or \
        ("%s:='%s'" % (arg, value)) in params['/gazebo/ignored_launch_args']


def test_rtf_is_cars_own():
    _, params = load('rtf:=0')
    assert params['/gazebo/rtf'] == 0
