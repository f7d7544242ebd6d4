#!/usr/bin/env python3
"""MuJoCo (PyPI `mujoco`) as a peer of car's physics: the seed car in box_house, built with MjSpec from the same
descriptions car reads (car._core.load_urdf_file / load_world_file), stepped at 1 kHz.

The model follows car's rules as closely as MuJoCo allows (docs/COMPAT-physics.md "How the car rolls"):
- links joined by fixed joints are one rigid body (MuJoCo: child bodies without a joint); a massless root link
  (base_footprint) is skipped, its fixed child becomes the free-floating base;
- drive wheels are hinge joints on their URDF axis driven by velocity servos (force = kv (ctrl - qdot), capped at
  the plug-in's wheelTorque), and collide as a sphere of the wheel radius at the wheel centre (car's one-point
  wheel contact);
- ball casters collide as frictionless spheres (condim 1) rigidly on the base (car: a frictionless sphere on a
  free continuous joint: the same forces, one body fewer);
- every other collision is the URDF's primitive; friction is the smaller mu of the pair, as in car and Gazebo
  (MuJoCo takes the larger one, so every geom gets the world's mu 1, and the casters 0 through condim 1);
- integrator implicitfast (the velocity servos' damping is integrated implicitly: the seed's 50 g wheels with
  30 N m caps are unstable with explicit Euler), 1 ms step, default solver (Newton, pyramidal cone).

Usage (through bench/run.sh): bench_mujoco.py [--steps N]   prints validation and steps/s.
"""
import argparse
import math
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
URDF = os.path.join(ROOT, 'test', 'data', 'car_camera_lidar04.urdf')
WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
GROUND_ONLY = '''<sdf version="1.6"><world name="ground"><model name="ground_plane"><static>true</static>
<link name="link"><collision name="c"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
</collision></link></model></world></sdf>'''
KV = 0.2  # [N m s / rad] wheel velocity-servo gain (1.0 makes the pyramidal-cone car hop)


def _quat(R):
    """wxyz quaternion of a 3x3 rotation (list of rows)."""
    import mujoco
    q = np.zeros(4)
    mujoco.mju_mat2Quat(q, np.asarray(R, dtype=float).reshape(9))
    return q.tolist()


def _add_geom(body, c, mujoco, **kw):
    """One core collision dict as a MuJoCo geom in its link's frame; None for what has no MuJoCo primitive."""
    o = c['origin']
    g = dict(pos=o['xyz'], quat=_quat(o['rotation']), friction=[1.0, 0.005, 0.0001])
    if c['type'] == 'box':
        g.update(type=mujoco.mjtGeom.mjGEOM_BOX, size=[s / 2 for s in c['size']])
    elif c['type'] == 'cylinder':
        g.update(type=mujoco.mjtGeom.mjGEOM_CYLINDER, size=[c['radius'], c['length'] / 2, 0])
    elif c['type'] == 'sphere':
        g.update(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[c['radius'], 0, 0])
    elif c['type'] == 'plane':
        g.update(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1])
    else:
        return None
    g.update(kw)
    return body.add_geom(**g)


def build(x=0.0, y=0.0, world_file=WORLD):
    """The MjSpec model of the seed car at (x, y) in a world (box_house; None: a ground plane only), the names of
    its two wheel servos, the wheel separation and radius [m], and the base body's name."""
    import mujoco
    from car import _core
    robot = _core.load_urdf_file(URDF)
    world = _core.load_world_file(world_file) if world_file else _core.load_world_string(GROUND_ONLY)
    drive = next(p for p in robot['plugins'] if 'diff_drive' in p['filename'])
    params = dict(drive['params'])
    wheel_torque = float(params.get('wheelTorque', 5))
    driven = {params['leftJoint'], params['rightJoint']}

    spec = mujoco.MjSpec()
    spec.option.timestep = world['step_size']
    spec.option.gravity = world['gravity']
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST

    # the world: static models' collisions in the world body, others as free bodies
    for m in world['models']:
        for link in m['links']:
            wp = link['world_pose']
            if m['static'] or not link['inertial']:
                frame = spec.worldbody.add_frame(pos=wp['xyz'], quat=_quat(wp['rotation']))
                for c in link['collisions']:
                    _add_geom(frame, c, mujoco)
            else:
                b = spec.worldbody.add_body(pos=wp['xyz'], quat=_quat(wp['rotation']))
                b.add_freejoint()
                i = link['inertial']
                b.mass = i['mass']
                b.ipos = i['origin']['xyz']
                b.fullinertia = [i['inertia'][0][0], i['inertia'][1][1], i['inertia'][2][2],
                                 i['inertia'][0][1], i['inertia'][0][2], i['inertia'][1][2]]
                for c in link['collisions']:
                    _add_geom(b, c, mujoco)

    links = {l['name']: l for l in robot['links']}
    children = {}
    for j in robot['joints']:
        children.setdefault(j['parent'], []).append(j)

    def add_link(parent_body, name, pos, quat, joint):
        link = links[name]
        b = parent_body.add_body(name=name, pos=pos, quat=quat)
        if joint is None:
            b.add_freejoint()
        elif joint['type'] in ('continuous', 'revolute') and joint['name'] in driven:
            b.add_joint(name=joint['name'], type=mujoco.mjtJoint.mjJNT_HINGE, axis=joint['axis'])
        i = link['inertial']
        if i:
            b.mass = i['mass']
            b.ipos = i['origin']['xyz']
            b.iquat = _quat(i['origin']['rotation'])
            b.fullinertia = [i['inertia'][0][0], i['inertia'][1][1], i['inertia'][2][2],
                             i['inertia'][0][1], i['inertia'][0][2], i['inertia'][1][2]]
        for c in link['collisions']:
            if joint is not None and joint['name'] in driven and c['type'] == 'cylinder':
                # one contact under the wheel centre, as car's wheel rule
                b.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[c['radius'], 0, 0], friction=[1, 0.005, 0.0001])
            elif joint is not None and joint['type'] == 'continuous' and c['type'] == 'sphere':
                # ball caster: frictionless
                _add_geom(b, c, mujoco, condim=1, priority=1)
            else:
                _add_geom(b, c, mujoco)
        for j in children.get(name, []):
            add_link(b, j['child'], j['origin']['xyz'], _quat(j['origin']['rotation']), j)
        return b

    root = robot['root_link']
    base_pos = [x, y, 0.0]
    if not links[root]['inertial'] and len(children.get(root, [])) == 1 and children[root][0]['type'] == 'fixed':
        j = children[root][0]
        base_pos = [x + j['origin']['xyz'][0], y + j['origin']['xyz'][1], j['origin']['xyz'][2]]
        root = j['child']
    add_link(spec.worldbody, root, base_pos, [1, 0, 0, 0], None)
    for jn in sorted(driven):
        spec.add_actuator(name=jn, target=jn, trntype=mujoco.mjtTrn.mjTRN_JOINT,
                          gaintype=mujoco.mjtGain.mjGAIN_FIXED, gainprm=[KV] + [0] * 9,
                          biastype=mujoco.mjtBias.mjBIAS_AFFINE, biasprm=[0, 0, -KV] + [0] * 7,
                          forcelimited=True, forcerange=[-wheel_torque, wheel_torque])
    model = spec.compile()
    sep = float(params['wheelSeparation'])
    radius = float(params['wheelDiameter']) / 2
    return model, params['leftJoint'], params['rightJoint'], sep, radius, root


