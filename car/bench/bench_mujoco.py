#!/usr/bin/env python3
"""MuJoCo (PyPI `mujoco`) as a peer of car's physics: the seed car in box_house, built with MjSpec from the same
descriptions car reads (car._core.load_urdf_file / load_world_file), stepped at 1 kHz.

Two models (docs/BENCH.md "The peers"):

- `strong` (the peer the ratios use): the strongest MuJoCo model of this scene that still does what car does,
  validated against car before it is timed (validate()). What car simulates (docs/COMPAT-physics.md "How the car
  rolls") and how MuJoCo says it:
  - links joined by fixed joints are one rigid body (MuJoCo: child bodies without a joint); a massless root link
    (base_footprint) is skipped, its fixed child becomes the free-floating base;
  - drive wheels are hinge joints on their URDF axis with armature 3e-3 kg m^2, driven by velocity servos
    (force = kv (ctrl - qdot), capped at the plug-in's wheelTorque), and collide as a sphere of the wheel radius at
    the wheel centre (car's one-point wheel contact);
  - ball casters collide as frictionless spheres (condim 1, priority 1) rigidly on the base (car: a frictionless
    sphere on a free continuous joint: the same forces, one body fewer);
  - the robot's geoms do not collide with each other (contype 2 / conaffinity 1 against the world's 1 / 3): car
    has self-collision off;
  - friction is the smaller mu of the pair, as in car and Gazebo (MuJoCo takes the larger one, so every geom gets
    the world's mu 1, and the casters 0 through condim 1);
  - contacts as stiff as the step allows (solref time constant 2 dt), so the car rests where car's rigid contacts
    hold it (within microns) instead of 0.2 mm lower;
  - Newton solver with at most 10 iterations (car: 10 PGS iterations), pyramidal cone, implicitfast (the servos'
    damping integrated implicitly), 1 ms step; island sleeping on, with the robot's tree never sleeping (car: Bullet
    deactivates resting world objects, the robot never sleeps); world objects with the SDF's inertia;
  - in a world where nothing moves but the robot (the bare plane), island discovery off (one tree: it changes
    nothing but the time);
  - the diff drive's wheelAcceleration ramp at its updateRate, as gazebo_ros_diff_drive (and car's plug-in) ramps
    (validation only: the timed run starts after the ramp has ended).
- `old`: the model this bench used before (default solver settings: 100 Newton iterations, the robot's geoms
  colliding with each other, no armature, kv 0.2, default contact softness), kept for the comparison.

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
KV_OLD = 0.2  # [N m s / rad] the old model's wheel velocity-servo gain (1.0 made it hop)
KV = 2.0      # [N m s / rad] the strong model's gain (with the armature, stable and 10x stiffer)
ARMATURE = 3e-3  # [kg m^2] on the drive wheels' hinges
SETTLE = 3000  # steps before timing


def _quat(R):
    """wxyz quaternion of a 3x3 rotation (list of rows)."""
    import mujoco
    q = np.zeros(4)
    mujoco.mju_mat2Quat(q, np.asarray(R, dtype=float).reshape(9))
    return q.tolist()


class Peer:
    """A compiled MuJoCo model of the seed car in a world, its data, and the diff drive's command path."""

    def __init__(self, model, left, right, sep, radius, base, params, base_link_offset):
        import mujoco
        self.model, self.sep, self.radius = model, sep, radius
        self.data = mujoco.MjData(model)
        self.left = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, left)
        self.right = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, right)
        self.base = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, base)
        # [m] base_link's frame in the base body's frame (car lumps base_link into the root link's body)
        self.offset = np.asarray(base_link_offset, dtype=float)
        # the plug-in's ramp (docs/COMPAT-plugins.md): the commanded wheel surface speeds [m/s], kept between updates
        self.rate = float(params.get('updateRate', 100.0))
        self.accel = float(params.get('wheelAcceleration', 0.0))
        self.surface = [0.0, 0.0]
        self.target = [0.0, 0.0]

    def set_cmd_vel(self, v, w):
        """The diff drive's wheel surface speed targets [m/s] for (v [m/s], w [rad/s])."""
        self.target = [v - w * self.sep / 2, v + w * self.sep / 2]

    def _update(self, ramp):
        """gazebo_ros_diff_drive's update, as car's WheelRamp: with either wheel's current surface speed within
        0.01 m/s of its target (or no ramp), both servos get their targets; otherwise each commanded speed moves by
        target - current clamped to accel times upstream's seconds since its last update (the period and one
        step)."""
        current = [self.data.actuator_velocity[self.left] * self.radius,
                   self.data.actuator_velocity[self.right] * self.radius]
        if not ramp or self.accel == 0 or any(abs(t - c) < 0.01 for t, c in zip(self.target, current)):
            out = list(self.target)
        else:
            lim = self.accel * (1.0 / self.rate + self.model.opt.timestep)
            for i in range(2):
                self.surface[i] += max(-lim, min(lim, self.target[i] - current[i]))
            out = list(self.surface)
        self.data.ctrl[self.left] = out[0] / self.radius
        self.data.ctrl[self.right] = out[1] / self.radius

    def step(self, n, ramp=True):
        """n steps with the plug-in's control: new wheel speeds every 1/updateRate s (every 10 steps at 1 kHz),
        ramped at wheelAcceleration."""
        import mujoco
        every = max(1, int(round(1.0 / (self.rate * self.model.opt.timestep))))
        while n > 0:
            self._update(ramp)
            k = min(n, every)
            mujoco.mj_step(self.model, self.data, nstep=k)
            n -= k

    def base_pose(self):
        """(x, y, z [m], yaw [rad]) of the base body's frame (base_link), world."""
        R = self.data.xmat[self.base].reshape(3, 3)
        p = self.data.xpos[self.base] + R @ self.offset
        return float(p[0]), float(p[1]), float(p[2]), math.atan2(R[1, 0], R[0, 0])


