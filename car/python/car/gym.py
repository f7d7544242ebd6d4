"""Gymnasium environments over the core (no ROS): drive the tutorial's car to a goal in box_house.

    import gymnasium as gym, car.gym
    env = gym.make('car/Drive-v0')                       # or car.gym.DriveEnv(goal=(2, 0), ...)
    venv = car.gym.DriveVectorEnv(8)                      # 8 worlds stepped by one C++ call per step

Observation (float32 Box): the lidar's ranges [m] (infinite ones as range_max), then the goal in the robot's frame
(dx, dy [m]), the robot's measured forward speed v [m/s] and yaw rate w [rad/s] (world-frame ground truth, as
odometry without drift). The lidar (5.5 Hz in the seed) holds its latest scan between scans.
Action (float32 Box): (v [m/s], w [rad/s]) for the diff drive, within (±max_v, ±max_w).
Reward per step: progress toward the goal [m] (previous distance − new distance), −collision_penalty on a new
contact with anything but the ground, −time_penalty; +goal_reward when the base is within goal_tolerance.
Terminated at the goal or (terminate_on_collision) at a collision; truncated after max_seconds of sim time.
reset(seed=s) builds the world with noise seed s: the same seed and actions give bit-identical observations.
"""
from __future__ import annotations

import math
import os

import gymnasium
import numpy as np
from gymnasium import spaces

from car import world_cache
from car.paths import package_dir

ROOT = package_dir()
DEFAULT_WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
DEFAULT_MODEL = os.path.join(ROOT, 'urdf', 'car_camera_lidar04.xacro')
_model_cache = {}


def _model_text(path):
    if path not in _model_cache:
        if path.endswith('.xacro'):
            from car import xacro_tool
            _model_cache[path] = xacro_tool.expand(path)
        else:
            with open(path, encoding='utf-8') as f:
                _model_cache[path] = f.read()
    return _model_cache[path]


class DriveEnv(gymnasium.Env):
    """One world, one car, one goal (see the module's docstring)."""

    metadata = {'render_modes': []}
    ROBOT = 'car'
    GOAL_LIMIT = 1000.0  # [m]
    SPEED_LIMIT = 100.0  # [m/s], [rad/s]

    def __init__(self, world_file=DEFAULT_WORLD, model_file=DEFAULT_MODEL, start=(0.0, 0.0, 0.0), goal=(2.0, 0.0),
                 goal_tolerance=0.3, control_rate=10.0, max_seconds=30.0, max_v=0.5, max_w=1.5,
                 collision_penalty=1.0, time_penalty=0.001, goal_reward=10.0, terminate_on_collision=True,
                 random_start=0.0):
        from car import _core
        self._core = _core
        self.world_file, self.model_file = world_file, model_file
        self.start, self.goal = tuple(float(v) for v in start), np.array(goal, dtype=float)
        self.goal_tolerance, self.max_seconds = goal_tolerance, max_seconds
        self.collision_penalty, self.time_penalty, self.goal_reward = collision_penalty, time_penalty, goal_reward
        self.terminate_on_collision, self.random_start = terminate_on_collision, random_start
        self._ground = self._ground_models()
        self.world = self._build(0, self.start)
        self.dt = self.world.dt
        self.steps_per_action = max(1, int(round(1.0 / (control_rate * self.dt))))
        lidar = next((s for s in self.world.sensors() if s['kind'] == 'laser' and s['robot'] == self.ROBOT), None)
        if lidar is None:
            raise ValueError('%s: the robot has no lidar (libgazebo_ros_laser.so)' % model_file)
        self._lidar = lidar['plugin']
        self.world.set_sensor_active(self.ROBOT, self._lidar, True)
        self.world.step(int(round(1.0 / (lidar['rate'] * self.dt))) + 1)
        scan = self._latest_scan()
        self.n_beams, self.range_max = len(scan['ranges']), float(scan['range_max'])
        # goal offsets within ±GOAL_LIMIT m, speeds within ±SPEED_LIMIT
        high = np.concatenate([np.full(self.n_beams, self.range_max), [self.GOAL_LIMIT] * 2,
                               [self.SPEED_LIMIT] * 2]).astype(np.float32)
        low = np.concatenate([np.zeros(self.n_beams), -high[self.n_beams:]]).astype(np.float32)
        self.observation_space = spaces.Box(low, high, dtype=np.float32)
        self.action_space = spaces.Box(np.array([-max_v, -max_w], np.float32), np.array([max_v, max_w], np.float32),
                                       dtype=np.float32)
        self._scan = None
        self._touching = set()
        self._seed = None

    # ---- building blocks (also used by the vector env) ----
    def _ground_models(self):
        return set(world_cache.world_description(self.world_file)[1])

    def _build(self, seed, pose):
        # a reset builds a new World from the world and robot parsed once per process (car.world_cache)
        w = self._core.World(world_cache.world_description(self.world_file)[0], seed=seed)
        w.spawn_model(world_cache.robot_model(_model_text(self.model_file), self.ROBOT), self.ROBOT, pose[0], pose[1],
                      0.0, 0.0, 0.0, pose[2])
        return w

    def _latest_scan(self):
        scans = self.world.take_sensor_outputs().get('scans', [])
        return scans[-1] if scans else None

    def _start_pose(self):
        if not self.random_start:
            return self.start
        dx, dy = self.np_random.uniform(-self.random_start, self.random_start, 2)
        yaw = self.np_random.uniform(-math.pi, math.pi)
        return (self.start[0] + dx, self.start[1] + dy, yaw)

    def _observe(self):
        s = self._latest_scan()
        if s is not None:
            r = np.asarray(s['ranges'], dtype=np.float32)
            self._scan = np.where(np.isfinite(r), np.minimum(r, self.range_max), self.range_max).astype(np.float32)
        ms = self.world.model_state(self.ROBOT)
        x, y, yaw = ms['position'][0], ms['position'][1], ms['yaw']
        d = self.goal - np.array([x, y])
        c, sn = math.cos(yaw), math.sin(yaw)
        goal_local = [c * d[0] + sn * d[1], -sn * d[0] + c * d[1]]
        v = c * ms['linear'][0] + sn * ms['linear'][1]
        tail = np.clip(goal_local, -self.GOAL_LIMIT, self.GOAL_LIMIT).tolist() + \
            np.clip([v, ms['angular'][2]], -self.SPEED_LIMIT, self.SPEED_LIMIT).tolist()
        obs = np.concatenate([self._scan, np.array(tail, dtype=np.float32)])
        self._xy = (x, y)
        return obs.astype(np.float32), float(np.hypot(d[0], d[1]))

    def _new_contacts(self):
        touching = set()
        for c in self.world.contacts():
            a, b = c['a'].split('/')[0], c['b'].split('/')[0]
            if a == self.ROBOT and b not in self._ground:
                touching.add(c['b'])
            elif b == self.ROBOT and a not in self._ground:
                touching.add(c['a'])
        new = touching - self._touching
        self._touching = touching
        return len(new)

    # ---- gymnasium API ----
    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        if seed is not None or self._seed is None:
            self._seed = 0 if seed is None else int(seed)
        self.world = self._build(self._seed, self._start_pose())
        self.world.set_sensor_active(self.ROBOT, self._lidar, True)
        # one scan period, so the first observation has a scan
        self.world.step(self.steps_per_action * 2)
        self._touching = set()
        self._scan = np.full(self.n_beams, self.range_max, np.float32)
        obs, self._dist = self._observe()
        return obs, {'distance': self._dist}

    def step(self, action):
        self._apply(action)
        self.world.step(self.steps_per_action)
        return self._after_step()

    def _apply(self, action):
        a = np.clip(np.asarray(action, dtype=np.float64), self.action_space.low, self.action_space.high)
        self.world.set_cmd_vel(self.ROBOT, float(a[0]), float(a[1]))

    def _after_step(self):
        obs, dist = self._observe()
        collisions = self._new_contacts()
        reward = (self._dist - dist) - self.collision_penalty * collisions - self.time_penalty
        self._dist = dist
        at_goal = dist <= self.goal_tolerance
        if at_goal:
            reward += self.goal_reward
        terminated = at_goal or (self.terminate_on_collision and collisions > 0)
        truncated = (not terminated) and self.world.time >= self.max_seconds
        return obs, float(reward), bool(terminated), bool(truncated), {
            'distance': dist, 'collisions': collisions, 'time': self.world.time, 'x': self._xy[0], 'y': self._xy[1]}


