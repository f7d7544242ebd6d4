#!/usr/bin/env python3
"""Time to the first step of box_house with the seed car (examples/sweep.yaml's run), cold and in a warm worker.

Three paths, interleaved (the order rotates each round), each timed from nothing to the end of the first step with
the lidar on:
  cold        a new Python process: import car._core (libcar_sim, sdformat and its static initialisers), expand
              the xacro, parse box_house and the URDF, build the World, spawn, step. Timed inside the process,
              from before the import (the interpreter's own start is printed apart).
  warm parse  a process that has done it before, parsing the world file and the URDF again (World(path) and
              spawn_urdf: what car batch did per run before car.world_cache).
  warm        a process that has done it before, through car.world_cache (car batch's path): World(description)
              from the parsed world, spawn_model from the parsed robot, one step.
Printed: each phase's median over the rounds (milliseconds), each path's median and best, and the ratios of the
medians. --json FILE writes the figures (startup.* keys, as bench_physics.py's); --merge-json FILE adds them to
an existing JSON file (bench/run.sh --json).

usage: bench_startup.py [--rounds 7] [--json FILE | --merge-json FILE]   (with the workspace sourced)
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
XACRO = os.path.join(ROOT, 'urdf', 'car_camera_lidar04.xacro')
T = time.perf_counter


def lidar_on(world):
    for s in world.sensors():
        if s['kind'] == 'laser':
            world.set_sensor_active(s['robot'], s['plugin'], True)


def cold_child():
    """The cold path in this (new) process; prints its phases [s] as JSON."""
    t0 = T()
    from car import _core
    t1 = T()
    from car import xacro_tool
    t2 = T()
    text = xacro_tool.expand(XACRO, {})
    t3 = T()
    desc = _core.parse_world_file(WORLD)
    t4 = T()
    model = _core.parse_urdf_string(text, 'mycar')
    t5 = T()
    world = _core.World(desc, seed=1)
    t6 = T()
    world.spawn_model(model, 'mycar')
    t7 = T()
    lidar_on(world)
    world.step(1)
    t8 = T()
    print(json.dumps({'import_core': t1 - t0, 'import_xacro': t2 - t1, 'xacro': t3 - t2, 'parse_world': t4 - t3,
                      'parse_urdf': t5 - t4, 'build_world': t6 - t5, 'spawn': t7 - t6, 'first_step': t8 - t7,
                      'total': t8 - t0}))


def cold():
    t = T()
    out = subprocess.run([sys.executable, os.path.abspath(__file__), '--cold-child'], check=True,
                         capture_output=True, text=True).stdout
    wall = T() - t
    ph = json.loads(out.strip().splitlines()[-1])
    # the interpreter's start and exit: the process's wall time less what it timed itself
    ph['interpreter'] = wall - ph['total']
    return ph


def warm_parse(text):
    from car import _core
    t0 = T()
    world = _core.World(WORLD, seed=1)
    t1 = T()
    world.spawn_urdf(text, 'mycar')
    t2 = T()
    lidar_on(world)
    world.step(1)
    t3 = T()
    # sdformat's fixed cost per document: an empty world parsed the same way
    _core.empty_world_description()
    t4 = T()
    return {'parse_and_build_world': t1 - t0, 'parse_urdf_and_spawn': t2 - t1, 'first_step': t3 - t2,
            'total': t3 - t0, 'parse_empty_world': t4 - t3}


def warm(text):
    from car import _core, world_cache
    t0 = T()
    desc, _ = world_cache.world_description(WORLD)
    model = world_cache.robot_model(text, 'mycar')
    t1 = T()
    world = _core.World(desc, seed=1)
    t2 = T()
    world.spawn_model(model, 'mycar')
    t3 = T()
    lidar_on(world)
    world.step(1)
    t4 = T()
    return {'cache_lookup': t1 - t0, 'build_world': t2 - t1, 'spawn': t3 - t2, 'first_step': t4 - t3,
            'total': t4 - t0}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--rounds', type=int, default=7, help='interleaved rounds (default 7)')
    ap.add_argument('--json', metavar='FILE', help='write the figures to FILE')
    ap.add_argument('--merge-json', metavar='FILE', help='add the figures to the JSON object in FILE')
    ap.add_argument('--cold-child', action='store_true', help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.cold_child:
        cold_child()
        return 0
    if a.rounds < 1:
        ap.error('--rounds must be at least 1')
    from car import world_cache, xacro_tool
    text = xacro_tool.expand(XACRO, {})
    # this process warm: libraries loaded, the world and the robot parsed once, one world built and stepped
    warm(text)
    warm_parse(text)
    paths = [('cold', cold), ('warm_parse', lambda: warm_parse(text)), ('warm', lambda: warm(text))]
    samples = {name: [] for name, _ in paths}
    load = []
    for r in range(a.rounds):
        for name, fn in paths[r % 3:] + paths[:r % 3]:
            samples[name].append(fn())
        load.append(os.getloadavg()[0])
    med = {name: {k: statistics.median(s[k] for s in ss) for k in ss[0]} for name, ss in samples.items()}
    best = {name: min(s['total'] for s in ss) for name, ss in samples.items()}
    print('time to the first step, box_house + seed car (car_camera_lidar04.xacro), lidar on; median of %d '
          'interleaved rounds [ms] (load average %.1f .. %.1f, %d cores)'
          % (a.rounds, min(load), max(load), os.cpu_count()))
    labels = {'cold': 'cold (new process)', 'warm_parse': 'warm, parsing each run (before world_cache)',
              'warm': 'warm, car.world_cache (car batch)'}
    for name, _ in paths:
        print('  %-44s %8.1f   (best %.1f)' % (labels[name], 1e3 * med[name]['total'], 1e3 * best[name]))
        for k, v in med[name].items():
            if k != 'total':
                print('      %-40s %8.1f' % (k, 1e3 * v))
    ratio_cold = med['cold']['total'] / med['warm']['total']
    ratio_parse = med['warm_parse']['total'] / med['warm']['total']
    print('  cold / warm %.0fx, warm parsing / warm cached %.0fx (medians)' % (ratio_cold, ratio_parse))
    fig = {'startup.rounds': a.rounds, 'startup.load_average_1min': load,
           'startup.method': 'time to the end of the first step of box_house with the seed car, lidar on; '
                             'median and best of %d interleaved rounds [s]' % a.rounds,
           'ratio.startup_cold_vs_warm.median': ratio_cold, 'ratio.startup_warm_parse_vs_warm.median': ratio_parse}
    for name, _ in paths:
        fig['startup.%s_s' % name] = best[name]
        fig['startup.%s_s.median' % name] = med[name]['total']
        fig['startup.%s_s.samples' % name] = [s['total'] for s in samples[name]]
        fig['startup.%s.phases_s.median' % name] = {k: v for k, v in med[name].items() if k != 'total'}
    if a.merge_json:
        with open(a.merge_json) as f:
            old = json.load(f)
        old.update(fig)
        fig = old
    if a.json or a.merge_json:
        with open(a.json or a.merge_json, 'w') as f:
            json.dump(fig, f, indent=1, sort_keys=True)
        print('figures written to %s' % (a.json or a.merge_json))
    world_cache.clear()
    return 0


if __name__ == '__main__':
    sys.exit(main())
