"""box_house's markers: the 4 walls and 6 objects where the SDF puts them."""
import math
import os

import numpy as np
import pytest

from car import _core
from car.ros import world_markers
from conftest import ROOT


@pytest.fixture(scope='module')
def specs():
    desc = _core.load_world_file(os.path.join(ROOT, 'worlds', 'box_house.world'))
    return {(s['ns'], i): s for i, s in enumerate(world_markers.marker_specs(desc))}


def by_ns(specs, ns):
    return [s for (n, _), s in specs.items() if n == ns]


def test_ten_objects_four_walls_and_the_ground(specs):
    names = sorted({n for n, _ in specs})
    assert names == ['box_house', 'ground_plane', 'unit_box', 'unit_box_0', 'unit_box_1', 'unit_cylinder',
                     'unit_cylinder_0', 'unit_cylinder_1']
    assert len(by_ns(specs, 'box_house')) == 4


def test_wall_2_pose_and_size(specs):
    # model (-1.97643, 0.059964), link (6.425, 0, yaw -1.5708), visual z 1.25: centre (4.44857, 0.059964, 1.25)
    wall = by_ns(specs, 'box_house')[1]
    assert wall['type'] == 'cube'
    assert wall['scale'] == pytest.approx([8, 0.15, 2.5])
    assert wall['pose'][:3, 3] == pytest.approx([4.44857, 0.059964, 1.25], abs=1e-5)
    assert math.atan2(wall['pose'][1, 0], wall['pose'][0, 0]) == pytest.approx(-1.5708, abs=1e-6)


def test_wall_colours_from_their_scripts(specs):
    walls = by_ns(specs, 'box_house')
    assert walls[1]['rgba'] == (0.62, 0.32, 0.24, 1.0)   # Gazebo/Bricks
    assert walls[3]['rgba'] == (0.52, 0.37, 0.26, 1.0)   # Gazebo/Wood


def test_unit_box_0_at_its_state_pose(specs):
    (box,) = by_ns(specs, 'unit_box_0')
    assert box['scale'] == pytest.approx([1, 1, 1])
    assert box['pose'][:3, 3] == pytest.approx([-4.96407, -2.00353, 0.499995])
    assert box['rgba'] == (0.7, 0.7, 0.7, 1.0)  # Gazebo/Grey


def test_unit_cylinder_size(specs):
    (cyl,) = by_ns(specs, 'unit_cylinder')
    assert cyl['type'] == 'cylinder'
    assert cyl['scale'] == pytest.approx([1.0, 1.0, 1.0])  # diameter 2 x 0.5, length 1


def test_ground_plane_is_a_thin_box_under_z_0(specs):
    (g,) = by_ns(specs, 'ground_plane')
    assert g['scale'] == pytest.approx([100, 100, 0.001])
    assert g['pose'][2, 3] == pytest.approx(-0.0005)


def test_marker_array_message(specs):
    arr = world_markers.to_marker_array(list(specs.values()), 'odom')
    assert len(arr.markers) == 11
    assert {m.header.frame_id for m in arr.markers} == {'odom'}
    assert len({(m.ns, m.id) for m in arr.markers}) == 11
