"""The Python side split by whether it needs a ROS master: `import car`, `import car.gym`, every module of car/ outside
car.ros, and the car.testing plug-in import nothing of ROS, each in a fresh interpreter that could import rospy
(its sys.modules looked at after the import); the modules that talk to ROS live in car.ros."""
import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT

PACKAGE = os.path.join(ROOT, 'python', 'car')
# top-level packages of ROS 1's Python side (client library, tools, generated messages)
ROS_ROOTS = ('rospy', 'roslib', 'rospkg', 'rosgraph', 'roslaunch', 'rosparam', 'genpy', 'tf2_ros', 'actionlib')
# what car/ itself holds besides car.ros: every .py module, and the pytest plug-in package
OFFLINE = sorted(['car'] + ['car.' + f[:-3] for f in os.listdir(PACKAGE) if f.endswith('.py') and f != '__init__.py']
                 + ['car.testing'])
CHECK = '''
import importlib, sys
importlib.import_module(sys.argv[1])
roots = set(sys.argv[2:])
print(' '.join(sorted(m for m in sys.modules if m.split('.')[0] in roots or m.split('.')[0].endswith('_msgs'))))
'''


def ros_modules_after_import(name):
    p = subprocess.run([sys.executable, '-c', CHECK, name] + list(ROS_ROOTS), capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, 'import %s failed:\n%s' % (name, p.stderr[-3000:])
    return p.stdout.split()


def test_rospy_is_there_to_be_imported():
    # the checks below mean something only where rospy could be imported (the catkin run; Debian's python3-rospy)
    p = subprocess.run([sys.executable, '-c', 'import rospy'], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr[-2000:]


@pytest.mark.parametrize('name', OFFLINE)
def test_module_imports_nothing_of_ros(name):
    assert ros_modules_after_import(name) == [], name


def test_the_ros_modules_live_in_car_ros():
    # a module of car/ outside car.ros names rospy in no import, not even inside a function
    found = []
    for f in sorted(os.listdir(PACKAGE)):
        if f.endswith('.py'):
            with open(os.path.join(PACKAGE, f), encoding='utf-8') as src:
                found += ['%s:%d' % (f, i + 1) for i, line in enumerate(src)
                          if re.match(r'\s*(import|from)\s+rospy\b', line)]
    assert found == []


def test_car_ros_holds_the_nodes():
    # the nine modules that talk to a master (and their /clock helper, and world_tool map --publish's)
    names = sorted(f[:-3] for f in os.listdir(os.path.join(PACKAGE, 'ros')) if f.endswith('.py'))
    assert names == ['__init__', 'arbotix', 'control', 'gzserver', 'map_publisher', 'rosclock', 'spawn', 'static_tf',
                     'teleop', 'web_view_node', 'world_markers']