class DriveVectorEnv(gymnasium.vector.VectorEnv):
    """num_envs DriveEnvs in one process; each step sets every action, then one C++ call
    (car._core.step_worlds, the GIL released) steps all worlds. Autoreset: a sub-env that ended is reset on the
    next step() call and its action is ignored for that step (gymnasium's NEXT_STEP mode)."""

    metadata = {'autoreset_mode': gymnasium.vector.AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs, **kwargs):
        from car import _core
        self._step_worlds = _core.step_worlds
        self.envs = [DriveEnv(**kwargs) for _ in range(num_envs)]
        self.num_envs = num_envs
        self.single_observation_space = self.envs[0].observation_space
        self.single_action_space = self.envs[0].action_space
        self.observation_space = gymnasium.vector.utils.batch_space(self.single_observation_space, num_envs)
        self.action_space = gymnasium.vector.utils.batch_space(self.single_action_space, num_envs)
        self._done = np.zeros(num_envs, bool)

    def reset(self, *, seed=None, options=None):
        seeds = [None] * self.num_envs if seed is None else (
            list(seed) if isinstance(seed, (list, tuple)) else [seed + i for i in range(self.num_envs)])
        obs = [e.reset(seed=s)[0] for e, s in zip(self.envs, seeds)]
        self._done[:] = False
        return np.stack(obs), {}

    def step(self, actions):
        actions = np.asarray(actions)
        running = []
        obs = [None] * self.num_envs
        rew = np.zeros(self.num_envs)
        term = np.zeros(self.num_envs, bool)
        trunc = np.zeros(self.num_envs, bool)
        for i, e in enumerate(self.envs):
            if self._done[i]:
                obs[i] = e.reset()[0]
            else:
                e._apply(actions[i])
                running.append(i)
        self._step_worlds([self.envs[i].world for i in running], self.envs[0].steps_per_action)
        for i in running:
            obs[i], rew[i], term[i], trunc[i], _ = self.envs[i]._after_step()
        self._done = term | trunc
        return np.stack(obs), rew, term, trunc, {}


gymnasium.register(id='car/Drive-v0', entry_point='car.gym:DriveEnv')
