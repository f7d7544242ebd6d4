"""What a failed test leaves behind: a top-down PNG of the models' trajectories over the world, and a rosbag of the
recorded topics."""
import os


def write_bag(path, recordings, trajectories=None):
    """Writes every Recorded message of the recordings to a rosbag at path, each at its sim stamp, in stamp order
    (ties in arrival order). Returns the number of messages written."""
    import rosbag
    import rospy
    msgs = [r for rec in recordings for r in rec.snapshot()]
    msgs.sort(key=lambda r: r.stamp)
    with rosbag.Bag(path, 'w') as bag:
        for r in msgs:
            bag.write(r.topic, r.msg, t=rospy.Time.from_sec(max(r.stamp, 0.0)))
    return len(msgs)


def write_plot(path, world, trajectories, title=''):
    """The world's occupancy slice (world_plot's, as `world_tool plot`) with each model's ground-truth path: a
    circle at its start, a square at its end. world None: car's empty world (the paths alone). Returns the number
    of models drawn."""
    from car import world_plot
    plt = world_plot._pyplot()
    if world:
        import numpy as np
        from car import world_map, world_tools
        desc = world_tools.load(world)
        res = 0.05
        grid, (ox, oy), _ = world_map.occupancy(desc, res, 0.05, 0.5)
        h, w = grid.shape
        fig, ax = plt.subplots(figsize=(8, 8 * h / max(w, 1) + 0.5), dpi=100)
        ax.imshow(np.where(grid == world_map.OCCUPIED, 0.35, 1.0), cmap='gray', vmin=0, vmax=1, origin='lower',
                  extent=(ox, ox + w * res, oy, oy + h * res), interpolation='nearest')
    else:
        fig, ax = plt.subplots(figsize=(8, 8), dpi=100)
    cmap = plt.get_cmap('tab10')
    drawn = 0
    for k, (name, pts) in enumerate(sorted(trajectories.items())):
        xs, ys = [p[1] for p in pts], [p[2] for p in pts]
        if not xs or (max(xs) - min(xs) < 1e-6 and max(ys) - min(ys) < 1e-6 and name == 'ground_plane'):
            continue
        c = cmap(k % 10)
        ax.plot(xs, ys, '-', color=c, linewidth=1.2, label=name)
        ax.plot(xs[0], ys[0], 'o', color=c, markersize=4)
        ax.plot(xs[-1], ys[-1], 's', color=c, markersize=4)
        drawn += 1
    if drawn:
        ax.legend(loc='best', fontsize=7)
    ax.set_xlabel('x [m]')
    ax.set_ylabel('y [m]')
    ax.set_aspect('equal')
    ax.set_title(title or 'trajectories (o start, s end)', fontsize=9)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return drawn


def safe_name(nodeid):
    keep = ''.join(c if c.isalnum() or c in '-_.' else '_' for c in nodeid)
    return keep.strip('_')[-150:]


def artifact_dir(config):
    """car-artifacts/ beside the JUnit XML (--junitxml), else --car-artifacts (default ./car-artifacts)."""
    explicit = config.getoption('car_artifacts')
    if explicit:
        return os.path.abspath(explicit)
    xml = getattr(config.option, 'xmlpath', None)
    if xml:
        return os.path.join(os.path.dirname(os.path.abspath(xml)), 'car-artifacts')
    return os.path.join(str(config.rootpath), 'car-artifacts')
