"""Colours of materials: URDF rgba, Gazebo/Name scripts (config/gazebo_materials.txt), SDF ambient/diffuse."""
from __future__ import annotations

import functools
import os

TABLE = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                     'config', 'gazebo_materials.txt')
DEFAULT = (0.7, 0.7, 0.7, 1.0)  # Gazebo's grey


@functools.lru_cache(maxsize=1)
def gazebo_colours() -> dict:
    out = {}
    with open(TABLE) as f:
        for line in f:
            parts = line.split('#', 1)[0].split()
            if len(parts) >= 5:
                out[parts[0]] = tuple(float(v) for v in parts[1:5])
    return out


def visual_colour(visual: dict) -> tuple:
    """RGBA of an SDF visual from car._core.load_world_file: a known Gazebo script (what Gazebo renders), else
    <diffuse>, else <ambient>, else grey."""
    script = visual.get('script') or ''
    if script in gazebo_colours():
        return gazebo_colours()[script]
    if visual.get('diffuse'):
        return tuple(visual['diffuse'])
    if visual.get('ambient'):
        return tuple(visual['ambient'])
    return DEFAULT
