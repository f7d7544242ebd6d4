"""Shape inertia formulas, checked against values worked out by hand."""
import math

import numpy as np
import pytest

from car import inertia

IDENTITY = {'xyz': [0, 0, 0], 'rotation': np.eye(3).tolist()}


def test_box():
    s = {'type': 'box', 'size': [1, 2, 3], 'origin': IDENTITY}
    # m (y^2 + z^2) / 12 etc. with m = 12
    assert np.diag(inertia.shape_inertia(s, 12.0)).tolist() == pytest.approx([13, 10, 5])


def test_cylinder_axis_is_z():
    s = {'type': 'cylinder', 'radius': 1.0, 'length': 2.0, 'origin': IDENTITY}
    # side = m (3 r^2 + h^2) / 12 = 6 (3 + 4) / 12, axial = m r^2 / 2 = 3
    assert np.diag(inertia.shape_inertia(s, 6.0)).tolist() == pytest.approx([3.5, 3.5, 3.0])


def test_sphere():
    s = {'type': 'sphere', 'radius': 0.5, 'origin': IDENTITY}
    assert np.diag(inertia.shape_inertia(s, 10.0)).tolist() == pytest.approx([1.0, 1.0, 1.0])


def test_rotated_cylinder_puts_axial_moment_on_y():
    c, s_ = math.cos(math.pi / 2), math.sin(math.pi / 2)
    rx = [[1, 0, 0], [0, c, -s_], [0, s_, c]]
    shape = {'type': 'cylinder', 'radius': 1.0, 'length': 2.0, 'origin': {'xyz': [0, 0, 0], 'rotation': rx}}
    tensor, centroid = inertia.expected_inertia(6.0, [shape], np.eye(3))
    assert np.diag(tensor).tolist() == pytest.approx([3.5, 3.0, 3.5])


def test_two_boxes_parallel_axis():
    # two 1 kg unit cubes centred at x = +-1: Iyy = Izz = 2 (1/6 + 1 * 1^2), Ixx = 2/6
    a = {'type': 'box', 'size': [1, 1, 1], 'origin': {'xyz': [1, 0, 0], 'rotation': np.eye(3).tolist()}}
    b = {'type': 'box', 'size': [1, 1, 1], 'origin': {'xyz': [-1, 0, 0], 'rotation': np.eye(3).tolist()}}
    tensor, centroid = inertia.expected_inertia(2.0, [a, b], np.eye(3))
    assert centroid.tolist() == pytest.approx([0, 0, 0])
    assert np.diag(tensor).tolist() == pytest.approx([1 / 3, 2 / 6 + 2, 2 / 6 + 2])


def test_mesh_has_no_formula():
    s = {'type': 'mesh', 'uri': 'x.stl', 'origin': IDENTITY}
    assert inertia.expected_inertia(1.0, [s], np.eye(3)) is None
