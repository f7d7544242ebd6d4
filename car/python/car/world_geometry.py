"""World geometry from the simulator's own reading of an SDF world (car._core.load_world_file): poses as 4x4
matrices, [m] and world frame throughout."""
from __future__ import annotations

import numpy as np


def transform(pose: dict) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = np.array(pose['rotation'])
    T[:3, 3] = pose['xyz']
    return T


def model_transform(model: dict) -> np.ndarray:
    return transform(model['pose'])


def shapes(desc: dict, kind: str = 'collisions'):
    """(model, link, shape dict, world transform of the shape) for every collision or visual of a world."""
    for m in desc['models']:
        Tm = model_transform(m)
        for l in m['links']:
            Tl = Tm @ transform(l['pose'])
            for s in l[kind]:
                yield m, l, s, Tl @ transform(s['origin'])
