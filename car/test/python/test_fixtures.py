"""The shipped files: the seed's xacro files compose as the tutorial composes them, and the expanded
fixture the C++ tests read stays equal to a fresh expansion."""
import os
import re
import xml.etree.ElementTree as ET

import pytest
import yaml

from car import xacro_tool
from conftest import DATA, ROOT, URDF

AGGREGATES = {
    'car_camera_lidar.xacro': ['inertial', 'car', 'camera', 'lidar'],
    'car_camera_lidar01.xacro': ['inertial', 'car', 'camera', 'lidar', 'move'],
    'car_camera_lidar02.xacro': ['inertial', 'car', 'camera', 'lidar', 'move', 'lidar01'],
    'car_camera_lidar03.xacro': ['inertial', 'car', 'camera', 'lidar', 'move', 'lidar01', 'camera01'],
    'car_camera_lidar04.xacro': ['inertial', 'car', 'camera', 'lidar', 'move', 'lidar01', 'camera01', 'kinect'],
}


def strip_comments(text):
    return re.sub(r'<!--.*?-->', '', text, flags=re.S)


@pytest.mark.parametrize('name', sorted(AGGREGATES))
def test_aggregate_includes(name):
    root = ET.parse(os.path.join(URDF, name)).getroot()
    incs = [e.get('filename') for e in root if e.tag.endswith('include')]
    assert incs == [n + '.xacro' for n in AGGREGATES[name]]


@pytest.mark.parametrize('name', sorted(AGGREGATES))
def test_aggregate_expands(name):
    ET.fromstring(xacro_tool.expand(os.path.join(URDF, name)))


def test_expanded_fixture_is_current(car04_xml):
    with open(os.path.join(DATA, 'car_camera_lidar04.urdf')) as f:
        fixture = f.read()
    assert ET.canonicalize(strip_comments(fixture), strip_text=True) == \
        ET.canonicalize(strip_comments(car04_xml), strip_text=True)


def test_control_yaml_is_the_seeds_arbotix_config():
    with open(os.path.join(ROOT, 'config', 'control.yaml')) as f:
        cfg = yaml.safe_load(f)
    assert cfg == {'controllers': {'base_controller': {
        'type': 'diff_controller', 'base_frame_id': 'base_footprint', 'base_width': 0.2, 'ticks_meter': 2000,
        'Kp': 12, 'Kd': 12, 'Ki': 0, 'Ko': 50, 'accel_limit': 1.0}}}


def test_box_house_world_models():
    root = ET.parse(os.path.join(ROOT, 'worlds', 'box_house.world')).getroot()
    assert root.get('version') == '1.7'
    models = [m.get('name') for m in root.find('world').findall('model')]
    assert models == ['ground_plane', 'box_house', 'unit_box', 'unit_cylinder', 'unit_box_0', 'unit_box_1',
                      'unit_cylinder_0', 'unit_cylinder_1']