class CarSim:
    """car's core through its Python API, with the same methods as Peer (for the validation)."""

    def __init__(self, world_file):
        from car import _core
        self.w = _core.World(world_file)
        with open(URDF) as f:
            self.w.spawn_urdf(f.read(), 'mycar')

    def set_cmd_vel(self, v, w):
        self.w.set_cmd_vel('mycar', v, w)

    def step(self, n, ramp=True):
        self.w.step(n)

    def base_pose(self):
        p = self.w.link_pose('mycar', 'base_link')
        return p['position'][0], p['position'][1], p['position'][2], p['yaw']


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


def build(x=0.0, y=0.0, world_file=WORLD, peer='strong'):
    """The Peer (compiled model and data) of the seed car at (x, y) in a world (box_house; None: a ground plane
    only); peer 'strong' or 'old' (the module's docstring)."""
    import mujoco
    from car import _core
    strong = peer == 'strong'
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
    # world geoms collide with everything (1 / 3), robot geoms with the world only (2 / 1)
    world_kw, robot_kw = {}, {}
    if strong:
        spec.option.solver = mujoco.mjtSolver.mjSOL_NEWTON
        spec.option.cone = mujoco.mjtCone.mjCONE_PYRAMIDAL
        spec.option.iterations = 10
        spec.option.enableflags |= int(mujoco.mjtEnableBit.mjENBL_SLEEP)
        world_kw = dict(contype=1, conaffinity=3)
        robot_kw = dict(contype=2, conaffinity=1)
        # contacts as stiff as refsafe allows (time constant 2 dt, critically damped)
        spec.default.geom.solref = [2 * world['step_size'], 1.0]

    # the world: static models' collisions in the world body, others as free bodies
    for m in world['models']:
        for link in m['links']:
            wp = link['world_pose']
            if m['static'] or not link['inertial']:
                frame = spec.worldbody.add_frame(pos=wp['xyz'], quat=_quat(wp['rotation']))
                for c in link['collisions']:
                    _add_geom(frame, c, mujoco, **world_kw)
            else:
                b = spec.worldbody.add_body(pos=wp['xyz'], quat=_quat(wp['rotation']))
                b.add_freejoint()
                i = link['inertial']
                b.mass = i['mass']
                b.ipos = i['origin']['xyz']
                b.iquat = _quat(i['origin']['rotation'])
                b.fullinertia = [i['inertia'][0][0], i['inertia'][1][1], i['inertia'][2][2],
                                 i['inertia'][0][1], i['inertia'][0][2], i['inertia'][1][2]]
                for c in link['collisions']:
                    _add_geom(b, c, mujoco, **world_kw)

    links = {l['name']: l for l in robot['links']}
    children = {}
    for j in robot['joints']:
        children.setdefault(j['parent'], []).append(j)

    def add_link(parent_body, name, pos, quat, joint):
        link = links[name]
        b = parent_body.add_body(name=name, pos=pos, quat=quat)
        if joint is None:
            b.add_freejoint()
            if strong:
                b.sleep = mujoco.mjtSleepPolicy.mjSLEEP_NEVER
        elif joint['type'] in ('continuous', 'revolute') and joint['name'] in driven:
            b.add_joint(name=joint['name'], type=mujoco.mjtJoint.mjJNT_HINGE, axis=joint['axis'],
                        armature=ARMATURE if strong else 0.0)
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
                b.add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[c['radius'], 0, 0], friction=[1, 0.005, 0.0001],
                           **robot_kw)
            elif joint is not None and joint['type'] == 'continuous' and c['type'] == 'sphere':
                # ball caster: frictionless
                _add_geom(b, c, mujoco, condim=1, priority=1, **robot_kw)
            else:
                _add_geom(b, c, mujoco, **robot_kw)
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
    kv = KV if strong else KV_OLD
    for jn in sorted(driven):
        spec.add_actuator(name=jn, target=jn, trntype=mujoco.mjtTrn.mjTRN_JOINT,
                          gaintype=mujoco.mjtGain.mjGAIN_FIXED, gainprm=[kv] + [0] * 9,
                          biastype=mujoco.mjtBias.mjBIAS_AFFINE, biasprm=[0, 0, -kv] + [0] * 7,
                          forcelimited=True, forcerange=[-wheel_torque, wheel_torque])
    if strong and not any(not m['static'] and l['inertial'] for m in world['models'] for l in m['links']):
        # nothing in the world moves but the robot: one kinematic tree, so island discovery buys nothing (8 % of a
        # step on the bare plane)
        spec.option.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_ISLAND)
    model = spec.compile()
    sep = float(params['wheelSeparation'])
    radius = float(params['wheelDiameter']) / 2
    lumped = {l['name']: l['pose']['xyz'] for l in robot['lumped']}
    offset = lumped.get('base_link', [0.0, 0.0, 0.0]) if root != 'base_link' else [0.0, 0.0, 0.0]
    return Peer(model, params['leftJoint'], params['rightJoint'], sep, radius, root, params, offset)


