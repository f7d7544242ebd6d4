"""arbotix_driver's configuration, kinematics and wheel finding (no ROS master)."""
import math
import os

import pytest
import yaml

from car.ros import arbotix
from conftest import DATA, ROOT


def seed_controllers():
    with open(os.path.join(ROOT, 'config', 'control.yaml')) as f:
        return yaml.safe_load(f)['controllers']


def test_seed_config_parses():
    (cfg,) = arbotix.parse_controllers(seed_controllers())
    assert (cfg.name, cfg.base_width, cfg.ticks_meter) == ('base_controller', 0.2, 2000.0)
    assert (cfg.base_frame_id, cfg.odom_frame_id, cfg.rate, cfg.accel_limit) == ('base_footprint', 'odom', 10.0, 1.0)
    assert cfg.gains == {'Kp': 12.0, 'Kd': 12.0, 'Ki': 0.0, 'Ko': 50.0}


@pytest.mark.parametrize('change, message', [
    (lambda c: c.pop('base_width'), '~controllers/base_controller/base_width is required'),
    (lambda c: c.pop('ticks_meter'), '~controllers/base_controller/ticks_meter is required'),
    (lambda c: c.update(type='follow_controller'),
     "~controllers/base_controller/type: unknown controller type 'follow_controller'"),
    (lambda c: c.update(base_width='wide'), "~controllers/base_controller/base_width must be a number, got 'wide'"),
    (lambda c: c.update(accel_limit=-1), '~controllers/base_controller/accel_limit must be >= 0'),
])
def test_bad_config_names_the_key(change, message):
    controllers = seed_controllers()
    change(controllers['base_controller'])
    with pytest.raises(arbotix.ConfigError, match=message.replace('(', r'\(').replace(')', r'\)')):
        arbotix.parse_controllers(controllers)


def test_no_controllers_at_all():
    with pytest.raises(arbotix.ConfigError, match='~controllers must be a map'):
        arbotix.parse_controllers(None)


def test_euler_circle_radius():
    (cfg,) = arbotix.parse_controllers(seed_controllers())
    cfg.accel_limit = 0.0
    sim = arbotix.DiffSim(cfg)
    sim.command(1.0, 1.0)
    pts = []
    for _ in range(63):
        sim.step(0.1)
        pts.append((sim.x, sim.y))
    # Euler steps of chord v dt turning w dt lie on a circle of radius v dt / (2 sin(w dt / 2))
    centre = (0.05, 0.1 / (2 * math.tan(0.05)))  # above the first chord's midpoint
    r = 0.1 / (2 * math.sin(0.05))
    assert all(math.dist(p, centre) == pytest.approx(r, abs=1e-9) for p in pts)


def test_accel_limit_ramps_each_wheel():
    (cfg,) = arbotix.parse_controllers(seed_controllers())
    sim = arbotix.DiffSim(cfg)
    sim.command(1.0, 0.0)
    steps = 0
    while sim.v < 1.0 - 1e-12:
        sim.step(0.1)
        steps += 1
    assert steps == 10  # 1 m/s at 1 m/s^2 in 0.1 s steps


def test_wheels_of_the_seed_car():
    from car import _core
    with open(os.path.join(DATA, 'car_camera_lidar04.urdf')) as f:
        model = _core.load_urdf_string(f.read(), 'car', False)
    wheels = {w.joint: (w.radius, w.side, d) for w, d in arbotix.find_wheels(model)}
    assert wheels == {'left2link': (0.0325, 1, 1), 'right2link': (0.0325, -1, 1)}
