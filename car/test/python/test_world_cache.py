"""car.world_cache: a warm worker parses a world and a robot once and builds each run's World from the const
descriptions; a run's results must not depend on what the worker ran before.

Scenario A: the seed car (seeded lidar noise, stddev 0.01 m) wandering in box_house with the lidar controller
(examples/wander.py), so the scan feeds back into the commands. B1: the same world and model, another seed and pose
(the same cached objects, other mutable state). B2: the empty world. A after B1 and B2 must give A's first result
byte for byte, and the same bytes as A in a new process (a cold worker).
"""
import json
import os
import shutil
import subprocess
import sys

from conftest import DATA, ROOT
from car import _core, batch_run, scenario, world_cache

WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
URDF = os.path.join(DATA, 'car_camera_lidar04.urdf')
WANDER = os.path.join(ROOT, 'examples', 'wander.py') + ':wander'


def run_of(world, seed, x, y, yaw, controller=True):
    drive = {'controller': WANDER, 'rate': 10} if controller else {'commands': [{'t': 0, 'v': 0.5, 'w': 0.3}]}
    raw = {'name': 'cache', 'world': world, 'duration': 1.5, 'seed': seed, 'record_rate': 20,
           'robots': [{'name': 'mycar', 'model': URDF, 'pose': {'x': x, 'y': y, 'yaw': yaw}, 'drive': drive}]}
    if world is None:
        del raw['world']
    return scenario.expand(raw, os.path.join(DATA, 'cache.yaml'))[0]


def result_bytes(res):
    """A run's result as bytes, wall time left out (JSON writes floats by repr, which round-trips exactly)."""
    assert res['status'] == 'ok', res['error']
    return json.dumps({k: v for k, v in res.items() if k != 'wall_time'}, sort_keys=True).encode()


def test_a_run_is_bit_identical_after_other_runs_in_the_same_worker():
    a = run_of(WORLD, 1, 0.0, 0.0, 0.0)
    first = result_bytes(batch_run.run(a))
    batch_run.run(run_of(WORLD, 7, -2.0, 1.0, 2.0))
    batch_run.run(run_of(None, 3, 0.5, 0.0, 1.0, controller=False))
    again = result_bytes(batch_run.run(a))
    assert first == again
    # a cold worker: A alone in a new process
    code = ('import json, sys; from car import batch_run; from test_world_cache import result_bytes; '
            'sys.stdout.buffer.write(result_bytes(batch_run.run(json.load(sys.stdin))))')
    cold = subprocess.run([sys.executable, '-c', code], input=json.dumps(a), capture_output=True, text=True,
                          cwd=os.path.dirname(os.path.abspath(__file__)), check=True).stdout.encode()
    assert cold == first
    # the run saw the noisy scan and moved: the comparison is not between two empty results
    row = json.loads(first)['robots'][0]
    assert row['min_obstacle'] == row['min_obstacle'] and row['distance'] > 0.1


def test_world_from_the_cached_description_equals_world_from_the_file():
    def drive(world, spawn):
        spawn(world)
        for s in world.sensors():
            if s['kind'] == 'laser':
                world.set_sensor_active(s['robot'], s['plugin'], True)
        world.set_cmd_vel('mycar', 0.5, 0.4)
        world.step(700)
        scans = [s['ranges'].tobytes() for s in world.take_sensor_outputs()['scans']]
        return json.dumps(world.model_state('mycar')), scans

    with open(URDF) as f:
        text = f.read()
    fresh = drive(_core.World(WORLD, seed=5), lambda w: w.spawn_urdf(text, 'mycar', 0.3, -0.2, 0, 0, 0, 0.5))
    desc = world_cache.world_description(WORLD)[0]
    model = world_cache.robot_model(text, 'mycar')
    cached = drive(_core.World(desc, seed=5), lambda w: w.spawn_model(model, 'mycar', 0.3, -0.2, 0, 0, 0, 0.5))
    assert len(fresh[1]) >= 3
    assert fresh == cached


def test_a_world_is_parsed_once_per_content(tmp_path):
    path = str(tmp_path / 'house.world')
    shutil.copy(WORLD, path)
    desc, ground = world_cache.world_description(path)
    assert world_cache.world_description(path)[0] is desc
    assert ground == {'ground_plane'} and desc.step_size == 0.001
    with open(WORLD) as f:
        text = f.read()
    # another version of the file (a 2 ms step) is parsed again
    with open(path, 'w') as f:
        f.write(text.replace('<max_step_size>0.001</max_step_size>', '<max_step_size>0.002</max_step_size>', 1))
    desc2, _ = world_cache.world_description(path)
    assert desc2 is not desc and desc2.step_size == 0.002


def test_the_empty_world_has_gazebos_ground_plane():
    desc, ground = world_cache.world_description(None)
    assert ground == {'ground_plane'}
    assert [m['name'] for m in desc.to_dict()['models']] == ['ground_plane']