def _circle(points):
    """(radius, centre x, centre y) of the least-squares circle x^2 + y^2 + D x + E y + F = 0 through points."""
    P = np.array(points)
    A = np.c_[P, np.ones(len(P))]
    D, E, F = np.linalg.lstsq(A, -(P ** 2).sum(axis=1), rcond=None)[0]
    return math.sqrt(D * D / 4 + E * E / 4 - F), -D / 2, -E / 2


def figures(make):
    """The five validation figures of a simulator (make(world_file) -> Peer or CarSim), each from a fresh world:
    - rest_height_m: base_link's height after 2 s at rest on a bare ground plane;
    - circle_radius_m, circle_centre_x/y_m: the least-squares circle of base_link over 6 s, sampled every 0.1 s,
      of the seed command (v = 1 m/s, w = 1 rad/s) from 2 s after it was given, on the bare plane;
    - yaw_rate_rad_s: base_link's mean yaw rate over those 6 s;
    - straight_speed_m_s: base_link's mean speed over 3 s of v = 0.5 m/s, from 3 s after it was given;
    - track: base_link's (x, y) every 0.1 s over 24 s of the seed command from the origin in box_house (compare()).
    """
    out = {}
    s = make(None)
    s.step(2000)
    out['rest_height_m'] = s.base_pose()[2]
    s.set_cmd_vel(1.0, 1.0)
    s.step(2000)
    pts, yaws = [], []
    for _ in range(61):
        x, y, _z, yaw = s.base_pose()
        pts.append((x, y))
        yaws.append(yaw)
        s.step(100)
    out['circle_radius_m'], out['circle_centre_x_m'], out['circle_centre_y_m'] = _circle(pts)
    out['yaw_rate_rad_s'] = float(np.unwrap(yaws)[-1] - yaws[0]) / 6.0
    s = make(None)
    s.set_cmd_vel(0.5, 0.0)
    s.step(3000)
    x0, y0 = s.base_pose()[:2]
    s.step(3000)
    x1, y1 = s.base_pose()[:2]
    out['straight_speed_m_s'] = math.hypot(x1 - x0, y1 - y0) / 3.0
    s = make(WORLD)
    s.set_cmd_vel(1.0, 1.0)
    track = []
    for _ in range(241):
        track.append(s.base_pose()[:2])
        s.step(100)
    out['track'] = track
    return out


