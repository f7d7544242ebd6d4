"""car batch: scenario files, one run's numbers, determinism, failures, resume, Parquet, Ray and the plots.

Fixtures in test/data/batch. The seed car's diff drive ramps the wheel speed at wheelAcceleration = 1.8 m/s^2
over upstream's 0.011 s per 0.01 s update (a = 1.98 m/s^2, docs/COMPAT-plugins.md), so a 0.5 m/s command from rest
loses v^2 / (2 a) = 0.25 / 3.96 = 0.0631 m against v t.
"""
import json
import math
import os

import pytest

from conftest import DATA, ROOT
from car import batch, batch_run, scenario

BATCH = os.path.join(DATA, 'batch')


def runs_of(name):
    return scenario.load(os.path.join(BATCH, name))


def same(a, b):
    """Bit-for-bit equal results (JSON writes floats by repr, which round-trips exactly; NaN == NaN here)."""
    return json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)


def by_overrides(results):
    return {res['overrides']: res for res in results}


@pytest.fixture(scope='module')
def straight(tmp_path_factory):
    out = str(tmp_path_factory.mktemp('straight'))
    return out, batch.run_all(runs_of('straight.yaml'), out, serial=True, progress=False)


def test_grid_sweep_is_the_product_of_its_lists():
    runs = runs_of('straight.yaml')
    assert len(runs) == 4
    assert len({r['id'] for r in runs}) == 4
    assert [r['scenario']['robots'][0]['pose']['y'] for r in runs] == [0.0, 0.0, 1.0, 1.0]
    assert [r['scenario']['robots'][0]['drive']['commands'][1]['w'] for r in runs] == [0.0, 0.5, 0.0, 0.5]


def test_run_ids_are_stable_hashes_of_the_overrides():
    assert scenario.run_id({'a': 1, 'b': 2}) == scenario.run_id({'b': 2, 'a': 1})
    assert runs_of('straight.yaml')[0]['id'] == runs_of('straight.yaml')[0]['id']


def test_unknown_field_names_the_file_and_the_field():
    with pytest.raises(scenario.ScenarioError) as e:
        runs_of('unknown_field.yaml')
    assert 'unknown_field.yaml' in str(e.value) and 'robots.0.speed' in str(e.value)
    assert 'unknown field' in str(e.value)


def test_missing_world_file_is_named():
    with pytest.raises(scenario.ScenarioError) as e:
        runs_of('bad_world.yaml')
    assert e.value.field == 'world' and 'no_such.world' in e.value.reason


def test_linspace_needs_start_stop_count():
    raw = {'robots': [{'model': os.path.join(DATA, 'car_camera_lidar04.urdf')}],
           'sweep': {'grid': {'seed': {'linspace': [0, 1]}}}}
    with pytest.raises(scenario.ScenarioError) as e:
        scenario.expand(raw, 'x.yaml')
    assert 'linspace takes [start, stop, count]' in str(e.value)


def test_straight_run_ends_at_v_t_less_the_ramp(straight):
    res = by_overrides(straight[1])[json.dumps({'robots.0.drive.commands.1.w': 0.0, 'robots.0.pose.y': 0.0},
                                               sort_keys=True)]
    assert res['status'] == 'ok', res['error']
    row = res['robots'][0]
    # 0.5 m/s for 2 s less the 0.0631 m ramp
    assert row['x'] == pytest.approx(0.9369, abs=0.01)
    assert row['y'] == pytest.approx(0.0, abs=0.005)
    assert row['distance'] == pytest.approx(0.9369, abs=0.01)
    assert row['collisions'] == 0


def test_start_pose_is_swept(straight):
    res = by_overrides(straight[1])[json.dumps({'robots.0.drive.commands.1.w': 0.0, 'robots.0.pose.y': 1.0},
                                               sort_keys=True)]
    assert res['robots'][0]['y'] == pytest.approx(1.0, abs=0.005)


