"""car batch: run a scenario's sweep on Ray and write the results as Parquet.

  car batch SCENARIO.yaml [-o OUTDIR] [--address ADDR] [--workers N] [--retries N] [--no-resume] [--serial]

Each run is one Ray task (the core through the Python API, no ROS master), one world per task. A local Ray
instance on all cores is started unless --address names a running cluster (`ray start --head` on one machine,
`ray start --address HEAD:6379` on the others). Results stream back as tasks finish (a progress bar); a task whose
worker died is retried (--retries); finished runs are kept in OUTDIR/parts/ so a second invocation only runs what
is missing (--no-resume starts over). At the end: OUTDIR/runs.parquet (one row per run and robot: final pose,
distance, collisions, min lidar distance, status, wall time, the swept values) and OUTDIR/trajectories.parquet
(run, robot, t, x, y, yaw), OUTDIR/runs.png (the trajectories over the world's footprint, as `world_tool plot`)
and a summary on the terminal. --serial runs in this process without Ray.
Exit status: 0 all runs ok, 1 some runs failed, 2 the scenario is invalid.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time

from car import batch_run, scenario


def _part_path(outdir, run_id):
    return os.path.join(outdir, 'parts', run_id + '.json')


def _save_part(outdir, result):
    path = _part_path(outdir, result['id'])
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        json.dump(result, f, allow_nan=True)
    os.replace(tmp, path)


def _load_part(outdir, run_id):
    try:
        with open(_part_path(outdir, run_id)) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def run_all(runs, outdir, address=None, workers=None, retries=2, resume=True, serial=False, progress=True):
    """Runs every run not already finished in outdir; returns all results in run order."""
    os.makedirs(os.path.join(outdir, 'parts'), exist_ok=True)
    results = {}
    if resume:
        for r in runs:
            part = _load_part(outdir, r['id'])
            if part is not None:
                results[r['id']] = part
    todo = [r for r in runs if r['id'] not in results]
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=len(runs), initial=len(runs) - len(todo), unit='run', file=sys.stderr)
    if todo and serial:
        for r in todo:
            res = batch_run.run(r)
            _save_part(outdir, res)
            results[r['id']] = res
            if bar:
                bar.update(1)
    elif todo:
        import ray
        env = {'env_vars': {k: os.environ[k] for k in ('PYTHONPATH', 'ROS_PACKAGE_PATH', 'LD_LIBRARY_PATH',
                                                      'CMAKE_PREFIX_PATH', 'GAZEBO_MODEL_PATH') if k in os.environ}}
        if address:
            ray.init(address=address, runtime_env=env, log_to_driver=False)
        else:
            ray.init(num_cpus=workers or os.cpu_count(), include_dashboard=False, runtime_env=env,
                     log_to_driver=False)
        try:
            task = ray.remote(max_retries=retries)(batch_run.run)
            pending = {task.remote(r): r for r in todo}
            while pending:
                done, _ = ray.wait(list(pending), num_returns=1)
                for ref in done:
                    r = pending.pop(ref)
                    try:
                        res = ray.get(ref)
                    except Exception as e:  # the worker died more often than --retries allows
                        res = {'id': r['id'], 'index': r['index'], 'overrides': json.dumps(r['overrides'],
                                                                                          sort_keys=True, default=str),
                               'status': 'failed', 'error': 'worker lost: %s' % e, 'sim_time': 0.0, 'robots': [],
                               'wall_time': math.nan}
                    _save_part(outdir, res)
                    results[r['id']] = res
                    if bar:
                        bar.update(1)
        finally:
            ray.shutdown()
    if bar:
        bar.close()
    return [results[r['id']] for r in runs]


def write_parquet(results, outdir):
    """runs.parquet and trajectories.parquet from a list of results; returns their paths."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    runs = {k: [] for k in ('run', 'index', 'robot', 'status', 'error', 'x', 'y', 'yaw', 'distance', 'collisions',
                            'min_obstacle', 'sim_time', 'wall_time', 'overrides')}
    swept = sorted({k for res in results for k in json.loads(res['overrides'])})
    for k in swept:
        runs['sweep.' + k] = []
    traj = {k: [] for k in ('run', 'robot', 't', 'x', 'y', 'yaw')}
    for res in results:
        ov = json.loads(res['overrides'])
        rows = res['robots'] or [{'robot': '', 'x': math.nan, 'y': math.nan, 'yaw': math.nan, 'distance': math.nan,
                                  'collisions': -1, 'min_obstacle': math.nan, 'trajectory': []}]
        for row in rows:
            runs['run'].append(res['id'])
            runs['index'].append(res['index'])
            runs['robot'].append(row['robot'])
            runs['status'].append(res['status'])
            runs['error'].append(res['error'])
            for k in ('x', 'y', 'yaw', 'distance', 'min_obstacle'):
                runs[k].append(float(row[k]) if row[k] is not None else math.nan)
            runs['collisions'].append(int(row['collisions']))
            runs['sim_time'].append(res['sim_time'])
            runs['wall_time'].append(res['wall_time'])
            runs['overrides'].append(res['overrides'])
            for k in swept:
                v = ov.get(k)
                runs['sweep.' + k].append(None if v is None else str(v) if not isinstance(v, (int, float)) else float(v))
            for t, x, y, yaw in row['trajectory']:
                traj['run'].append(res['id'])
                traj['robot'].append(row['robot'])
                traj['t'].append(t)
                traj['x'].append(x)
                traj['y'].append(y)
                traj['yaw'].append(yaw)
    paths = (os.path.join(outdir, 'runs.parquet'), os.path.join(outdir, 'trajectories.parquet'))
    pq.write_table(pa.table(runs), paths[0])
    pq.write_table(pa.table(traj), paths[1])
    return paths