def validate(peer='strong'):
    """{figure: value} of the MuJoCo peer and of car (car's under 'car.'), and the largest distance between the two
    box_house tracks [m] (track_max_diff_m) and at 12 s (track_diff_12s_m)."""
    mj = figures(lambda world: build(world_file=world, peer=peer))
    car = figures(CarSim)
    out = {}
    for k in mj:
        if k == 'track':
            continue
        out[k] = mj[k]
        out['car.' + k] = car[k]
    d = [math.hypot(a[0] - b[0], a[1] - b[1]) for a, b in zip(mj['track'], car['track'])]
    out['track_max_diff_m'] = max(d)
    out['track_diff_12s_m'] = d[120]
    return out


def print_validation(v, peer='strong', file=sys.stdout):
    print('MuJoCo %s, %s model, against car (same measurement):' % (version(), peer), file=file)
    print('  rest height %.6f m (car %.6f)' % (v['rest_height_m'], v['car.rest_height_m']), file=file)
    print('  circle radius %.4f m, centre (%.3f, %.3f) (car %.4f m, (%.3f, %.3f))' % (
        v['circle_radius_m'], v['circle_centre_x_m'], v['circle_centre_y_m'], v['car.circle_radius_m'],
        v['car.circle_centre_x_m'], v['car.circle_centre_y_m']), file=file)
    print('  yaw rate %.4f rad/s (car %.4f)' % (v['yaw_rate_rad_s'], v['car.yaw_rate_rad_s']), file=file)
    print('  straight line %.4f m/s (car %.4f)' % (v['straight_speed_m_s'], v['car.straight_speed_m_s']), file=file)
    print('  box_house track over 24 s: largest distance from car\'s %.3f m (%.3f m at 12 s)' % (
        v['track_max_diff_m'], v['track_diff_12s_m']), file=file)


def rates(steps, settle=SETTLE, sleep=False, peer='old', world_file=WORLD):
    """(steps per wall second, steps per CPU second of this thread) of MuJoCo's own loop (mj_step with nstep: no
    Python per step) driving the seed command in a world (box_house; None: the bare plane), on a model built
    afresh. peer 'old': sleep turns island sleeping on; 'strong' always sleeps (the robot never)."""
    import mujoco
    p = build(world_file=world_file, peer=peer)
    if sleep:
        # data made after the flag (MuJoCo sets up its sleep state when it makes the data)
        p.model.opt.enableflags |= int(mujoco.mjtEnableBit.mjENBL_SLEEP)
        p.data = mujoco.MjData(p.model)
    p.set_cmd_vel(1.0, 1.0)
    # the strong model ramps as the plug-in does (the ramp ends after 0.6 s: the timed run's servo targets are
    # constant); the old one was timed with the targets set at once, as before
    p.step(settle, ramp=peer == 'strong')
    t, c = time.perf_counter(), time.thread_time()
    mujoco.mj_step(p.model, p.data, nstep=steps)
    c, t = time.thread_time() - c, time.perf_counter() - t
    return steps / t, steps / max(c, 1e-9)


def steps_per_second(steps, settle=SETTLE, sleep=False, peer='old', world_file=WORLD):
    """Steps per wall second of rates()."""
    return rates(steps, settle, sleep, peer, world_file)[0]


def version():
    import mujoco
    return mujoco.__version__


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--steps', type=int, default=30000)
    ap.add_argument('--peer', choices=('strong', 'old'), default='strong')
    a = ap.parse_args()
    print_validation(validate(a.peer), a.peer)
    for name, world in (('box_house', WORLD), ('bare plane', None)):
        if a.peer == 'old':
            print('MuJoCo old model, %s, steps/s: %.0f (sleeping off), %.0f (sleeping on)' % (
                name, steps_per_second(a.steps, world_file=world),
                steps_per_second(a.steps, sleep=True, world_file=world)))
        else:
            print('MuJoCo strong model, %s, steps/s: %.0f' % (
                name, steps_per_second(a.steps, peer='strong', world_file=world)))
    return 0


if __name__ == '__main__':
    sys.exit(main())
