"""box_house as a 0.05 m map: cells worked out by hand from the SDF."""
import os

import numpy as np
import pytest

from car import _core, world_map
from conftest import ROOT

RES = 0.05


@pytest.fixture(scope='module')
def box_house_map():
    desc = _core.load_world_file(os.path.join(ROOT, 'worlds', 'box_house.world'))
    return world_map.occupancy(desc, RES, 0.05, 0.5)


def test_origin_and_size(box_house_map):
    grid, origin, skipped = box_house_map
    # walls span x -8.47643 .. 4.52357, y -3.94004 .. 4.05996: origin floor(./0.05)*0.05, size ceil
    assert origin == pytest.approx((-8.5, -3.95))
    assert grid.shape == (161, 261)
    assert skipped == []


def test_wall_1_rows(box_house_map):
    grid, _, _ = box_house_map
    # Wall_1: y 3.90996 .. 4.05996 -> cell centres -3.95 + (iy + 0.5) 0.05 in it: rows 157..159; at x = 0.025 (col 170)
    assert [grid[iy, 170] for iy in range(155, 161)] == [0, 0, 100, 100, 100, 0]


def test_wall_3_rows(box_house_map):
    grid, _, _ = box_house_map
    # Wall_3: y -3.94004 .. -3.79004 -> rows 0..2
    assert [grid[iy, 170] for iy in range(0, 5)] == [100, 100, 100, 0, 0]


def test_wall_2_columns(box_house_map):
    grid, _, _ = box_house_map
    # Wall_2: x 4.37357 .. 4.52357 -> columns 257..259; at y = -0.025 (row 78)
    assert [grid[78, ix] for ix in range(255, 261)] == [0, 0, 100, 100, 100, 0]


def test_inside_is_free_around_the_start(box_house_map):
    grid, _, _ = box_house_map
    # 1 m around the origin (cols 150..189, rows 59..98): nothing stands there
    assert (grid[59:99, 150:190] == 0).all()


def test_unit_cylinder_0_is_a_disc(box_house_map):
    grid, origin, _ = box_house_map
    # unit_cylinder_0 at (-0.988146, 2.12658), r 0.5: its centre cell is occupied, a cell 0.55 m away is not
    ix, iy = int((-0.988146 - origin[0]) / RES), int((2.12658 - origin[1]) / RES)
    assert grid[iy, ix] == 100
    assert grid[iy, ix + 11] == 0


def test_written_map_reads_back_the_same(box_house_map, tmp_path):
    grid, origin, _ = box_house_map
    pgm, yml = world_map.write_map(grid, origin, RES, str(tmp_path / 'box_house'))
    back, back_origin, back_res = world_map.read_map(yml)
    assert np.array_equal(back, grid)
    assert back_origin == pytest.approx(origin)
    assert back_res == RES
    with open(yml) as f:
        text = f.read()
    for key in ('image: box_house.pgm', 'resolution: 0.05', 'origin: [-8.5, -3.95, 0.0]', 'negate: 0',
                'occupied_thresh: 0.65', 'free_thresh: 0.196'):
        assert key in text


def test_bad_slab_is_refused():
    desc = _core.load_world_file(os.path.join(ROOT, 'worlds', 'box_house.world'))
    with pytest.raises(ValueError, match='z_max must be above z_min'):
        world_map.occupancy(desc, RES, 1.0, 0.5)