def summary(results) -> str:
    """A short table: runs ok/failed, and min / mean / max of each metric over the ok runs."""
    ok = [row for res in results if res['status'] == 'ok' for row in res['robots']]
    failed = [res for res in results if res['status'] != 'ok']
    lines = ['%d runs: %d ok, %d failed; %.1f robot-sim-s in %.1f s of worker time' % (
        len(results), len(results) - len(failed), len(failed),
        sum(res['sim_time'] * max(1, len(res['robots'])) for res in results if res['status'] == 'ok'),
        sum(res['wall_time'] for res in results if math.isfinite(res['wall_time'])))]
    if ok:
        lines.append('%-14s %12s %12s %12s' % ('metric', 'min', 'mean', 'max'))
        for k in ('x', 'y', 'yaw', 'distance', 'collisions', 'min_obstacle'):
            vals = [float(r[k]) for r in ok if r[k] is not None and not (isinstance(r[k], float) and math.isnan(r[k]))]
            if vals:
                lines.append('%-14s %12.4f %12.4f %12.4f' % (k, min(vals), sum(vals) / len(vals), max(vals)))
    for res in failed[:5]:
        last = res['error'].strip().splitlines()[-1] if res['error'].strip() else '?'
        lines.append('failed run %s (#%d): %s' % (res['id'], res['index'], last))
    return '\n'.join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog='car batch', description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('scenario')
    ap.add_argument('-o', '--output', help='output folder (default: batch_out/<scenario name>)')
    ap.add_argument('--address', help="a running Ray cluster's address (default: start a local one)")
    ap.add_argument('--workers', type=int, help='local Ray CPUs (default: all cores)')
    ap.add_argument('--retries', type=int, default=2, help='retries of a task whose worker died')
    ap.add_argument('--no-resume', dest='resume', action='store_false', help='run every run again')
    ap.add_argument('--serial', action='store_true', help='run in this process, without Ray')
    ap.add_argument('--quiet', action='store_true', help='no progress bar')
    ap.add_argument('--no-plot', action='store_true', help='do not draw OUTDIR/runs.png')
    a = ap.parse_args(argv)
    try:
        runs = scenario.load(a.scenario)
    except scenario.ScenarioError as e:
        print('car batch: error: %s' % e, file=sys.stderr)
        return 2
    outdir = a.output or os.path.join('batch_out', runs[0]['scenario']['name'])
    t0 = time.perf_counter()
    results = run_all(runs, outdir, a.address, a.workers, a.retries, a.resume, a.serial, progress=not a.quiet)
    paths = write_parquet(results, outdir)
    print(summary(results))
    print('wall time %.1f s; results: %s, %s' % (time.perf_counter() - t0, paths[0], paths[1]))
    world = runs[0]['scenario']['world']
    if world and not a.no_plot:
        from car import world_plot
        png = os.path.join(outdir, 'runs.png')
        try:
            world_plot.plot_runs(world, paths[0], png)
            print('plot: %s' % png)
        except ValueError as e:  # a world with nothing to slice (ground only)
            print('plot: not drawn (%s)' % e)
    return 0 if all(r['status'] == 'ok' for r in results) else 1


if __name__ == '__main__':
    sys.exit(main())
