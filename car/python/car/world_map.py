"""A world as a map: an occupancy grid sliced from the collision geometry between two heights, written in
map_server's format (PGM + YAML) and read back."""
from __future__ import annotations

import math
import os

import numpy as np

from car.world_geometry import shapes

OCCUPIED, FREE = 100, 0           # nav_msgs/OccupancyGrid values
PGM_OCCUPIED, PGM_FREE = 0, 254   # map_server pixels (negate 0): black occupied, white free
Z_SAMPLES = 5                     # heights tested across the slab


def _inside(shape: dict, p: np.ndarray) -> np.ndarray:
    """Which points (N x 3, shape frame) lie inside a primitive."""
    t = shape['type']
    if t == 'box':
        h = np.array(shape['size']) / 2
        return np.all(np.abs(p) <= h + 1e-12, axis=1)
    if t == 'cylinder':
        return (p[:, 0] ** 2 + p[:, 1] ** 2 <= shape['radius'] ** 2 + 1e-12) & (np.abs(p[:, 2]) <= shape['length'] / 2)
    if t == 'sphere':
        return np.sum(p ** 2, axis=1) <= shape['radius'] ** 2 + 1e-12
    return np.zeros(len(p), bool)


def _corners(shape: dict) -> np.ndarray:
    """Corners of the shape's bounding box, shape frame."""
    t = shape['type']
    if t == 'box':
        h = np.array(shape['size']) / 2
    elif t == 'cylinder':
        h = np.array([shape['radius'], shape['radius'], shape['length'] / 2])
    else:
        h = np.array([shape['radius']] * 3)
    return np.array([[sx * h[0], sy * h[1], sz * h[2]] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])


def occupancy(desc: dict, resolution: float, z_min: float, z_max: float):
    """Grid (rows from the origin upward, int8 OCCUPIED/FREE), origin (x, y) [m] of cell (0, 0)'s corner, and
    what was skipped. A cell is occupied when a collision shape covers its centre at some height in [z_min, z_max].
    Planes (the ground) and meshes are left out."""
    if not resolution > 0:
        raise ValueError('resolution must be > 0')
    if not z_max > z_min:
        raise ValueError('z_max must be above z_min')
    items, skipped = [], []
    for m, l, s, T in shapes(desc, 'collisions'):
        if s['type'] not in ('box', 'cylinder', 'sphere'):
            if s['type'] != 'plane':
                skipped.append('%s/%s/%s (%s)' % (m['name'], l['name'], s['name'], s['type']))
            continue
        world = (T[:3, :3] @ _corners(s).T).T + T[:3, 3]
        lo, hi = world.min(axis=0), world.max(axis=0)
        if hi[2] < z_min or lo[2] > z_max:
            continue
        items.append((s, T, lo, hi))
    if not items:
        raise ValueError('no collision geometry between z = %g and %g m' % (z_min, z_max))
    lo = np.min([i[2] for i in items], axis=0)
    hi = np.max([i[3] for i in items], axis=0)
    ox, oy = math.floor(lo[0] / resolution) * resolution, math.floor(lo[1] / resolution) * resolution
    width = int(math.ceil((hi[0] - ox) / resolution - 1e-9))
    height = int(math.ceil((hi[1] - oy) / resolution - 1e-9))
    grid = np.full((height, width), FREE, np.int8)
    zs = np.linspace(z_min, z_max, Z_SAMPLES)
    for s, T, a, b in items:
        # cells whose centres fall in the shape's bounding box
        ix0, ix1 = max(0, int((a[0] - ox) / resolution - 0.5)), min(width - 1, int((b[0] - ox) / resolution))
        iy0, iy1 = max(0, int((a[1] - oy) / resolution - 0.5)), min(height - 1, int((b[1] - oy) / resolution))
        xs = ox + (np.arange(ix0, ix1 + 1) + 0.5) * resolution
        ys = oy + (np.arange(iy0, iy1 + 1) + 0.5) * resolution
        X, Y, Z = np.meshgrid(xs, ys, zs, indexing='ij')
        pts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
        local = (pts - T[:3, 3]) @ T[:3, :3]
        hit = _inside(s, local).reshape(len(xs), len(ys), len(zs)).any(axis=2)
        sub = grid[iy0:iy1 + 1, ix0:ix1 + 1]
        sub[hit.T] = OCCUPIED
    return grid, (ox, oy), skipped


def write_map(grid: np.ndarray, origin, resolution: float, basename: str) -> tuple:
    """basename.pgm (top row first, as map_server reads it) and basename.yaml; returns both paths."""
    pgm, yml = basename + '.pgm', basename + '.yaml'
    img = np.where(grid == OCCUPIED, PGM_OCCUPIED, PGM_FREE).astype(np.uint8)[::-1]
    with open(pgm, 'wb') as f:
        f.write(b'P5\n# CREATOR: car world_tool map %.3f m/pix\n%d %d\n255\n' % (resolution, img.shape[1], img.shape[0]))
        f.write(img.tobytes())
    with open(yml, 'w') as f:
        f.write('image: %s\nresolution: %r\norigin: [%r, %r, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n'
                'free_thresh: 0.196\n' % (os.path.basename(pgm), resolution, float(origin[0]), float(origin[1])))
    return pgm, yml


def read_map(yaml_path: str):
    """(grid, origin (x, y), resolution) of a map_server map, with map_server's thresholds (trinary)."""
    import yaml
    with open(yaml_path) as f:
        meta = yaml.safe_load(f)
    image = meta['image'] if os.path.isabs(meta['image']) else os.path.join(os.path.dirname(yaml_path), meta['image'])
    with open(image, 'rb') as f:
        data = f.read()
    tokens, pos = [], 0
    while len(tokens) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b'#':
            pos = data.index(b'\n', pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        tokens.append(data[pos:end])
        pos = end
    if tokens[0] != b'P5':
        raise ValueError('%s: not a binary PGM (P5)' % image)
    w, h = int(tokens[1]), int(tokens[2])
    img = np.frombuffer(data[pos + 1:pos + 1 + w * h], np.uint8).reshape(h, w)[::-1]
    p = (255.0 - img) / 255.0 if not meta.get('negate', 0) else img / 255.0
    grid = np.full((h, w), -1, np.int8)
    grid[p > meta['occupied_thresh']] = OCCUPIED
    grid[p < meta['free_thresh']] = FREE
    return grid, tuple(meta['origin'][:2]), float(meta['resolution'])
