"""Inertia tensors implied by a link's mass and collision shapes (uniform density).

All tensors are 3x3 numpy arrays in kg m^2, about the centre of mass.
"""
from __future__ import annotations

import math

import numpy as np


def shape_volume(shape: dict) -> float | None:
    """Volume [m^3] of a primitive shape dict from the core; None for meshes and planes."""
    t = shape['type']
    if t == 'box':
        x, y, z = shape['size']
        return x * y * z
    if t == 'cylinder':
        return math.pi * shape['radius'] ** 2 * shape['length']
    if t == 'sphere':
        return 4.0 / 3.0 * math.pi * shape['radius'] ** 3
    return None


def shape_inertia(shape: dict, mass: float) -> np.ndarray | None:
    """Inertia of a solid primitive of given mass about its centroid, in the shape's own frame."""
    t = shape['type']
    if t == 'box':
        x, y, z = shape['size']
        return np.diag([mass * (y * y + z * z) / 12.0, mass * (x * x + z * z) / 12.0, mass * (x * x + y * y) / 12.0])
    if t == 'cylinder':
        r, h = shape['radius'], shape['length']
        side = mass * (3.0 * r * r + h * h) / 12.0
        return np.diag([side, side, mass * r * r / 2.0])
    if t == 'sphere':
        r = shape['radius']
        return np.eye(3) * (2.0 / 5.0 * mass * r * r)
    return None


def expected_inertia(mass: float, shapes: list, frame_rotation) -> tuple | None:
    """Tensor implied by spreading mass over the shapes by volume, about their joint centroid.

    Returns (inertia in the frame with rotation frame_rotation relative to the link, centroid in the link
    frame), or None when a shape has no volume formula (mesh, plane) or there are no shapes.
    """
    vols = [shape_volume(s) for s in shapes]
    if not shapes or any(v is None for v in vols) or sum(vols) <= 0.0:
        return None
    total = sum(vols)
    masses = [mass * v / total for v in vols]
    centres = [np.array(s['origin']['xyz']) for s in shapes]
    centroid = sum(m * c for m, c in zip(masses, centres)) / mass
    inertia = np.zeros((3, 3))
    for s, m, c in zip(shapes, masses, centres):
        R = np.array(s['origin']['rotation'])
        local = R @ shape_inertia(s, m) @ R.T
        d = c - centroid
        # parallel-axis theorem, link frame
        inertia += local + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    Rf = np.array(frame_rotation)
    return Rf.T @ inertia @ Rf, centroid


def relative_error(declared: np.ndarray, expected: np.ndarray) -> float:
    """Frobenius norm of the difference, relative to the expected tensor."""
    return float(np.linalg.norm(declared - expected) / max(np.linalg.norm(expected), 1e-300))
