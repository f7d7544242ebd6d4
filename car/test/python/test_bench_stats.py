"""bench/bench_physics.py's aggregation (best of N interleaved rounds, median) and parsers, and bench/table.py's
rendering of a record with and without medians. Values worked out by hand; nothing here times anything."""
import json
import os
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, os.path.join(ROOT, 'bench'))
import bench_physics  # noqa: E402
import table  # noqa: E402


def test_round_order_rotates_left_by_the_round():
    names = ['A', 'B', 'C']
    assert [bench_physics.round_order(names, r) for r in range(4)] == [
        ['A', 'B', 'C'], ['B', 'C', 'A'], ['C', 'A', 'B'], ['A', 'B', 'C']]


def test_interleaved_runs_each_measurement_once_per_round_in_rotated_order():
    calls = []

    def make(name, key):
        def f():
            calls.append(name)
            return {key: float(len(calls))}
        return f
    samples = bench_physics.interleaved([('A', make('A', 'a')), ('B', make('B', 'b')), ('C', make('C', 'c'))], 3)
    # rounds: A B C | B C A | C A B  -> call numbers: a = 1, 6, 8; b = 2, 4, 9; c = 3, 5, 7
    assert calls == ['A', 'B', 'C', 'B', 'C', 'A', 'C', 'A', 'B']
    assert samples == {'a': [1.0, 6.0, 8.0], 'b': [2.0, 4.0, 9.0], 'c': [3.0, 5.0, 7.0]}


def test_summary_is_the_largest_sample_and_the_median():
    # sorted 30, 40, 52 -> median 40; best (fastest) 52
    assert bench_physics.summary([52.0, 30.0, 40.0]) == (52.0, 40.0)
    # an even count: the mean of the middle two, (30 + 40) / 2 = 35
    assert bench_physics.summary([30.0, 52.0, 40.0, 10.0]) == (52.0, 35.0)


def test_record_keeps_the_stable_key_for_the_best_and_adds_median_and_samples():
    fig = {}
    bench_physics.record(fig, {'physics.car_core_cpp': [51864.0, 34344.0, 30084.0]})
    assert fig == {'physics.car_core_cpp': 51864.0, 'physics.car_core_cpp.median': 34344.0,
                   'physics.car_core_cpp.samples': [51864.0, 34344.0, 30084.0]}


def test_parse_core_reads_the_wall_and_cpu_rates():
    line = 'core: 47533 steps/s = 47.5x real time at dt 0.0010 s (30000 steps in 0.631 s; 49180 steps per CPU second)\n'
    assert bench_physics.parse_core(line) == (47533.0, 49180.0)
    # a bench_core from before the CPU figure: the wall rate alone
    assert bench_physics.parse_core('core: 47533 steps/s = 47.5x real time at dt 0.0010 s (30000 steps in 0.631 s)') \
        == (47533.0, None)


def test_parse_sensors_reads_rays_frames_and_real_time():
    out = ('threads 2\nphysics alone: 28.3x real time\n'
           'lidar: 28 scans of 100000 rays in 0.8654 s over physics -> 3.24 M rays/s\n'
           'depth: 100 frames 640x480 in 6.652 s over physics -> 15.0 frames/s = 4.6 M rays/s\n'
           'full stack (physics 1 kHz, lidar 5.5 Hz, depth 10 Hz): 1.5x real time\n')
    assert bench_physics.parse_sensors(out) == {'rays': pytest.approx(3.24e6), 'fps': 15.0, 'full': 1.5}


def test_parse_sensors_reads_the_depth_image_alone():
    out = ('depth: 100 frames 640x480 in 6.652 s over physics -> 15.0 frames/s = 4.6 M rays/s\n'
           'depth image alone: 100 frames 640x480 in 3.326 s over physics -> 30.1 frames/s\n')
    assert bench_physics.parse_sensors(out) == {'fps': 15.0, 'depth_alone_fps': 30.1}


def _physics_record(**extra):
    f = {'physics.car_core_cpp': 40000.0, 'physics.mujoco': 20000.0, 'physics.mujoco_sleep': 32000.0,
         'physics.pybullet_10it': 10000.0, 'physics.car_ros_node': 30000.0}
    f.update(extra)
    return f


def test_table_of_an_old_single_sample_record_has_no_median_column():
    text = table.render(_physics_record())
    # 40000 / max(20000, 32000) = 1.25; 40000 / 10000 = 4.00; 30000 / 40000 = 75 %
    assert '| 40000; 1.25x MuJoCo (best of sleeping on/off: 32000), 4.00x PyBullet at 10 it. (10000) |' in text
    assert '| 30000 = 75 % of the core | >= 90 % of the core | **no** |' in text
    assert 'median' not in text


