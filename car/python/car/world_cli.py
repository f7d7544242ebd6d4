"""world_tool: flatten, check and map SDF worlds.

  world_tool flatten WORLD [-o OUT]
  world_tool check WORLD [--json] [--strict]
  world_tool map WORLD [-o BASENAME] [--resolution 0.05] [--z-min 0.05] [--z-max 0.5] [--publish] [--frame odom]
  world_tool plot WORLD [--runs OUT/runs.parquet] [-o runs.png]
  world_tool plot --runs OUT/runs.parquet --sweep PARAM --metric METRIC [-o sweep.png]
"""
from __future__ import annotations

import argparse
import json
import sys

from car import world_tools


def cmd_flatten(a) -> int:
    try:
        left_out = []
        text = world_tools.flatten_to_string(a.world, left_out)
    except world_tools.WorldError as e:
        print('world_tool: error: %s' % e, file=sys.stderr)
        return 2
    for w in left_out:
        print('world_tool: warning: %s: %s' % (w['element'], w['message']), file=sys.stderr)
    if a.output:
        with open(a.output, 'w', encoding='utf-8') as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0


def cmd_check(a) -> int:
    report = world_tools.check(a.world)
    c = report['counts']
    code = 2 if c['error'] else (1 if a.strict and c['warning'] else 0)
    if a.json:
        report['exit_code'] = code
        print(json.dumps(report, indent=2))
        return code
    print('car world check: %s' % a.world)
    for p in report.get('plugins', []):
        # a world model's plug-in, simulated as a robot's (docs/COMPAT-sdf.md 16), with its resolved parameters
        where = " in sensor '%s' (%s) on link '%s'" % (p['sensor'], p['sensor_type'], p['link']) if p['sensor'] else ''
        print("  plug-in %s (%s) of model '%s' -> %s%s" % (p['name'], p['filename'], p['model'], p['kind'], where))
        for prm in p['params']:
            print('      %-32s %s%s%s' % (prm['key'], prm['value'] if prm['value'] != '' else "''",
                                        (' ' + prm['unit']) if prm['unit'] else '', '   (default)' if prm['default'] else ''))
    for f in report['findings'] or [{'severity': 'ok', 'element': '', 'message': 'no findings'}]:
        print('  %-7s %s%s' % (f['severity'], (f['element'] + ': ') if f['element'] else '', f['message']))
        if 'expected' in f:
            print('          declared %s' % f['declared'])
            print('          expected %s' % f['expected'])
    print('summary: %d error(s), %d warning(s), %d note(s)' % (c['error'], c['warning'], c['info']))
    return code


def cmd_map(a) -> int:
    from car import world_map
    try:
        desc = world_tools.load(a.world, [])
        grid, origin, skipped = world_map.occupancy(desc, a.resolution, a.z_min, a.z_max)
    except (world_tools.WorldError, ValueError) as e:
        print('world_tool: error: %s' % e, file=sys.stderr)
        return 2
    for s in skipped:
        print('world_tool: warning: %s is not sliced into the map' % s, file=sys.stderr)
    base = a.output or a.world.rsplit('/', 1)[-1].rsplit('.', 1)[0]
    pgm, yml = world_map.write_map(grid, origin, a.resolution, base)
    occupied = int((grid == world_map.OCCUPIED).sum())
    print('world_tool: %s + %s: %d x %d cells of %g m, origin (%g, %g), %d occupied, slab z %g..%g m'
          % (pgm, yml, grid.shape[1], grid.shape[0], a.resolution, origin[0], origin[1], occupied, a.z_min, a.z_max))
    if a.publish:
        # the one part of world_tool that needs ROS (car.ros and rospy; pip's wheel has neither)
        import importlib.util
        if importlib.util.find_spec('rospy') is None or importlib.util.find_spec('car.ros') is None:
            print('world_tool: error: --publish needs ROS (rospy and car.ros, which a pip install lacks); the map '
                  'is written', file=sys.stderr)
            return 2
        from car.ros import map_publisher
        map_publisher.publish(grid, origin, a.resolution, a.frame, a.topic, a.world)
    return 0


def cmd_plot(a) -> int:
    from car import world_plot
    try:
        if a.sweep:
            if not a.runs:
                raise ValueError('--sweep needs --runs')
            n = world_plot.plot_sweep(a.runs, a.sweep, a.metric, a.output or 'sweep.png')
            print('world_tool: %s: %s against %s, %d runs' % (a.output or 'sweep.png', a.metric, a.sweep, n))
            return 0
        if not a.world:
            raise ValueError('a world file is needed for the top view')
        n, size = world_plot.plot_runs(a.world, a.runs, a.output or 'runs.png')
        print('world_tool: %s: %d x %d px, %d trajectories' % (a.output or 'runs.png', size[0], size[1], n))
        return 0
    except (world_tools.WorldError, ValueError, OSError) as e:
        print('world_tool: error: %s' % e, file=sys.stderr)
        return 2


def main(argv=None) -> int:
    # roslaunch's remappings (NAME:=VALUE) dropped, as rospy.myargv does; without rospy, which a pip install lacks
    argv = [a for a in (sys.argv if argv is None else ['world_tool'] + list(argv)) if ':=' not in a][1:]
    ap = argparse.ArgumentParser(prog='world_tool', description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest='command', required=True)
    f = sub.add_parser('flatten', help='one self-contained world: includes resolved, <state> applied')
    f.add_argument('world')
    f.add_argument('-o', '--output')
    c = sub.add_parser('check', help='physics-aware checks of every link, unknown geometry, missing uris, poses')
    c.add_argument('world')
    c.add_argument('--json', action='store_true')
    c.add_argument('--strict', action='store_true', help='warnings fail (exit 1)')
    m = sub.add_parser('map', help="an occupancy grid in map_server's format (PGM + YAML)")
    m.add_argument('world')
    m.add_argument('-o', '--output', help='base name of the .pgm and .yaml (default: the world name)')
    m.add_argument('--resolution', type=float, default=0.05, help='[m] per cell (default 0.05)')
    m.add_argument('--z-min', type=float, default=0.05, help='[m] bottom of the slice (default 0.05)')
    m.add_argument('--z-max', type=float, default=0.5, help='[m] top of the slice (default 0.5)')
    m.add_argument('--publish', action='store_true', help='also publish it latched as nav_msgs/OccupancyGrid')
    m.add_argument('--topic', default='/map')
    m.add_argument('--frame', default='odom', help='frame of the published map (default odom, the simulator world)')
    p = sub.add_parser('plot', help='the world from above with batch runs\' trajectories, or a sweep plot')
    p.add_argument('world', nargs='?')
    p.add_argument('--runs', help='runs.parquet written by car batch (trajectories.parquet beside it)')
    p.add_argument('--sweep', help='plot METRIC against this swept parameter instead')
    p.add_argument('--metric', default='distance', help='a runs.parquet column (default distance)')
    p.add_argument('-o', '--output', help='PNG to write (default runs.png / sweep.png)')
    a = ap.parse_args(argv)
    return {'flatten': cmd_flatten, 'check': cmd_check, 'map': cmd_map, 'plot': cmd_plot}[a.command](a)


if __name__ == '__main__':
    sys.exit(main())
