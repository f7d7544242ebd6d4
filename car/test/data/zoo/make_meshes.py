#!/usr/bin/env python3
"""Writes the zoo's mesh fixtures (run from anywhere; the files are committed):

meshes/box.stl  binary STL, a box 0.2 x 0.2 x 0.1 m centred on its origin (12 triangles)
meshes/cube.obj Wavefront OBJ, a cube of edge 0.1 m centred on its origin (6 quads)
"""
import itertools
import os
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'meshes')


def box_faces(hx, hy, hz):
    """The 6 faces of a box as 4 corners each, counter-clockwise seen from outside."""
    v = {(sx, sy, sz): (sx * hx, sy * hy, sz * hz) for sx, sy, sz in itertools.product((-1, 1), repeat=3)}
    quads = [((-1, -1, -1), (-1, 1, -1), (1, 1, -1), (1, -1, -1)),   # bottom, -z
             ((-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)),       # top, +z
             ((-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1)),   # -y
             ((-1, 1, -1), (-1, 1, 1), (1, 1, 1), (1, 1, -1)),       # +y
             ((-1, -1, -1), (-1, -1, 1), (-1, 1, 1), (-1, 1, -1)),   # -x
             ((1, -1, -1), (1, 1, -1), (1, 1, 1), (1, -1, 1))]       # +x
    return [[v[c] for c in q] for q in quads]


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    s = sum(x * x for x in n) ** 0.5
    return [x / s for x in n]


def write_stl(path, faces):
    tris = [t for q in faces for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
    with open(path, 'wb') as f:
        f.write(b'car zoo box 0.2 x 0.2 x 0.1 m'.ljust(80, b' '))
        f.write(struct.pack('<I', len(tris)))
        for a, b, c in tris:
            f.write(struct.pack('<12fH', *normal(a, b, c), *a, *b, *c, 0))


def write_obj(path, faces):
    verts, idx = [], []
    for q in faces:
        ids = []
        for p in q:
            if p not in verts:
                verts.append(p)
            ids.append(verts.index(p) + 1)
        idx.append(ids)
    with open(path, 'w') as f:
        f.write('# car zoo cube, edge 0.1 m, centred\n')
        for p in verts:
            f.write('v %g %g %g\n' % p)
        for ids in idx:
            f.write('f %d %d %d %d\n' % tuple(ids))


if __name__ == '__main__':
    os.makedirs(HERE, exist_ok=True)
    write_stl(os.path.join(HERE, 'box.stl'), box_faces(0.1, 0.1, 0.05))
    write_obj(os.path.join(HERE, 'cube.obj'), box_faces(0.05, 0.05, 0.05))
