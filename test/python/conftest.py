"""Shared fixtures: paths into the package, and the tools run as programs."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, 'test', 'data')
URDF = os.path.join(ROOT, 'urdf')


def run_tool(name, *args):
    """Runs scripts/NAME with this interpreter; returns the CompletedProcess (text mode)."""
    return subprocess.run([sys.executable, os.path.join(ROOT, 'scripts', name)] + list(args),
                          capture_output=True, text=True, timeout=120)


@pytest.fixture(scope='session')
def car04_xml():
    from car import xacro_tool
    return xacro_tool.expand(os.path.join(URDF, 'car_camera_lidar04.xacro'))
