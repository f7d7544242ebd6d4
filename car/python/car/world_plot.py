"""Pictures of batch runs: the world's footprint from above with each run's trajectory, and a sweep plot.

plot_runs(world_file, runs_parquet, out_png): the occupancy slice of the world (world_map.occupancy, the same
slice as `world_tool map`) in grey, each run's trajectory coloured by run, a circle at the start, a square at the
end, a red x where the run ended with collisions > 0. plot_sweep(runs_parquet, param, metric, out_png): a metric
against a swept parameter, one point per run (failed runs left out). Matplotlib with the Agg back end (headless).
"""
from __future__ import annotations

import math


def _pyplot():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    return plt


def _read(path):
    import pyarrow.parquet as pq
    return pq.read_table(path).to_pydict()


def plot_runs(world_file, runs_parquet=None, out_png='runs.png', resolution=0.05, z_min=0.05, z_max=0.5):
    """Writes the top view; returns (number of runs drawn, image size in pixels)."""
    import numpy as np

    from car import world_map, world_tools
    plt = _pyplot()
    desc = world_tools.load(world_file, [])
    grid, (ox, oy), _ = world_map.occupancy(desc, resolution, z_min, z_max)
    h, w = grid.shape
    fig, ax = plt.subplots(figsize=(8, 8 * h / max(w, 1) + 0.5), dpi=100)
    ax.imshow(np.where(grid == world_map.OCCUPIED, 0.35, 1.0), cmap='gray', vmin=0, vmax=1, origin='lower',
              extent=(ox, ox + w * resolution, oy, oy + h * resolution), interpolation='nearest')
    drawn = 0
    if runs_parquet:
        import os
        runs = _read(runs_parquet)
        traj_path = os.path.join(os.path.dirname(runs_parquet), 'trajectories.parquet')
        traj = _read(traj_path)
        by_run = {}
        for i, run in enumerate(traj['run']):
            by_run.setdefault((run, traj['robot'][i]), []).append((traj['t'][i], traj['x'][i], traj['y'][i]))
        collided = {(runs['run'][i], runs['robot'][i]) for i in range(len(runs['run'])) if runs['collisions'][i] > 0}
        cmap = plt.get_cmap('viridis')
        keys = sorted(by_run)
        for k, key in enumerate(keys):
            pts = sorted(by_run[key])
            xs, ys = [p[1] for p in pts], [p[2] for p in pts]
            c = cmap(k / max(1, len(keys) - 1))
            ax.plot(xs, ys, '-', color=c, linewidth=1.2, alpha=0.9)
            ax.plot(xs[0], ys[0], 'o', color=c, markersize=4)
            ax.plot(xs[-1], ys[-1], 's', color=c, markersize=4)
            if key in collided:
                ax.plot(xs[-1], ys[-1], 'x', color='red', markersize=8, markeredgewidth=2)
            drawn += 1
    ax.set_xlabel('x [m]')
    ax.set_ylabel('y [m]')
    ax.set_aspect('equal')
    ax.set_title('%s%s' % (desc.get('name', world_file), ': %d runs (o start, s end, x collided)' % drawn if drawn else ''))
    fig.tight_layout()
    fig.savefig(out_png)
    size = fig.get_size_inches() * fig.dpi
    plt.close(fig)
    return drawn, (int(round(size[0])), int(round(size[1])))


def plot_sweep(runs_parquet, param, metric, out_png='sweep.png'):
    """A metric against a swept parameter ('robots.0.pose.x' or 'sweep.robots.0.pose.x'); returns points drawn."""
    plt = _pyplot()
    runs = _read(runs_parquet)
    col = param if param in runs else 'sweep.' + param
    if col not in runs:
        raise ValueError('%s is not a swept parameter of %s (swept: %s)' % (
            param, runs_parquet, ', '.join(k[6:] for k in runs if k.startswith('sweep.')) or 'none'))
    if metric not in runs:
        raise ValueError('unknown metric %r' % metric)
    pts = [(runs[col][i], runs[metric][i]) for i in range(len(runs['run']))
           if runs['status'][i] == 'ok' and runs[col][i] is not None and not math.isnan(float(runs[metric][i]))]
    fig, ax = plt.subplots(figsize=(6, 4), dpi=100)
    ax.plot([p[0] for p in pts], [p[1] for p in pts], 'o', alpha=0.7)
    ax.set_xlabel(col[6:] if col.startswith('sweep.') else col)
    ax.set_ylabel(metric)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(out_png)
    plt.close(fig)
    return len(pts)
