#!/usr/bin/env python3
"""Throughput of car.gym.DriveVectorEnv(n) against n separate DriveEnvs in one process (docs/BATCH.md).

Every round, for each n: the vector env and n separate envs (built once) are reset to the same seeds and stepped
--steps env steps (10 Hz control, 100 physics steps each; action (0.3 m/s, 0.2 rad/s), goal far away so nothing
ends); the separate envs one after the other from Python. Then one world alone is stepped the same physics steps
in one C++ call (world.step): the single-world core rate. The order of the three alternates between rounds.
Printed: median and best of the rounds' env steps/s, the median of the rounds' vector/separate ratios, the
vector env's physics steps/s per core (cores = min(pool threads, n)) against the single-world core rate, and the
CPUs the process got while timed (process CPU s / wall s: below 2 on 2 cores, other processes took the rest).

usage: bench_vector_env.py [--envs 8 32] [--steps 30] [--rounds 5] [--json FILE]   (with the workspace sourced)
"""
import argparse
import json
import os
import statistics
import sys
import time

import numpy as np


CPU = []  # (wall s, process CPU s) of the last timed call


def timed(fn):
    t, c = time.perf_counter(), time.process_time()
    fn()
    CPU[:] = [time.perf_counter() - t, time.process_time() - c]
    return CPU[0]


def rounds_for(n, steps, rounds, threads):
    import car.gym as cg
    kw = dict(goal=(50.0, 0.0))
    vec = cg.DriveVectorEnv(n, **kw)
    sep = [cg.DriveEnv(**kw) for _ in range(n)]
    one = cg.DriveEnv(**kw)
    k = vec.envs[0].steps_per_action
    acts = np.tile(np.array([0.3, 0.2], np.float32), (n, 1))

    def run_vec():
        vec.reset(seed=0)
        return timed(lambda: [vec.step(acts) for _ in range(steps)])

    def run_sep():
        for i, e in enumerate(sep):
            e.reset(seed=i)
        return timed(lambda: [e.step(a) for _ in range(steps) for e, a in zip(sep, acts)])

    def run_one():
        one.reset(seed=0)
        one.world.set_cmd_vel(one.ROBOT, 0.3, 0.2)
        return timed(lambda: one.world.step(steps * k))

    runs = [('vector', run_vec), ('separate', run_sep), ('core', run_one)]
    out = {'vector': [], 'separate': [], 'core': [], 'ratio': [], 'vector_cpu_per_wall': [],
           'separate_cpu_per_wall': [], 'core_cpu_per_wall': []}
    for r in range(rounds):
        got = {}
        for name, fn in (runs if r % 2 == 0 else runs[::-1]):
            got[name] = fn()
            out[name + '_cpu_per_wall'].append(CPU[1] / CPU[0])  # CPUs this process used while timed
        out['vector'].append(n * steps / got['vector'])       # env steps/s
        out['separate'].append(n * steps / got['separate'])   # env steps/s
        out['core'].append(steps * k / got['core'])           # physics steps/s of one world
        out['ratio'].append(got['separate'] / got['vector'])
    cores = min(threads, n)
    per_core = [v * k / cores for v in out['vector']]          # physics steps/s per core
    return {
        'n': n, 'env_steps': steps, 'physics_steps_per_env_step': k, 'cores': cores,
        'vector_env_steps_per_s': {'median': statistics.median(out['vector']), 'best': max(out['vector'])},
        'separate_env_steps_per_s': {'median': statistics.median(out['separate']), 'best': max(out['separate'])},
        'vector_over_separate': {'median': statistics.median(out['ratio']), 'best': max(out['ratio'])},
        'vector_physics_steps_per_s_per_core': {'median': statistics.median(per_core), 'best': max(per_core)},
        'single_world_core_steps_per_s': {'median': statistics.median(out['core']), 'best': max(out['core'])},
        'per_core_over_single_world': statistics.median(per_core) / statistics.median(out['core']),
        'vector_cpu_per_wall': statistics.median(out['vector_cpu_per_wall']),
        'separate_cpu_per_wall': statistics.median(out['separate_cpu_per_wall']),
        'core_cpu_per_wall': statistics.median(out['core_cpu_per_wall']),
        'rounds': out,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--envs', type=int, nargs='+', default=[8, 32])
    ap.add_argument('--steps', type=int, default=30, help='env steps per round (default 30 = 3 s of sim time)')
    ap.add_argument('--rounds', type=int, default=5)
    ap.add_argument('--json', help='write the results here')
    a = ap.parse_args()
    threads = int(os.environ.get('OMP_NUM_THREADS', 0)) or os.cpu_count()
    load = os.getloadavg()[0]
    print('vector env: box_house, the seed car, %d env steps per round, %d rounds, %d pool threads, %d cores, '
          'load average %.1f' % (a.steps, a.rounds, threads, os.cpu_count(), load))
    res = []
    for n in a.envs:
        r = rounds_for(n, a.steps, a.rounds, threads)
        res.append(r)
        f = '%-34s median %8.0f  best %8.0f %s'
        print(f % ('DriveVectorEnv(%d)' % n, r['vector_env_steps_per_s']['median'],
                   r['vector_env_steps_per_s']['best'], 'env steps/s'))
        print(f % ('%d separate DriveEnv' % n, r['separate_env_steps_per_s']['median'],
                   r['separate_env_steps_per_s']['best'], 'env steps/s'))
        print('%-34s median %8.2fx best %7.2fx' % ('  vector / separate', r['vector_over_separate']['median'],
                                                  r['vector_over_separate']['best']))
        print(f % ('  vector, per core (%d)' % r['cores'], r['vector_physics_steps_per_s_per_core']['median'],
                   r['vector_physics_steps_per_s_per_core']['best'], 'physics steps/s'))
        print(f % ('  one world, world.step', r['single_world_core_steps_per_s']['median'],
                   r['single_world_core_steps_per_s']['best'], 'physics steps/s'))
        print('%-34s %.2f' % ('  per core / one world (medians)', r['per_core_over_single_world']))
        print('%-34s vector %.2f, separate %.2f, one world %.2f' % (
            '  CPUs used (CPU s / wall s)', r['vector_cpu_per_wall'], r['separate_cpu_per_wall'],
            r['core_cpu_per_wall']))
    print('load average after: %.1f' % os.getloadavg()[0])
    if a.json:
        with open(a.json, 'w') as f:
            json.dump({'threads': threads, 'cores': os.cpu_count(), 'load_before': load,
                       'load_after': os.getloadavg()[0], 'results': res}, f, indent=1)
    return 0


if __name__ == '__main__':
    sys.exit(main())
