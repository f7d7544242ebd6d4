"""Parse once per process, build many: the const half of a world and of a robot, kept for the next run.

A warm worker (car batch's Ray worker, a gym env's reset) builds a new World for every run. Parsing box_house
through sdformat costs ~0.2 s; building a World from the parsed description costs a few ms. So the parsed forms are
cached here, keyed by content, and each run builds its World from them:

  desc, ground = world_description(path)   # car._core.WorldDescription, names of the models that hold a plane
  model = robot_model(urdf_text, name)      # car._core.RobotModel
  world = new_world(path, seed)             # = car._core.World(desc, seed=seed)
  world.spawn_model(model, name, x, y, z, roll, pitch, yaw)

The cached objects are const descriptions: World(desc) and World.spawn_model copy what they keep, so no run sees
what another run did (test/python/test_world_cache.py runs A, B, A in one process and compares A bit for bit).
"""
from __future__ import annotations

import functools
import hashlib

# a worker that sweeps over many worlds or models keeps only the latest few
CACHE_SIZE = 8


def _digest(path: str) -> str:
    with open(path, 'rb') as f:
        return hashlib.sha256(f.read()).hexdigest()


@functools.lru_cache(maxsize=CACHE_SIZE)
def _parsed_world(path: str, digest: str):
    from car import _core
    desc = _core.parse_world_file(path) if path else _core.empty_world_description()
    d = desc.to_dict()
    ground = frozenset(m['name'] for m in d['models']
                       if any(c['type'] == 'plane' for l in m['links'] for c in l['collisions']))
    return desc, ground


def world_description(path):
    """(car._core.WorldDescription, frozenset of ground model names) for a world file (None or '': Gazebo's empty
    world), parsed once per process and file content. Touching a ground model is not a collision."""
    if not path:
        return _parsed_world('', '')
    # the path matters too: relative includes and meshes resolve against its folder
    return _parsed_world(path, _digest(path))


@functools.lru_cache(maxsize=CACHE_SIZE)
def robot_model(urdf: str, name: str):
    """car._core.RobotModel of URDF text, parsed once per process for each (text, name). The name is the model's
    source, as World.spawn_urdf(xml, name) sets it (in messages; relative mesh URIs start at its folder)."""
    from car import _core
    return _core.parse_urdf_string(urdf, name)


def new_world(path, seed: int = 0, solver_iterations: int = 10):
    """A fresh World of a world file (None: the empty world) from the cached description."""
    from car import _core
    return _core.World(world_description(path)[0], solver_iterations=solver_iterations, seed=seed)


def clear():
    """Forget every parsed world and model (the next run parses again)."""
    _parsed_world.cache_clear()
    robot_model.cache_clear()
