"""Colours of materials: the core's colour rule (car_sim's materials: a known Gazebo/Name script, else the URDF or
SDF colour, else grey), exposed here for the Python tools so that rviz markers, maps and the simulator's cameras
agree."""
from __future__ import annotations

import functools

DEFAULT = (0.7, 0.7, 0.7, 1.0)  # Gazebo's grey


@functools.lru_cache(maxsize=1)
def gazebo_colours() -> dict:
    """Gazebo's standard materials as RGBA (config/gazebo_materials.txt, read by the core)."""
    from car import _core
    return _core.gazebo_colours()


def visual_colour(visual: dict) -> tuple:
    """RGBA of an SDF visual from car._core.load_world_file: a known Gazebo script (what Gazebo renders), else
    <diffuse>, else <ambient>, else grey."""
    from car import _core
    return _core.visual_colour(visual.get('script') or '', visual.get('diffuse'), visual.get('ambient'))
