"""car.gym: the Gymnasium environment over the core (box_house, the tutorial's car, a goal).

The car starts at the origin facing +x; reset() steps 0.2 s with no command (two control periods, so the first
observation has a lidar scan). A 0.5 m/s command ramps at wheelAcceleration 1.8 m/s^2 and loses 0.0694 m against
v t. The default goal is (2, 0) with a 0.3 m tolerance.
"""
import warnings

import numpy as np
import pytest

import gymnasium

import car.gym as cg  # (registers car/Drive-v0)


@pytest.fixture(scope='module')
def env():
    return cg.DriveEnv()


def drive(env, action, steps, seed=0):
    obs, _ = env.reset(seed=seed)
    out = [obs]
    for _ in range(steps):
        obs, r, term, trunc, info = env.step(np.array(action, np.float32))
        out.append(obs)
        if term or trunc:
            break
    return np.stack(out), (r, term, trunc, info)


def test_env_checker_passes():
    from gymnasium.utils.env_checker import check_env
    with warnings.catch_warnings():
        # every warning of the checker fails the test (it only warns about observations outside the space, NaN
        # rewards or non-bool flags), except the one about the unnormalised (v, w) action space: SI units, on purpose
        warnings.simplefilter('error')
        warnings.filterwarnings('ignore', message='.*we recommend using a symmetric and normalized space')
        # made through the registry, so the checker has the env's spec (and tests its render modes)
        check_env(gymnasium.make('car/Drive-v0').unwrapped)


def test_registered_id_makes_the_env():
    e = gymnasium.make('car/Drive-v0')
    assert isinstance(e.unwrapped, cg.DriveEnv)


def test_first_observation_has_the_goal_in_the_robot_frame(env):
    obs, info = env.reset(seed=0)
    # goal (2, 0) seen from (0, 0) facing +x
    assert obs[-4] == pytest.approx(2.0, abs=0.005)
    assert obs[-3] == pytest.approx(0.0, abs=0.005)
    assert info['distance'] == pytest.approx(2.0, abs=0.005)


def test_scan_is_in_the_observation(env):
    obs, _ = env.reset(seed=0)
    scan = obs[:env.n_beams]
    assert env.n_beams == 360
    # box_house has walls all round: some beams hit something closer than range_max (30 m)
    assert scan.min() < 5.0 and scan.max() <= env.range_max


def test_driving_at_the_goal_terminates_when_within_tolerance(env):
    # x(t) = 0.5 (t - 0.2) - 0.0694 >= 2 - 0.3 first at a 0.1 s control tick t = 3.8 s
    _, (r, term, trunc, info) = drive(env, (0.5, 0.0), 100)
    assert term and not trunc
    assert info['time'] == pytest.approx(3.8, abs=1e-9)
    assert info['distance'] <= 0.3
    assert r > 10.0  # the goal reward on the last step


def test_same_seed_same_actions_bit_identical(env):
    a, _ = drive(env, (0.4, 0.3), 20, seed=5)
    b, _ = drive(env, (0.4, 0.3), 20, seed=5)
    assert np.array_equal(a, b)


def test_collision_terminates_with_the_penalty():
    # goal out of reach behind the east wall; the car drives into the wall
    e = cg.DriveEnv(goal=(50.0, 0.0), max_seconds=30.0)
    _, (r, term, trunc, info) = drive(e, (0.5, 0.0), 400)
    assert term and info['collisions'] >= 1
    assert r < -0.5
    # box_house's Wall_2 is centred at x = 4.449 and 0.15 m thick: its inner face is x = 4.374; the base
    # cylinder's radius is 0.1 m, so the first contact comes with the base at x = 4.274
    assert info['x'] == pytest.approx(4.274, abs=0.01)


def test_vector_env_equals_separate_envs():
    n = 3
    v = cg.DriveVectorEnv(n)
    obs_v, _ = v.reset(seed=10)
    singles = [cg.DriveEnv() for _ in range(n)]
    obs_s = [e.reset(seed=10 + i)[0] for i, e in enumerate(singles)]
    assert np.array_equal(obs_v, np.stack(obs_s))
    actions = np.array([[0.5, 0.0], [0.3, 0.5], [0.0, -1.0]], np.float32)
    for _ in range(10):
        obs_v, rew_v, _, _, _ = v.step(actions)
        outs = [e.step(a) for e, a in zip(singles, actions)]
    assert np.array_equal(obs_v, np.stack([o[0] for o in outs]))
    assert np.array_equal(rew_v, np.array([o[1] for o in outs]))
