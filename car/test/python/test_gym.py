"""car.gym: the Gymnasium environment over the core (box_house, the tutorial's car, a goal).

The car starts at the origin facing +x; reset() steps 0.2 s with no command (two control periods, so the first
observation has a lidar scan). A 0.5 m/s command ramps at wheelAcceleration 1.8 m/s^2 over upstream's 0.011 s
per 0.01 s update (1.98 m/s^2, docs/COMPAT-plugins.md) and loses v^2 / 2a = 0.0631 m against v t. The default goal
is (2, 0) with a 0.3 m tolerance.
"""
import hashlib
import os
import subprocess
import sys
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
    # x(t) = 0.5 (t - 0.2) - 0.0631 >= 2 - 0.3 from t = 3.73 s: first at a 0.1 s control tick t = 3.8 s
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


def vector_trace(n=8, steps=200):
    """n envs from seeds 20.., stepped with seeded random actions; every step's obs, rewards, ends (bytes)."""
    v = cg.DriveVectorEnv(n)
    obs, _ = v.reset(seed=20)
    # forward 0.2-0.5 m/s, turning -1.3..1.3 rad/s about a bias per env: goals, walls and resets within 20 s
    rng = np.random.default_rng(7)
    acts = np.stack([rng.uniform(0.2, 0.5, (steps, n)),
                     rng.uniform(-0.8, 0.8, (steps, n)) + np.linspace(-0.5, 0.5, n)], axis=-1).astype(np.float32)
    out = [obs.tobytes()]
    for k in range(steps):
        obs, rew, term, trunc, _ = v.step(acts[k])
        out += [obs.tobytes(), rew.tobytes(), term.tobytes(), trunc.tobytes()]
    return out, acts


# The vector env steps its 8 worlds on the pool (docs/BATCH.md): every step's observations, rewards and ends equal
# those of 8 separate envs (seeds 20..27) stepped one after the other with the same random actions over 200 steps
# (20 s), with gymnasium's next-step autoreset done by hand for the separate envs (reset, reward 0, no end).
def test_vector_env_of_eight_equals_separate_envs_every_step():
    n, steps = 8, 200
    got, acts = vector_trace(n, steps)
    singles = [cg.DriveEnv() for _ in range(n)]
    want = [np.stack([e.reset(seed=20 + i)[0] for i, e in enumerate(singles)]).tobytes()]
    done = np.zeros(n, bool)
    for k in range(steps):
        outs = [e.reset() + (0.0, False, False, None) if done[i] else e.step(acts[k][i])
                for i, e in enumerate(singles)]
        rew = np.array([o[-4] if done[i] else o[1] for i, o in enumerate(outs)])
        term = np.array([False if done[i] else o[2] for i, o in enumerate(outs)])
        trunc = np.array([False if done[i] else o[3] for i, o in enumerate(outs)])
        want += [np.stack([o[0] for o in outs]).tobytes(), rew.tobytes(), term.tobytes(), trunc.tobytes()]
        done = term | trunc
    # the run has ends and so autoresets in it, not only free driving: goals (+10) and collisions (-1)
    assert sum(np.frombuffer(got[4 * k + 3], bool).sum() for k in range(steps)) >= 3
    rewards = np.concatenate([np.frombuffer(got[4 * k + 2]) for k in range(steps)])
    assert (rewards > 5).any() and (rewards < -0.5).any()
    for k, (a, b) in enumerate(zip(got, want)):
        assert a == b, 'reset observations differ' if k == 0 else 'step %d: %s differ' % (
            (k - 1) // 4, ['observations', 'rewards', 'terminated', 'truncated'][(k - 1) % 4])
    assert len(got) == len(want)


# The same run on 1 and 3 pool threads (OMP_NUM_THREADS, in a new process) gives the same bytes as here.
def test_vector_env_does_not_depend_on_the_thread_count():
    here = hashlib.sha256(b''.join(vector_trace(8, 60)[0])).hexdigest()
    code = ('import hashlib, sys; sys.path[:0] = %r; import test_gym as t; '
            'print(hashlib.sha256(b"".join(t.vector_trace(8, 60)[0])).hexdigest())' % [os.path.dirname(__file__)])
    for threads in ('1', '3'):
        env = dict(os.environ, OMP_NUM_THREADS=threads)
        r = subprocess.run([sys.executable, '-c', code], env=env, capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stderr
        assert r.stdout.split()[-1] == here, '%s threads' % threads


def test_step_worlds_refuses_a_world_twice():
    from car import _core
    a, b = _core.World(cg.DEFAULT_WORLD), _core.World(cg.DEFAULT_WORLD)
    with pytest.raises(ValueError, match=r'^step_worlds: worlds\[2\] is worlds\[0\]; a world may appear once$'):
        _core.step_worlds([a, b, a], 10)
    assert a.time == 0.0 and b.time == 0.0
