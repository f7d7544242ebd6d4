"""gzserver's command line (car.ros.gzserver, docs/COMPAT-dropins.md): what each Gazebo 11 option becomes."""
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), '..', '..', 'python'))
from car.ros import gzserver  # noqa: E402
from car.ros.gzserver import UsageError, node_argv, parse  # noqa: E402


def test_empty_world_launch_line_as_gazebo_ros_builds_it():
    # empty_world.launch with paused:=true verbose:=true: "-u  --verbose -e ode  worlds/empty.world" + roslaunch's
    o = parse(['-u', '', '--verbose', '-e', 'ode', '', 'worlds/empty.world', '__name:=gazebo', '__log:=/tmp/x.log'])
    assert (o['paused'], o['verbose'], o['engine'], o['world']) == (True, True, 'ode', 'worlds/empty.world')
    assert node_argv(o) == ['__name:=gazebo', '__log:=/tmp/x.log', '_world_name:=worlds/empty.world',
                            '_paused:=true']


def test_world_file_only():
    assert node_argv(parse(['/w/box.world'])) == ['_world_name:=/w/box.world']


def test_no_world_leaves_the_name_to_the_node():
    assert node_argv(parse(['--verbose'])) == []


def test_seed_and_iters_become_integer_parameters():
    o = parse(['--seed', '7', '--iters=250', 'w.world'])
    assert node_argv(o) == ['_world_name:=w.world', '_seed:=7', '_iters:=250']


def test_remappings_pass_through_unchanged():
    assert parse(['cmd_vel:=/a/cmd_vel', '_rtf:=0'])['ros_args'] == ['cmd_vel:=/a/cmd_vel', '_rtf:=0']


def test_gazebo_ros_system_plugins_accepted_silently_from_any_folder():
    o = parse(['-s', '/opt/ros/noetic/lib/libgazebo_ros_api_plugin.so', '-s', 'libgazebo_ros_paths_plugin.so'])
    assert o['warnings'] == [] and len(o['plugins']) == 2


def test_other_system_plugin_goes_to_the_node_with_the_command_line():
    # -s of a library car does not serve: no warning; the node gets the file and gzserver's argv (YAML lists)
    o = parse(['-u', '-s', 'libmy_system_plugin.so', '__name:=gazebo', 'w.world'])
    assert o['warnings'] == [] and o['system_plugins'] == ['libmy_system_plugin.so']
    assert node_argv(o) == ['__name:=gazebo', '_world_name:=w.world', '_paused:=true',
                            '_system_plugins:=["libmy_system_plugin.so"]',
                            '_server_argv:=["gzserver", "-u", "-s", "libmy_system_plugin.so", "w.world"]']


def test_gui_plugin_warned_by_name_in_gazebo():
    o = parse(['-g', 'libmy_gui.so'], program='gazebo')
    assert o['warnings'] == ['-g libmy_gui.so: not loaded: car is headless (no GUI plug-ins)']
    assert o['system_plugins'] == []


def test_gui_plugin_refused_by_gzserver_accepted_by_gazebo():
    with pytest.raises(UsageError, match='^-g: '):
        parse(['-g', 'libgazebo_ros_api_plugin.so'])
    assert parse(['-g', 'libgazebo_ros_api_plugin.so'], program='gazebo')['warnings'] == []


def test_record_options_warned_each():
    o = parse(['-r', '--record_path', '/tmp/log', '--record_period', '0.5'])
    assert [w.split(':')[0] for w in o['warnings']] == ['-r', '--record_path', '--record_period']


def test_unknown_engine_names_the_argument():
    with pytest.raises(UsageError, match=r'^-e havok: unknown physics engine'):
        parse(['-e', 'havok'])


@pytest.mark.parametrize('argv,start', [
    (['--seed', 'x'], '--seed x: not an integer'),
    (['--iters', '-3'], '--iters -3: must be >= 0'),
    (['-e'], '-e: needs a value'),
    (['--frobnicate'], '--frobnicate: unknown option'),
    (['a.world', 'b.world'], 'b.world: a second world file'),
    (['-p', 'state.log'], '-p state.log: car cannot play back'),
])
def test_bad_arguments_named(argv, start):
    with pytest.raises(UsageError) as e:
        parse(argv)
    assert str(e.value).startswith(start)


def test_main_reports_bad_argument_with_status_2(capsys):
    assert gzserver.main(['--iters', 'ten']) == 2
    assert capsys.readouterr().err.strip() == 'gzserver: --iters ten: not an integer'


def test_main_execs_sim_node_with_the_translated_arguments(monkeypatch, capsys):
    calls = []
    monkeypatch.setattr(gzserver, '_sim_node', lambda: '/x/sim_node')
    monkeypatch.setattr(os, 'execv', lambda exe, args: calls.append((exe, args)))
    gzserver.main(['-e', 'bullet', '-s', 'libfoo.so', 'w.world', '__name:=gazebo'])
    assert calls == [('/x/sim_node', ['/x/sim_node', '__name:=gazebo', '_world_name:=w.world',
                                      '_system_plugins:=["libfoo.so"]',
                                      '_server_argv:=["gzserver", "-e", "bullet", "-s", "libfoo.so", "w.world"]'])]
    out = capsys.readouterr()
    assert out.out.count('physics engine "bullet"') == 1
    assert out.err == ''
