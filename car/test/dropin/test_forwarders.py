"""The compat packages are thin forwarders (docs/COMPAT-dropins.md): each executable names its car target, the
package files carry upstream's names, and the launch files declare upstream's arguments."""
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

ROOT = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), '..', '..'))
COMPAT = os.path.join(os.path.dirname(ROOT), 'compat')

# executable -> the car entry point it forwards to (module function, or car executable exec'd by path)
FORWARDS = {
    'gazebo_ros/scripts/gzserver': 'from car.ros.gzserver import main',
    'gazebo_ros/scripts/gazebo': 'from car.ros.gzserver import gazebo_main',
    'gazebo_ros/scripts/gzclient': 'from car.ros.gzserver import client_main',
    'gazebo_ros/scripts/debug': 'from car.ros.gzserver import main',
    'gazebo_ros/scripts/perf': 'from car.ros.gzserver import main',
    'gazebo_ros/scripts/spawn_model': 'from car.ros.spawn import main',
    'gazebo/scripts/gzserver': 'from car.ros.gzserver import main',
    'gazebo/scripts/gazebo': 'from car.ros.gzserver import gazebo_main',
    'gazebo/scripts/gzclient': 'from car.ros.gzserver import client_main',
    'gazebo/scripts/spawn_model': 'from car.ros.spawn import main',
    'xacro/xacro': 'from car.xacro_tool import main',
    'xacro/xacro.py': 'from car.xacro_tool import main',
    'controller_manager/scripts/spawner': 'find_node("car", "spawner")',
    'controller_manager/scripts/unspawner': 'find_node("car", "unspawner")',
    'controller_manager/scripts/controller_manager': 'find_node("car", "controller_manager")',
}

# gazebo_ros noetic-devel empty_world.launch: every argument and its default
UPSTREAM_EMPTY_WORLD = {
    'paused': 'false', 'use_sim_time': 'true', 'extra_gazebo_args': '', 'gui': 'true', 'recording': 'false',
    'headless': 'false', 'debug': 'false', 'physics': 'ode', 'verbose': 'false', 'output': 'screen',
    'world_name': 'worlds/empty.world', 'respawn_gazebo': 'false', 'use_clock_frequency': 'false',
    'pub_clock_frequency': '100', 'enable_ros_network': 'true', 'server_required': 'false', 'gui_required': 'false',
}


@pytest.mark.parametrize('rel', sorted(FORWARDS))
def test_executable_forwards_to_car(rel):
    path = os.path.join(COMPAT, rel)
    pkg, name = rel.split('/', 1)
    if pkg == 'xacro':
        # run by path ($(find xacro)/xacro): executable
        assert os.access(path, os.X_OK), rel + ' is not executable'
    else:
        # run through catkin's relay only: not executable in the source, or `rosrun car spawn_model` (which searches
        # car's folder, compat/ included) would find it beside car's own
        assert not os.access(path, os.X_OK), rel + ' is executable'
        assert name in open(os.path.join(COMPAT, pkg, 'CMakeLists.txt')).read()
    assert FORWARDS[rel] in open(path).read()


@pytest.mark.parametrize('name', ['gazebo_ros', 'gazebo', 'xacro', 'controller_manager'])
def test_package_named_as_upstream(name):
    assert ET.parse(os.path.join(COMPAT, name, 'package.xml')).getroot().find('name').text == name


def test_empty_world_declares_every_upstream_argument_with_its_default():
    root = ET.parse(os.path.join(COMPAT, 'gazebo_ros', 'launch', 'empty_world.launch')).getroot()
    args = {a.get('name'): a.get('default') for a in root.findall('arg')}
    assert {k: args.get(k) for k in UPSTREAM_EMPTY_WORLD} == UPSTREAM_EMPTY_WORLD
    passed = {a.get('name') for a in root.find('include').findall('arg')}
    assert set(UPSTREAM_EMPTY_WORLD) <= passed


@pytest.mark.parametrize('name', ['elevator', 'mud', 'range', 'rubble', 'shapes', 'willowgarage'])
def test_upstream_world_launch_files_present(name):
    assert os.path.exists(os.path.join(COMPAT, 'gazebo_ros', 'launch', name + '_world.launch'))


def _env():
    env = dict(os.environ)
    env['PYTHONPATH'] = os.path.join(ROOT, 'python') + os.pathsep + env.get('PYTHONPATH', '')
    return env


def test_xacro_forwarder_expands_like_cars_xacro():
    src = os.path.join(ROOT, 'test', 'dropin', 'tiny.urdf.xacro')
    out = subprocess.run([sys.executable, os.path.join(COMPAT, 'xacro', 'xacro'), src, 'len:=0.25'],
                         capture_output=True, text=True, env=_env(), check=True).stdout
    # ${len*2} with len:=0.25 -> 0.5
    assert re.search(r'<box size="0.5 0.5 0.5"\s*/>', out)


def test_xacro_py_warns_deprecated_and_still_expands():
    src = os.path.join(ROOT, 'test', 'dropin', 'tiny.urdf.xacro')
    r = subprocess.run([sys.executable, os.path.join(COMPAT, 'xacro', 'xacro.py'), src],
                       capture_output=True, text=True, env=_env())
    assert r.returncode == 0 and 'deprecated' in r.stderr and '<box size="0.2 0.2 0.2"' in r.stdout


def test_gzserver_forwarder_reports_bad_argument():
    r = subprocess.run([sys.executable, os.path.join(COMPAT, 'gazebo_ros', 'scripts', 'gzserver'), '--seed', 'x'],
                       capture_output=True, text=True, env=_env())
    assert (r.returncode, r.stderr.strip()) == (2, 'gzserver: --seed x: not an integer')


def test_controller_manager_forwarder_execs_car_script_with_arguments(tmp_path):
    # a stand-in `car` package whose spawner echoes its arguments: the forwarder must exec it with them unchanged
    pkg = tmp_path / 'car'
    (pkg / 'scripts').mkdir(parents=True)
    (pkg / 'package.xml').write_text('<package format="2"><name>car</name><version>0.0.0</version>'
                                     '<description>x</description><maintainer email="a@b.c">x</maintainer>'
                                     '<license>BSD</license></package>')
    spawner = pkg / 'scripts' / 'spawner'
    spawner.write_text('#!/bin/sh\necho "ARGS $*"\n')
    spawner.chmod(0o755)
    env = _env()
    env['ROS_PACKAGE_PATH'] = str(tmp_path)
    env['CMAKE_PREFIX_PATH'] = str(tmp_path / 'none')
    r = subprocess.run([sys.executable, os.path.join(COMPAT, 'controller_manager', 'scripts', 'spawner'),
                        '--namespace', '/r1', 'joint_state_controller', 'diff_drive_controller'],
                       capture_output=True, text=True, env=env)
    assert r.stdout.strip() == 'ARGS --namespace /r1 joint_state_controller diff_drive_controller', r.stderr
