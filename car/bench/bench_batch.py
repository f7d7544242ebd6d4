#!/usr/bin/env python3
"""Throughput of car's batch runs and Gymnasium vector env, measured in this run.

1. A sweep of N runs (examples/sweep.yaml's grid, each run shortened to --seconds of sim time): robot-simulated
   seconds per wall second with 1 local Ray worker, with all local cores, and on a two-node Ray cluster started
   on this machine (`ray start --head` + a second `ray start --address`, one CPU each), to show the cluster path.
2. car.gym: env steps/s (10 Hz control, 100 physics steps each) of DriveVectorEnv(N) against N separate DriveEnvs
   stepped one after the other from Python.

usage: bench_batch.py [--runs 64] [--seconds 5] [--envs 8] [--no-cluster]   (through bench/run.sh's environment)
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def sweep_runs(n, seconds):
    from car import scenario
    runs = scenario.load(os.path.join(ROOT, 'examples', 'sweep.yaml'))[:n]
    for r in runs:
        r['scenario']['duration'] = seconds
    return runs


def sweep_rate(runs, **kw):
    from car import batch
    with tempfile.TemporaryDirectory() as out:
        t = time.perf_counter()
        res = batch.run_all(runs, out, progress=False, resume=False, **kw)
        wall = time.perf_counter() - t
    assert all(r['status'] == 'ok' for r in res), [r['error'] for r in res if r['status'] != 'ok'][:1]
    return sum(r['sim_time'] for r in res) / wall, wall


def cluster_rate(runs):
    env = dict(os.environ)
    ray = os.path.join(os.path.dirname(sys.executable), 'ray')
    port = '6391'
    subprocess.run([ray, 'start', '--head', '--port', port, '--num-cpus', '1', '--include-dashboard', 'false'],
                   check=True, capture_output=True, env=env)
    try:
        subprocess.run([ray, 'start', '--address', '127.0.0.1:' + port, '--num-cpus', '1'], check=True,
                       capture_output=True, env=env)
        return sweep_rate(runs, address='127.0.0.1:' + port)
    finally:
        subprocess.run([ray, 'stop', '--force'], capture_output=True, env=env)


def gym_rates(n, steps=50):
    import car.gym as cg
    acts = np.tile(np.array([0.3, 0.2], np.float32), (n, 1))
    v = cg.DriveVectorEnv(n, goal=(50.0, 0.0))
    v.reset(seed=0)
    t = time.perf_counter()
    for _ in range(steps):
        v.step(acts)
    vec = n * steps / (time.perf_counter() - t)
    envs = [cg.DriveEnv(goal=(50.0, 0.0)) for _ in range(n)]
    for i, e in enumerate(envs):
        e.reset(seed=i)
    t = time.perf_counter()
    for _ in range(steps):
        for e, a in zip(envs, acts):
            e.step(a)
    sep = n * steps / (time.perf_counter() - t)
    return vec, sep


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument('--runs', type=int, default=64)
    ap.add_argument('--seconds', type=float, default=5.0)
    ap.add_argument('--envs', type=int, default=8)
    ap.add_argument('--no-cluster', dest='cluster', action='store_false')
    a = ap.parse_args()
    runs = sweep_runs(a.runs, a.seconds)
    print('batch: %d runs of the seed car in box_house, %.0f s of sim time each (load average %.1f, %d cores)'
          % (len(runs), a.seconds, os.getloadavg()[0], os.cpu_count()))
    one, w1 = sweep_rate(runs, workers=1)
    print('%-44s %10.1f robot-sim-s per wall s (%.0f s)' % ('Ray, 1 local worker', one, w1))
    allc, wa = sweep_rate(runs, workers=os.cpu_count())
    print('%-44s %10.1f robot-sim-s per wall s (%.0f s), %.2fx one worker' % (
        'Ray, %d local workers' % os.cpu_count(), allc, wa, allc / one))
    if a.cluster:
        cl, wc = cluster_rate(runs)
        print('%-44s %10.1f robot-sim-s per wall s (%.0f s), %.2fx one worker' % (
            'Ray cluster: head + 1 node, 1 CPU each', cl, wc, cl / one))
    vec, sep = gym_rates(a.envs)
    print('%-44s %10.0f env steps/s' % ('car.gym DriveVectorEnv(%d)' % a.envs, vec))
    print('%-44s %10.0f env steps/s, vector/separate %.2f' % ('%d separate DriveEnv' % a.envs, sep, vec / sep))
    return 0


if __name__ == '__main__':
    sys.exit(main())
