#!/usr/bin/env python3
"""Writes the mesh fixtures of the core tests: the same axis-aligned box in three formats.

box.stl  binary STL, 200 x 200 x 100 mm written in millimetres (the URDF scales it by 0.001)
box.obj  Wavefront OBJ, a 1 m cube centred on its origin
box.dae  COLLADA, 0.2 x 0.2 x 0.1 m, one red material (diffuse 1 0 0 1)
Run it again only to change them; the tests read the committed files.
"""
import struct

# The 8 corners of a box of half-sizes (hx, hy, hz) and its 12 outward-facing triangles.
FACES = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
         (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def corners(hx, hy, hz):
    return [(-hx, -hy, -hz), (hx, -hy, -hz), (hx, hy, -hz), (-hx, hy, -hz),
            (-hx, -hy, hz), (hx, -hy, hz), (hx, hy, hz), (-hx, hy, hz)]


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    s = sum(x * x for x in n) ** 0.5
    return tuple(x / s for x in n)


def write_stl(path, hx, hy, hz):
    vs = corners(hx, hy, hz)
    with open(path, 'wb') as f:
        f.write(b'car test box (mm)'.ljust(80, b' '))
        f.write(struct.pack('<I', len(FACES)))
        for a, b, c in FACES:
            f.write(struct.pack('<3f', *normal(vs[a], vs[b], vs[c])))
            for k in (a, b, c):
                f.write(struct.pack('<3f', *vs[k]))
            f.write(struct.pack('<H', 0))


def write_obj(path, h):
    with open(path, 'w') as f:
        f.write('# car test cube, 1 m\n')
        for v in corners(h, h, h):
            f.write('v %g %g %g\n' % v)
        for a, b, c in FACES:
            f.write('f %d %d %d\n' % (a + 1, b + 1, c + 1))


def write_dae(path, hx, hy, hz):
    vs = corners(hx, hy, hz)
    pos = ' '.join('%g %g %g' % v for v in vs)
    idx = ' '.join('%d %d %d' % f for f in FACES)
    with open(path, 'w') as f:
        f.write(f'''<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_effects><effect id="red-fx"><profile_COMMON><technique sid="common"><lambert>
    <diffuse><color>1 0 0 1</color></diffuse></lambert></technique></profile_COMMON></effect></library_effects>
  <library_materials><material id="red" name="red"><instance_effect url="#red-fx"/></material></library_materials>
  <library_geometries><geometry id="box" name="box"><mesh>
    <source id="box-pos"><float_array id="box-pos-array" count="24">{pos}</float_array>
      <technique_common><accessor source="#box-pos-array" count="8" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="box-vtx"><input semantic="POSITION" source="#box-pos"/></vertices>
    <triangles material="red" count="12"><input semantic="VERTEX" source="#box-vtx" offset="0"/><p>{idx}</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="box-node">
    <instance_geometry url="#box"><bind_material><technique_common>
      <instance_material symbol="red" target="#red"/></technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
''')


if __name__ == '__main__':
    write_stl('box.stl', 100.0, 100.0, 50.0)
    write_obj('box.obj', 0.5)
    write_dae('box.dae', 0.1, 0.1, 0.05)
