#!/usr/bin/env python3
"""The README's performance table (issue 13's rows) from one `bash bench/run.sh --json FILE` run: each figure,
its peer and ratio from the same run, the target, and whether it is met.

usage: bench/table.py FILE.json      (prints Markdown)
"""
import json
import sys


def _rows(f):
    core = f['physics.car_core_cpp']
    mj = max(f['physics.mujoco'], f['physics.mujoco_sleep'])
    pb10 = f['physics.pybullet_10it']
    rows = [
        ('core physics, seed car in box_house, 1 kHz [steps/s]',
         '%.0f; %.2fx MuJoCo (best of sleeping on/off: %.0f), %.2fx PyBullet at 10 it. (%.0f)'
         % (core, core / mj, mj, core / pb10, pb10),
         '>= MuJoCo; >= 4x PyBullet', core >= mj and core >= 4 * pb10),
        ('ROS node `rtf:=0`, /odom subscribed [steps/s]',
         '%.0f = %.0f %% of the core' % (f['physics.car_ros_node'], 100 * f['physics.car_ros_node'] / core),
         '>= 90 % of the core', f['physics.car_ros_node'] >= 0.9 * core),
    ]
    if 'lidar.car_1core_rays_per_s' in f:
        rows += [
            ('seed cars with lidar (5.5 Hz) + diff drive at >= 1x real time, one process',
             '%d' % f['many.cars_at_1x_real_time'], '>= 100', f['many.cars_at_1x_real_time'] >= 100),
            ('lidar kernel, rays/s, 1 core',
             '%.1f M; %.2fx PyBullet rayTestBatch (%.1f M)' % (f['lidar.car_1core_rays_per_s'] / 1e6,
                                                             f['lidar.car_1core_rays_per_s'] / f['lidar.pybullet_1thread_rays_per_s'],
                                                             f['lidar.pybullet_1thread_rays_per_s'] / 1e6),
             '>= 20 M', f['lidar.car_1core_rays_per_s'] >= 20e6),
            ('depth + colour + cloud 640x480, 2 cores [frames/s]',
             '%.0f; %.1fx PyBullet TinyRenderer (%.1f)' % (f['depth.car_2core_fps'],
                                                           f['depth.car_2core_fps'] / f['depth.pybullet_tinyrenderer_fps'],
                                                           f['depth.pybullet_tinyrenderer_fps']),
             '>= 200', f['depth.car_2core_fps'] >= 200),
            ('full stack in the core (physics, lidar 5.5 Hz, depth 10 Hz) [x real time]',
             '%.1f' % f['full_stack.core_x_real_time'], '>= 10', f['full_stack.core_x_real_time'] >= 10),
            ('full stack through ROS, /scan and the 20 Hz cloud subscribed [x real time]',
             '%.1f' % f['full_stack.ros_cloud_x_real_time'], '>= 5', f['full_stack.ros_cloud_x_real_time'] >= 5),
        ]
    return rows


def render(f):
    m = f.get('machine', {})
    out = ['| figure | this run | target | met |', '|---|---|---|---|']
    for name, value, target, met in _rows(f):
        out.append('| %s | %s | %s | %s |' % (name, value, target, 'yes' if met else '**no**'))
    if m:
        out.append('')
        out.append('%d CPUs, load average %.1f at the end of the run (%s).' % (m.get('cpus', 0),
                                                                          m.get('load_average_1min', 0.0),
                                                                          m.get('platform', '')))
    return '\n'.join(out)


if __name__ == '__main__':
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with open(sys.argv[1]) as fh:
        print(render(json.load(fh)))