def test_table_of_a_repeated_record_shows_best_and_median_and_says_how():
    f = _physics_record(**{'bench.repeat': 5, 'physics.car_core_cpp.median': 36000.0, 'physics.mujoco.median': 18000.0,
                           'physics.mujoco_sleep.median': 30000.0, 'physics.pybullet_10it.median': 9000.0,
                           'physics.car_ros_node.median': 27000.0})
    text = table.render(json.loads(json.dumps(f)))
    assert '| figure | this run: best of 5 | median of 5 | target | met (best) |' in text
    # medians: 36000 / 30000 = 1.20, 36000 / 9000 = 4.00, 27000 / 36000 = 75 %; met judged on the bests
    # (40000 >= 32000 and 40000 >= 4 x 10000)
    assert ('| 40000; 1.25x MuJoCo (best of sleeping on/off: 32000), 4.00x PyBullet at 10 it. (10000) '
            '| 36000; 1.20x MuJoCo (best of sleeping on/off: 30000), 4.00x PyBullet at 10 it. (9000) '
            '| >= MuJoCo; >= 4x PyBullet | yes |') in text
    assert '| 30000 = 75 % of the core | 27000 = 75 % of the core |' in text
    assert 'measured 5 times in interleaved rounds' in text


def test_table_has_the_node_alone_row_when_the_record_has_it():
    # 37000 / 40000 = 92.5 % -> "92 %" (%.0f rounds half to even), met; a record without the key has no such row
    text = table.render(_physics_record(**{'physics.car_ros_node_alone': 37000.0}))
    assert '/odom subscribed [steps/s] | 37000 = 92 % of the core | >= 90 % of the core | yes |' in text
    assert 'node alone' not in table.render(_physics_record())


def test_a_measurement_with_fewer_rounds_runs_only_in_the_first_ones():
    calls = []

    def make(name):
        def f():
            calls.append(name)
            return {name: float(len(calls))}
        return f
    samples = bench_physics.interleaved([('A', make('A')), ('B', make('B'), 1)], 3)
    # round 1: A B; round 2: (B skipped) A; round 3: A (B skipped)
    assert calls == ['A', 'B', 'A', 'A']
    assert samples == {'A': [1.0, 3.0, 4.0], 'B': [2.0]}


def test_table_says_when_the_many_robots_search_ran_in_fewer_rounds():
    f = _physics_record(**{'bench.repeat': 5, 'bench.many_repeat': 2})
    for k in list(f):
        if not k.startswith('bench.'):
            f[k + '.median'] = f[k]
    sensors = {'many.cars_at_1x_real_time': 64, 'lidar.car_1core_rays_per_s': 6.8e6,
               'lidar.pybullet_1thread_rays_per_s': 0.2e6, 'depth.car_2core_fps': 50.0,
               'depth.pybullet_tinyrenderer_fps': 12.5, 'full_stack.core_x_real_time': 4.0,
               'full_stack.ros_cloud_x_real_time': 1.3}
    for k, v in sensors.items():
        f[k] = f[k + '.median'] = v
    text = table.render(f)
    # 6.8 M / 0.2 M = 34.00x; 50 / 12.5 = 4.0x
    assert '| 6.8 M; 34.00x PyBullet rayTestBatch (0.2 M) |' in text
    assert '| 50; 4.0x PyBullet TinyRenderer (12.5) |' in text
    assert 'The many-robots search (a bisection of about 35 s) ran in 2 of the rounds.' in text


def test_table_compares_the_core_with_the_strong_mujoco_model_in_both_worlds():
    # a record with the strong peer: box_house 40000 / 50000 = 0.80x (old model: max(20000, 32000)), bare plane
    # 60000 / 48000 = 1.25x, met
    f = _physics_record(**{'physics.mujoco_strong': 50000.0, 'physics.car_core_cpp_plane': 60000.0,
                           'physics.mujoco_strong_plane': 48000.0, 'physics.mujoco_plane': 30000.0})
    text = table.render(f)
    assert ('| 40000; 0.80x MuJoCo (strong model: 50000; old model 32000), 4.00x PyBullet at 10 it. (10000) '
            '| >= MuJoCo; >= 4x PyBullet | **no** |') in text
    assert ('| core physics, the same car on a bare ground plane [steps/s] '
            '| 60000; 1.25x MuJoCo (strong model: 48000; old model 30000) | >= MuJoCo | yes |') in text
