"""One scenario run in the core (no ROS): build the world, spawn the robots, drive them, measure.

run(run) -> result dict (plain Python values, so it travels through Ray and into Parquet):
  id, index, overrides (JSON text), status ('ok' | 'failed'), error (traceback text or ''),
  per robot (one row each in `robots`): final x, y, yaw [m, rad] (world frame, ground truth), distance [m]
  (path length of the base, sampled at 100 Hz), collisions (contact onsets with anything but a ground plane,
  counted per touched body at 100 Hz), min_obstacle [m] (the smallest finite lidar range seen, NaN without a lidar),
  and the trajectory (t, x, y, yaw at the scenario's record_rate);
  sim_time [s], wall_time [s].
The same run (scenario and seed) gives bit-identical numbers on any worker: the core is deterministic and
nothing here reads a clock except wall_time.
"""
from __future__ import annotations

import importlib.util
import json
import math
import time
import traceback

from car import world_cache

SAMPLE_HZ = 100.0  # [Hz] how often distance and contacts are sampled


def _load_controller(spec: str):
    path, func = spec.rsplit(':', 1)
    mod_name = 'car_controller_%d' % (abs(hash(path)) % 10**9)
    s = importlib.util.spec_from_file_location(mod_name, path)
    mod = importlib.util.module_from_spec(s)
    s.loader.exec_module(mod)
    if not hasattr(mod, func):
        raise AttributeError('%s has no function %r' % (path, func))
    return getattr(mod, func)


# Expanded models per worker process: (path, modification time, xacro args) -> URDF text. A sweep that does not
# change the model expands it once per worker, not once per run.
_MODELS = {}


def _model_text(robot: dict) -> str:
    import os
    key = (robot['model'], os.path.getmtime(robot['model']), json.dumps(robot['xacro_args'], sort_keys=True))
    if key not in _MODELS:
        if robot['model'].endswith('.xacro'):
            from car import xacro_tool
            _MODELS[key] = xacro_tool.expand(robot['model'], robot['xacro_args'])
        else:
            with open(robot['model'], encoding='utf-8') as f:
                _MODELS[key] = f.read()
    return _MODELS[key]