def command(model, data, left, right, sep, radius, v, w):
    """The diff drive's wheel speeds for (v [m/s], w [rad/s]) as servo targets [rad/s]."""
    import mujoco
    data.ctrl[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, left)] = (v - w * sep / 2) / radius
    data.ctrl[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, right)] = (v + w * sep / 2) / radius


def validate():
    """(base height at rest [m], radius of the circle driven at v = 1, w = 1 [m]) on a bare ground plane (the
    circle from box_house's origin runs into its furniture) — car's values: 0.055, 1.000."""
    import mujoco
    model, left, right, sep, radius, base = build(world_file=None)
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data, nstep=2000)
    bid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, base)
    # car's figure is base_link's height; car lumps base_link into the massless root's body (fixed joint), so
    # its frame sits at its lumped offset in that body
    from car import _core
    lumped = {l['name']: l['pose']['xyz'] for l in _core.load_urdf_file(URDF)['lumped']}
    offset = np.array(lumped.get('base_link', [0.0, 0.0, 0.0]) if base != 'base_link' else [0.0, 0.0, 0.0])
    rest_z = float((data.xpos[bid] + data.xmat[bid].reshape(3, 3) @ offset)[2])
    command(model, data, left, right, sep, radius, 1.0, 1.0)
    mujoco.mj_step(model, data, nstep=2000)
    pts = []
    for _ in range(60):
        mujoco.mj_step(model, data, nstep=100)
        pts.append(data.xpos[bid][:2].copy())
    # least-squares circle through the points: x^2 + y^2 + D x + E y + F = 0
    P = np.array(pts)
    A = np.c_[P, np.ones(len(P))]
    D, E, F = np.linalg.lstsq(A, -(P ** 2).sum(axis=1), rcond=None)[0]
    r = math.sqrt(D * D / 4 + E * E / 4 - F)
    return rest_z, r


def rates(steps, settle=3000, sleep=False):
    """(steps per wall second, steps per CPU second of this thread) of MuJoCo's own loop (mj_step with nstep: no
    Python per step) driving the seed command in box_house, on a model built afresh; sleep: MuJoCo's island
    sleeping on (resting bodies skipped, as Bullet's deactivation does in car)."""
    import mujoco
    model, left, right, sep, radius, _ = build()
    if sleep:
        model.opt.enableflags |= int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    data = mujoco.MjData(model)
    command(model, data, left, right, sep, radius, 1.0, 1.0)
    mujoco.mj_step(model, data, nstep=settle)
    t, c = time.perf_counter(), time.thread_time()
    mujoco.mj_step(model, data, nstep=steps)
    c, t = time.thread_time() - c, time.perf_counter() - t
    return steps / t, steps / max(c, 1e-9)


def steps_per_second(steps, settle=3000, sleep=False):
    """Steps per wall second of rates()."""
    return rates(steps, settle, sleep)[0]


def version():
    import mujoco
    return mujoco.__version__


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument('--steps', type=int, default=30000)
    a = ap.parse_args()
    z, r = validate()
    print('MuJoCo %s: base at rest %.4f m (car 0.055), circle radius %.3f m (car 1.000)' % (version(), z, r))
    print('MuJoCo steps/s: %.0f (sleeping off), %.0f (sleeping on)' % (steps_per_second(a.steps),
                                                                      steps_per_second(a.steps, sleep=True)))
    return 0


if __name__ == '__main__':
    sys.exit(main())