def test_turn_command_at_its_time(straight):
    res = by_overrides(straight[1])[json.dumps({'robots.0.drive.commands.1.w': 0.5, 'robots.0.pose.y': 0.0},
                                               sort_keys=True)]
    # w = 0.5 rad/s from t = 1.5 s: each wheel's 0.025 m/s change takes one ramp step (0.0198 m/s), then, within
    # 0.01 m/s of its target, the rest at once: 0.02 s, so yaw = 0.5 (0.5 - 0.02 / 2) = 0.245 rad
    assert res['robots'][0]['yaw'] == pytest.approx(0.245, abs=0.01)


def test_trajectory_is_sampled_at_the_record_rate(straight):
    traj = straight[1][0]['robots'][0]['trajectory']
    # 10 Hz over 2 s, both ends included
    assert [round(p[0], 6) for p in traj] == [round(0.1 * i, 6) for i in range(21)]


def test_no_lidar_hit_on_bare_ground_is_nan(straight):
    assert math.isnan(straight[1][0]['robots'][0]['min_obstacle'])


def test_same_seed_gives_bit_identical_results(straight, tmp_path):
    again = batch.run_all(runs_of('straight.yaml'), str(tmp_path), serial=True, progress=False)
    for a, b in zip(straight[1], again):
        assert same(a['robots'], b['robots'])


def test_controller_that_raises_fails_its_run_and_the_others_go_on(tmp_path):
    results = batch.run_all(runs_of('controllers.yaml'), str(tmp_path), serial=True, progress=False)
    assert [r['status'] for r in results] == ['failed', 'ok']
    assert 'RuntimeError: controller exploded at t=0.00' in results[0]['error']
    # forward at 0.5 m/s for 1 s less the ramp
    assert results[1]['robots'][0]['x'] == pytest.approx(0.5 - 0.0631, abs=0.01)


def test_resume_runs_only_what_is_missing(straight, monkeypatch):
    def fail(_):
        raise AssertionError('a finished run ran again')
    monkeypatch.setattr(batch_run, 'run', fail)
    again = batch.run_all(runs_of('straight.yaml'), straight[0], serial=True, progress=False)
    assert [r['id'] for r in again] == [r['id'] for r in straight[1]]


def test_parquet_has_a_row_per_run_and_the_swept_columns(straight):
    import pyarrow.parquet as pq
    runs_path, traj_path = batch.write_parquet(straight[1], straight[0])
    runs = pq.read_table(runs_path).to_pydict()
    assert len(runs['run']) == 4
    assert runs['sweep.robots.0.pose.y'] == [0.0, 0.0, 1.0, 1.0]
    assert len(pq.read_table(traj_path).to_pydict()['t']) == 4 * 21


def test_ray_workers_give_the_serial_results_bit_for_bit(straight, tmp_path):
    results = batch.run_all(runs_of('straight.yaml'), str(tmp_path), workers=2, progress=False)
    for a, b in zip(straight[1], results):
        assert a['status'] == b['status'] == 'ok'
        assert same(a['robots'], b['robots'])


def test_cli_exit_codes(tmp_path, capsys):
    assert batch.main([os.path.join(BATCH, 'unknown_field.yaml')]) == 2
    assert 'robots.0.speed' in capsys.readouterr().err
    assert batch.main([os.path.join(BATCH, 'controllers.yaml'), '--serial', '--quiet', '-o', str(tmp_path)]) == 1


def test_top_view_draws_every_run(straight):
    from car import world_plot
    runs_path, _ = batch.write_parquet(straight[1], straight[0])
    out = os.path.join(straight[0], 'runs.png')
    n, size = world_plot.plot_runs(os.path.join(ROOT, 'worlds', 'box_house.world'), runs_path, out)
    assert n == 4
    with open(out, 'rb') as f:
        assert f.read(8) == b'\x89PNG\r\n\x1a\n'


def test_sweep_plot_names_unknown_parameters(straight):
    from car import world_plot
    runs_path, _ = batch.write_parquet(straight[1], straight[0])
    with pytest.raises(ValueError) as e:
        world_plot.plot_sweep(runs_path, 'robots.0.pose.x', 'distance', os.path.join(straight[0], 's.png'))
    assert 'robots.0.pose.y' in str(e.value)
    assert world_plot.plot_sweep(runs_path, 'robots.0.pose.y', 'distance', os.path.join(straight[0], 's.png')) == 4
