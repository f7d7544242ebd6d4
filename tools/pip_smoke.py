"""The pip install's smoke test (tools/test_pip.sh; docs/INSTALL.md "Python only"), run by a venv's python that
has car's wheel installed and no ROS: `import car` and every module that needs no ROS import without rospy, the
package and its data come from the venv, car.World steps the tutorial's car in box_house, the Gymnasium env steps,
and the console scripts `world_tool` and `car batch` (on Ray) run. Exit 0 when all hold; an AssertionError names
the first that does not."""
import importlib
import importlib.util
import os
import subprocess
import sys
import tempfile

# the modules a pip install offers: everything in car/ but car.ros, the ROS nodes' (not in the wheel)
PYTHON_ONLY = ('car', 'car.paths', 'car.cli', 'car.world_cli', 'car.world_tools', 'car.world_map', 'car.world_plot',
               'car.world_geometry', 'car.world_cache', 'car.materials', 'car.inertia', 'car.xacro14',
               'car.xacro_tool', 'car.model_check', 'car.scenario', 'car.batch', 'car.batch_run', 'car.gym')


def run(*cmd, cwd=None):
    p = subprocess.run(list(cmd), capture_output=True, text=True, timeout=600, cwd=cwd)
    assert p.returncode == 0, '%s exited %d:\n%s\n%s' % (' '.join(cmd), p.returncode, p.stdout[-3000:],
                                                            p.stderr[-3000:])
    return p.stdout


def main():
    venv = sys.prefix
    assert venv != sys.base_prefix, 'run me with the venv that has car installed'
    for name in PYTHON_ONLY:
        importlib.import_module(name)
    ros = sorted(m for m in sys.modules if m.split('.')[0] in ('rospy', 'roslib', 'rospkg', 'rosgraph', 'roslaunch'))
    assert not ros, 'importing car pulled in ROS: %s' % ros
    # the ROS nodes' modules are the catkin build's only (pyproject.toml's wheel.exclude)
    assert importlib.util.find_spec('car.ros') is None, 'the wheel ships car.ros'

    import car
    from car.paths import package_dir
    assert car.__file__.startswith(venv), 'car imported from %s, not the venv %s' % (car.__file__, venv)
    data = package_dir()
    assert data.startswith(venv) and os.path.isfile(os.path.join(data, 'worlds', 'box_house.world')), data

    # car.World: the tutorial's car in box_house, driven in a circle
    from car import xacro_tool
    w = car.World(os.path.join(data, 'worlds', 'box_house.world'), seed=0)
    w.spawn_urdf(xacro_tool.expand(os.path.join(data, 'urdf', 'car_camera_lidar04.xacro')), 'mycar', x=0, y=0, yaw=0)
    w.set_cmd_vel('mycar', 0.5, 0.5)
    w.step(2000)
    pos = w.model_state('mycar')['position']
    assert abs(w.time - 2.0) < 1e-9 and 0.3 < (pos[0] ** 2 + pos[1] ** 2) ** 0.5 < 1.5, (w.time, pos)
    # the core found its own data (Gazebo's colours, the built-in models) in the wheel
    assert car.load_world_file(os.path.join(data, 'worlds', 'box_house.world'))['models'], 'no models in box_house'

    # the Gymnasium env through gymnasium.make, its module named in the id
    import gymnasium
    env = gymnasium.make('car.gym:car/Drive-v0', max_seconds=2.0)
    obs, _ = env.reset(seed=1)
    for _ in range(5):
        obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
    assert env.observation_space.contains(obs), 'observation outside its space'
    env.close()

    # the console scripts
    bindir = os.path.join(venv, 'bin')
    with tempfile.TemporaryDirectory() as tmp:
        out = run(os.path.join(bindir, 'world_tool'), 'check', os.path.join(data, 'worlds', 'box_house.world'))
        run(os.path.join(bindir, 'world_tool'), 'map', os.path.join(data, 'worlds', 'box_house.world'),
            '-o', os.path.join(tmp, 'house'))
        assert os.path.isfile(os.path.join(tmp, 'house.pgm')), 'world_tool map wrote no house.pgm'
        with open(os.path.join(tmp, 'two.yaml'), 'w') as f:
            f.write('name: two\nworld: $(find car)/worlds/box_house.world\nduration: 1.0\nseed: 1\n'
                    'robots:\n  - name: mycar\n    model: $(find car)/urdf/car_camera_lidar04.xacro\n'
                    '    drive:\n      commands:\n        - {t: 0, v: 0.5, w: 0.0}\n'
                    'sweep:\n  list:\n    - {seed: 1}\n    - {seed: 2}\n')
        out = run(os.path.join(bindir, 'car'), 'batch', 'two.yaml', '-o', 'out', '--workers', '2', '--quiet', cwd=tmp)
        assert os.path.isfile(os.path.join(tmp, 'out', 'runs.parquet')), 'car batch wrote no runs.parquet:\n' + out
        import pyarrow.parquet as pq
        runs = pq.read_table(os.path.join(tmp, 'out', 'runs.parquet')).to_pydict()
        assert runs['status'] == ['ok', 'ok'], runs['status']
    print('pip smoke: ok (car %s from %s)' % (importlib.metadata.version('car'), os.path.dirname(car.__file__)))


if __name__ == '__main__':
    import importlib.metadata
    main()
