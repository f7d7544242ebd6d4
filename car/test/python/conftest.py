"""Shared fixtures: paths into the package, and the tools run as programs."""
import os
import subprocess
import sys

import pytest

# The repository, whether pytest runs it from the checkout or through catkin's link farm (.ws/src/car/test/python)
# car's package folder, and the repository holding it beside compat/, tools/ and docs/
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
REPO = os.path.dirname(ROOT)
DATA = os.path.join(ROOT, 'test', 'data')
URDF = os.path.join(ROOT, 'urdf')
# The devel space whose generated message headers the C++ checks read: catkin's run_tests passes it
# (CAR_DEVEL_PREFIX); run by hand, the workspace tools/setup.sh makes.
DEVEL = os.environ.get('CAR_DEVEL_PREFIX') or os.path.join(REPO, '.ws', 'devel')
# Where a real (non-drop-in) ROS package is installed, tools/setup.sh leaves compat/NAME out of the workspace.
SYSTEM_PREFIXES = ('/opt/ros/noetic', '/usr', '/usr/local')


def generated_header(pkg, name):
    """The path of the C++ header catkin generated for message or service pkg/name from compat/pkg. Skips (naming
    the real package) only where a real pkg is installed, so compat/'s is not built; with compat/ in use a missing
    header is a failure of the build, and the test that reads it fails."""
    for prefix in SYSTEM_PREFIXES:
        if os.path.isfile(os.path.join(prefix, 'share', pkg, 'package.xml')):
            pytest.skip('a real %s is installed in %s: compat/%s is not built' % (pkg, prefix, pkg))
    return os.path.join(DEVEL, 'include', pkg, name + '.h')


def run_tool(name, *args):
    """Runs scripts/NAME with this interpreter; returns the CompletedProcess (text mode)."""
    return subprocess.run([sys.executable, os.path.join(ROOT, 'scripts', name)] + list(args),
                          capture_output=True, text=True, timeout=120)


@pytest.fixture(scope='session')
def car04_xml():
    from car import xacro_tool
    return xacro_tool.expand(os.path.join(URDF, 'car_camera_lidar04.xacro'))
