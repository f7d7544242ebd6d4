"""Scenarios for batch runs: a YAML file describing a world, robots, what drives them and a sweep over any field.

    name: corridor_sweep          # optional, for the output's file names
    world: ../worlds/box_house.world   # relative to this file, $(find pkg)/..., absolute, or omitted: ground only
    duration: 20.0                # [s] of simulated time per run
    seed: 1                       # noise seed; the same seed and scenario give bit-identical results
    record_rate: 10               # [Hz] trajectory samples kept per run (0: none)
    robots:
      - name: mycar
        model: ../urdf/xacro/car.urdf.xacro   # .urdf or .xacro (expanded with xacro_args)
        xacro_args: {}
        pose: {x: 0, y: 0, z: 0, yaw: 0}      # [m], [rad], world frame
        drive:                      # one of:
          commands:                 #   a timed list: from t [s] on, drive (v [m/s], w [rad/s])
            - {t: 0, v: 0.5, w: 0.0}
          controller: ctrl.py:steer #   f(observation) -> (v, w), called at rate [Hz]
          rate: 10
    sweep:                          # optional; runs = the base scenario with each set of overrides
      grid:                         #   every combination (the product of the lists)
        robots.0.pose.x: [-1, 0, 1]
        robots.0.pose.yaw: {linspace: [0, 3.14, 4]}
      list:                         #   or (and, after the grid) these override sets one by one
        - {seed: 2}

A field path is dotted; list items by index (robots.0.pose.x). Errors name the file, the field and the reason.
No ROS: the runs use the core's Python API.
"""
from __future__ import annotations

import copy
import hashlib
import itertools
import json
import math
import os
import re

import yaml

TOP_FIELDS = {'name', 'world', 'duration', 'seed', 'record_rate', 'robots', 'sweep'}
ROBOT_FIELDS = {'name', 'model', 'xacro_args', 'pose', 'drive'}
POSE_FIELDS = {'x', 'y', 'z', 'roll', 'pitch', 'yaw'}
DRIVE_FIELDS = {'commands', 'controller', 'rate'}
COMMAND_FIELDS = {'t', 'v', 'w'}
SWEEP_FIELDS = {'grid', 'list'}
MAX_RUNS = 1_000_000


class ScenarioError(Exception):
    """A scenario that cannot run: str() is 'FILE: FIELD: REASON'."""

    def __init__(self, file: str, field: str, reason: str):
        super().__init__('%s: %s: %s' % (file, field or '(top)', reason))
        self.file, self.field, self.reason = file, field, reason