def simulate(sc: dict) -> dict:
    """Runs one validated scenario; returns {'sim_time', 'robots': [per-robot metrics and trajectory]}."""
    from car import _core
    # the world and the robots' models are parsed once per worker (car.world_cache); each run builds its own
    # World from those const descriptions, so a run's results do not depend on what the worker ran before
    desc, ground = world_cache.world_description(sc['world'])
    world = _core.World(desc, seed=sc['seed'])
    dt = world.dt
    robots = sc['robots']
    lidars = {}
    for r in robots:
        p = r['pose']
        world.spawn_model(world_cache.robot_model(_model_text(r), r['name']), r['name'], p['x'], p['y'], p['z'],
                          p['roll'], p['pitch'], p['yaw'])
    for s in world.sensors():
        if s['kind'] == 'laser' and s['robot'] not in lidars:
            lidars[s['robot']] = s['plugin']
            world.set_sensor_active(s['robot'], s['plugin'], True)
    controllers = {r['name']: _load_controller(r['drive']['controller']) for r in robots if r['drive']['controller']}
    state = {r['name']: {'distance': 0.0, 'collisions': 0, 'touching': set(), 'min_obstacle': math.inf,
                         'scan': None, 'scan_info': None, 'traj': [], 'last': None, 'next_cmd': 0, 'v': 0.0,
                         'w': 0.0} for r in robots}

    total = int(round(sc['duration'] / dt))
    sample_every = max(1, int(round(1.0 / (SAMPLE_HZ * dt))))
    record_every = int(round(1.0 / (sc['record_rate'] * dt))) if sc['record_rate'] > 0 else 0
    control_every = {r['name']: max(1, int(round(1.0 / (r['drive']['rate'] * dt)))) for r in robots}

    def observe(name, tick):
        ms = world.model_state(name)
        return {'time': tick * dt, 'x': ms['position'][0], 'y': ms['position'][1], 'yaw': ms['yaw'],
                'v': math.hypot(ms['linear'][0], ms['linear'][1]), 'w': ms['angular'][2],
                'scan': state[name]['scan'], 'scan_info': state[name]['scan_info']}

    tick = 0
    while True:
        # commands due at this tick
        for r in robots:
            n, st, d = r['name'], state[r['name']], r['drive']
            if n in controllers:
                if tick % control_every[n] == 0:
                    v, w = controllers[n](observe(n, tick))
                    world.set_cmd_vel(n, float(v), float(w))
            else:
                cmds = d['commands']
                while st['next_cmd'] < len(cmds) and cmds[st['next_cmd']]['t'] <= tick * dt + 1e-12:
                    c = cmds[st['next_cmd']]
                    world.set_cmd_vel(n, c['v'], c['w'])
                    st['next_cmd'] += 1
        # measurements due at this tick
        if tick % sample_every == 0 or tick == total:
            touching = {r['name']: set() for r in robots}
            for c in world.contacts():
                a, b = c['a'].split('/')[0], c['b'].split('/')[0]
                if a in touching and b not in ground:
                    touching[a].add(c['b'])
                if b in touching and a not in ground:
                    touching[b].add(c['a'])
            for r in robots:
                st = state[r['name']]
                st['collisions'] += len(touching[r['name']] - st['touching'])
                st['touching'] = touching[r['name']]
                ms = world.model_state(r['name'])
                pos = ms['position']
                if st['last'] is not None:
                    st['distance'] += math.hypot(pos[0] - st['last'][0], pos[1] - st['last'][1])
                st['last'] = pos
            outs = world.take_sensor_outputs()
            for s in outs.get('scans', []):
                st = state[s['robot']]
                ranges = s['ranges'].tolist() if hasattr(s['ranges'], 'tolist') else [float(x) for x in s['ranges']]
                finite = [x for x in ranges if math.isfinite(x)]
                if finite:
                    st['min_obstacle'] = min(st['min_obstacle'], min(finite))
                st['scan'] = ranges
                # the geometry a controller needs to tell the ranges' bearings [rad] and validity [m]
                st['scan_info'] = {k: float(s[k]) for k in ('angle_min', 'angle_increment', 'range_min', 'range_max')}
        if record_every and (tick % record_every == 0 or tick == total):
            for r in robots:
                ms = world.model_state(r['name'])
                state[r['name']]['traj'].append((tick * dt, ms['position'][0], ms['position'][1], ms['yaw']))
        if tick >= total:
            break
        # step to the next tick where something is due (commands, samples, records, controllers)
        due = [sample_every - tick % sample_every]
        if record_every:
            due.append(record_every - tick % record_every)
        for r in robots:
            n = r['name']
            if n in controllers:
                due.append(control_every[n] - tick % control_every[n])
            else:
                cmds, i = r['drive']['commands'], state[n]['next_cmd']
                if i < len(cmds):
                    due.append(max(1, int(math.ceil(cmds[i]['t'] / dt - 1e-9)) - tick))
        n = max(1, min(min(due), total - tick))
        world.step(n)
        tick += n

    rows = []
    for r in robots:
        st = state[r['name']]
        ms = world.model_state(r['name'])
        rows.append({'robot': r['name'], 'x': ms['position'][0], 'y': ms['position'][1], 'yaw': ms['yaw'],
                     'distance': st['distance'], 'collisions': st['collisions'],
                     'min_obstacle': st['min_obstacle'] if math.isfinite(st['min_obstacle']) else math.nan,
                     'trajectory': st['traj']})
    return {'sim_time': total * dt, 'robots': rows}


def run(r: dict) -> dict:
    """One run of a sweep (see car.scenario.expand): never raises; a failure is a result with status 'failed'."""
    t0 = time.perf_counter()
    out = {'id': r['id'], 'index': r['index'], 'overrides': json.dumps(r['overrides'], sort_keys=True, default=str),
           'status': 'ok', 'error': '', 'sim_time': 0.0, 'robots': []}
    try:
        out.update(simulate(r['scenario']))
    except Exception:  # a controller that raises, a model that does not load: this run fails, the others go on
        out['status'] = 'failed'
        out['error'] = traceback.format_exc()
    out['wall_time'] = time.perf_counter() - t0
    return out
