#!/usr/bin/env python3
"""What a model scripted by set_model_state at every step costs (docs/COMPAT.md set_model_state): box_house with the
seed car, its lidar (5.5 Hz) and Kinect (20 Hz, every part) on, stepped 1 ms at a time from Python, while a model
is moved 1 mm along x before every step:

  none     nothing moved (the base);
  dynamic  unit_box (a dynamic model: its body is placed);
  static   box_house (a static model, four walls: its collisions and its bodies in the ray scene are placed).

Each round times every case once, in an order rotated by one each round, from a fresh world after 500 settling
steps. Printed: per case the median and best of the rounds' microseconds per step, and each case's median extra
cost over `none`. A static model's move costs about what a dynamic one's does when the ray scene is moved, not
rebuilt.

usage: bench_teleport.py [--steps 2000] [--rounds 5]   (with the workspace sourced)
"""
import argparse
import os
import statistics
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
URDF = os.path.join(ROOT, 'test', 'data', 'car_camera_lidar04.urdf')


def world():
    from car import _core
    w = _core.World(WORLD)
    with open(URDF) as f:
        w.spawn_urdf(f.read(), 'mycar')
    for s in w.sensors():
        w.set_sensor_active(s['robot'], s['plugin'], True)
    w.step(500)
    return w


def run(case, steps):
    w = world()
    model = {'dynamic': 'unit_box', 'static': 'box_house'}.get(case)
    start = w.model_state(model)['position'] if model else None
    t = time.perf_counter()
    for k in range(steps):
        if model:
            w.set_model_state(model, [start[0] + 0.001 * (k % 100), start[1], start[2]])
        w.step(1)
        w.take_sensor_outputs()
    return (time.perf_counter() - t) / steps * 1e6


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--steps', type=int, default=2000)
    ap.add_argument('--rounds', type=int, default=5)
    a = ap.parse_args()
    cases = ['none', 'dynamic', 'static']
    samples = {c: [] for c in cases}
    for r in range(a.rounds):
        for c in cases[r % 3:] + cases[:r % 3]:
            samples[c].append(run(c, a.steps))
    base = statistics.median(samples['none'])
    for c in cases:
        med = statistics.median(samples[c])
        print('%-8s %7.1f us/step median, %7.1f best; extra over none %+6.1f us' % (c, med, min(samples[c]),
                                                                                     med - base))


if __name__ == '__main__':
    main()