def _number(file, field, value, minimum=None, positive=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ScenarioError(file, field, '%r is not a finite number' % (value,))
    if positive and value <= 0:
        raise ScenarioError(file, field, '%r is not > 0' % (value,))
    if minimum is not None and value < minimum:
        raise ScenarioError(file, field, '%r is below %r' % (value, minimum))
    return float(value)


def _unknown(file, where, d, allowed):
    if not isinstance(d, dict):
        raise ScenarioError(file, where, 'expected a mapping, got %s' % type(d).__name__)
    extra = sorted(set(d) - allowed)
    if extra:
        raise ScenarioError(file, '%s%s' % (where + '.' if where else '', extra[0]),
                            'unknown field (known: %s)' % ', '.join(sorted(allowed)))


def resolve_path(path: str, base_dir: str) -> str:
    """A file named in a scenario: $(find pkg)/rest through rospkg (without it: $(find car) only), absolute, or
    relative to the scenario's folder."""
    m = re.match(r'^\$\(find ([^)\s]+)\)(.*)$', path)
    if m:
        try:
            import rospkg
        except ImportError:  # a pip install without ROS: $(find car) is car's own files, other packages unknown
            from car.paths import package_dir
            return package_dir() + m.group(2) if m.group(1) == 'car' else path
        try:
            return rospkg.RosPack().get_path(m.group(1)) + m.group(2)
        except rospkg.ResourceNotFound:
            return path
    return path if os.path.isabs(path) else os.path.normpath(os.path.join(base_dir, path))


def validate(sc: dict, file: str) -> dict:
    """Checks one (expanded) scenario and returns it normalised: defaults filled, paths absolute."""
    _unknown(file, '', sc, TOP_FIELDS)
    base = os.path.dirname(os.path.abspath(file)) if os.path.exists(file) else os.getcwd()
    out = {'name': str(sc.get('name') or os.path.splitext(os.path.basename(file))[0])}
    world = sc.get('world')
    if world:
        out['world'] = resolve_path(str(world), base)
        if not os.path.isfile(out['world']):
            raise ScenarioError(file, 'world', 'no such file: %s' % out['world'])
    else:
        out['world'] = None
    out['duration'] = _number(file, 'duration', sc.get('duration', 10.0), positive=True)
    seed = sc.get('seed', 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ScenarioError(file, 'seed', '%r is not an integer >= 0' % (seed,))
    out['seed'] = seed
    out['record_rate'] = _number(file, 'record_rate', sc.get('record_rate', 10), minimum=0)
    robots = sc.get('robots')
    if not isinstance(robots, list) or not robots:
        raise ScenarioError(file, 'robots', 'expected a non-empty list of robots')
    out['robots'] = []
    names = set()
    for i, r in enumerate(robots):
        where = 'robots.%d' % i
        _unknown(file, where, r, ROBOT_FIELDS)
        name = str(r.get('name') or 'robot%d' % i)
        if name in names:
            raise ScenarioError(file, where + '.name', 'duplicate robot name %r' % name)
        names.add(name)
        if not r.get('model'):
            raise ScenarioError(file, where + '.model', 'missing (a .urdf or .xacro file)')
        model = resolve_path(str(r['model']), base)
        if not os.path.isfile(model):
            raise ScenarioError(file, where + '.model', 'no such file: %s' % model)
        args = r.get('xacro_args') or {}
        if not isinstance(args, dict):
            raise ScenarioError(file, where + '.xacro_args', 'expected a mapping of argument: value')
        pose = r.get('pose') or {}
        _unknown(file, where + '.pose', pose, POSE_FIELDS)
        pose = {k: _number(file, '%s.pose.%s' % (where, k), pose.get(k, 0.0)) for k in sorted(POSE_FIELDS)}
        drive = r.get('drive') or {}
        _unknown(file, where + '.drive', drive, DRIVE_FIELDS)
        if 'commands' in drive and 'controller' in drive:
            raise ScenarioError(file, where + '.drive', 'give commands or a controller, not both')
        d = {'commands': [], 'controller': None, 'rate': _number(file, where + '.drive.rate', drive.get('rate', 10),
                                                                 positive=True)}
        for k, c in enumerate(drive.get('commands') or []):
            cw = '%s.drive.commands.%d' % (where, k)
            _unknown(file, cw, c, COMMAND_FIELDS)
            d['commands'].append({f: _number(file, cw + '.' + f, c.get(f, 0.0)) for f in ('t', 'v', 'w')})
        times = [c['t'] for c in d['commands']]
        if times != sorted(times):
            raise ScenarioError(file, where + '.drive.commands', 'times must not decrease')
        if drive.get('controller'):
            spec = str(drive['controller'])
            if ':' not in spec:
                raise ScenarioError(file, where + '.drive.controller', "expected 'file.py:function', got %r" % spec)
            path, func = spec.rsplit(':', 1)
            path = resolve_path(path, base)
            if not os.path.isfile(path):
                raise ScenarioError(file, where + '.drive.controller', 'no such file: %s' % path)
            d['controller'] = '%s:%s' % (path, func)
        out['robots'].append({'name': name, 'model': model, 'xacro_args': {str(k): str(v) for k, v in args.items()},
                              'pose': pose, 'drive': d})
    return out


def _values(file, field, spec):
    if isinstance(spec, dict) and set(spec) == {'linspace'}:
        a = spec['linspace']
        if not (isinstance(a, list) and len(a) == 3 and isinstance(a[2], int) and a[2] >= 1):
            raise ScenarioError(file, 'sweep.grid.' + field, 'linspace takes [start, stop, count]')
        lo, hi, n = _number(file, field, a[0]), _number(file, field, a[1]), a[2]
        return [lo + (hi - lo) * i / (n - 1) for i in range(n)] if n > 1 else [lo]
    if isinstance(spec, dict) and set(spec) == {'range'}:
        a = spec['range']
        if not (isinstance(a, list) and len(a) == 3 and float(a[2]) != 0):
            raise ScenarioError(file, 'sweep.grid.' + field, 'range takes [start, stop, step]')
        lo, hi, st = (_number(file, field, x) for x in a)
        n = int(math.floor((hi - lo) / st + 1e-9)) + 1
        return [lo + i * st for i in range(max(n, 0))]
    if not isinstance(spec, list) or not spec:
        raise ScenarioError(file, 'sweep.grid.' + field, 'expected a non-empty list, {linspace: ...} or {range: ...}')
    return spec


def set_field(sc: dict, path: str, value, file: str = '<scenario>'):
    """Sets a dotted field (robots.0.pose.x) in a raw scenario mapping, creating mappings on the way."""
    keys = path.split('.')
    node = sc
    for i, k in enumerate(keys[:-1]):
        if isinstance(node, list):
            if not k.isdigit() or int(k) >= len(node):
                raise ScenarioError(file, path, 'no list item %s' % k)
            node = node[int(k)]
        else:
            if not isinstance(node, dict):
                raise ScenarioError(file, path, '%s is not a mapping' % '.'.join(keys[:i]))
            node = node.setdefault(k, {})
    last = keys[-1]
    if isinstance(node, list):
        if not last.isdigit() or int(last) >= len(node):
            raise ScenarioError(file, path, 'no list item %s' % last)
        node[int(last)] = value
    elif isinstance(node, dict):
        node[last] = value
    else:
        raise ScenarioError(file, path, 'cannot set a field inside a %s' % type(node).__name__)


def run_id(overrides: dict) -> str:
    """A stable id for one run: a short hash of its overrides (same sweep entry, same id, on any machine)."""
    text = json.dumps(overrides, sort_keys=True, default=str)
    return hashlib.sha1(text.encode()).hexdigest()[:12]


def expand(raw: dict, file: str) -> list:
    """The runs of a raw scenario: one per sweep entry (or the scenario alone). Each run is
    {'id', 'index', 'overrides', 'scenario'} with the scenario validated."""
    if not isinstance(raw, dict):
        raise ScenarioError(file, '', 'a scenario is a mapping (name, world, duration, seed, robots, sweep)')
    _unknown(file, '', raw, TOP_FIELDS)
    sweep = raw.get('sweep') or {}
    _unknown(file, 'sweep', sweep, SWEEP_FIELDS)
    base = {k: v for k, v in raw.items() if k != 'sweep'}
    sets = []
    grid = sweep.get('grid') or {}
    if not isinstance(grid, dict):
        raise ScenarioError(file, 'sweep.grid', 'expected a mapping of field: values')
    if grid:
        fields = list(grid)
        values = [_values(file, f, grid[f]) for f in fields]
        n = 1
        for v in values:
            n *= len(v)
        if n > MAX_RUNS:
            raise ScenarioError(file, 'sweep.grid', '%d runs is more than the limit of %d' % (n, MAX_RUNS))
        sets += [dict(zip(fields, combo)) for combo in itertools.product(*values)]
    lst = sweep.get('list') or []
    if not isinstance(lst, list) or not all(isinstance(x, dict) for x in lst):
        raise ScenarioError(file, 'sweep.list', 'expected a list of mappings field: value')
    sets += lst
    if not sets:
        sets = [{}]
    runs = []
    for i, ov in enumerate(sets):
        sc = copy.deepcopy(base)
        for f, v in ov.items():
            if f.split('.')[0] not in TOP_FIELDS - {'sweep'}:
                raise ScenarioError(file, 'sweep: ' + f, 'unknown field')
            set_field(sc, f, v, file)
        runs.append({'id': run_id(ov), 'index': i, 'overrides': ov, 'scenario': validate(sc, file)})
    return runs


def load(path: str) -> list:
    """Reads a scenario file and returns its runs (see expand)."""
    try:
        with open(path, encoding='utf-8') as f:
            raw = yaml.safe_load(f)
    except OSError as e:
        raise ScenarioError(path, '', 'cannot read: %s' % e.strerror)
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        where = 'line %d' % (mark.line + 1) if mark else ''
        raise ScenarioError(path, where, 'not YAML: %s' % getattr(e, 'problem', e))
    return expand(raw, path)
