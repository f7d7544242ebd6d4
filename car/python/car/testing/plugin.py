"""The pytest side of car.testing: options, the `sim` fixture, and the failure report.

Nothing ROS is imported until a test asks for `sim`, so the plug-in costs nothing in test runs that do not use it.
"""
import os

import pytest

_SEED_KEY = 'car_testing_seed'


def pytest_addoption(parser):
    g = parser.getgroup('car', 'car.testing: the car simulator as a fixture (docs/TESTING.md)')
    g.addoption('--car-seed', dest='car_seed', default=None,
                help='noise seed of every simulator (integer, or "random"); default: ini car_seed, else 0')
    g.addoption('--car-scope', dest='car_scope', default=None, choices=('module', 'function'),
                help='one simulator per test module (default; reset between tests) or per test')
    g.addoption('--car-use-master', dest='car_use_master', action='store_true', default=False,
                help='use the master ROS_MASTER_URI names (rostest\'s) instead of starting one on a free port')
    g.addoption('--car-artifacts', dest='car_artifacts', default=None,
                help='folder for failure plots and bags (default: car-artifacts/ beside --junitxml, else ./car-artifacts)')
    g.addoption('--car-rtf', dest='car_rtf', default=None, type=float,
                help='real-time factor of every simulator (default: the marker\'s, else ini car_rtf, else 0)')
    parser.addini('car_seed', 'default noise seed (integer or "random")', default='0')
    parser.addini('car_scope', 'module or function', default='module')
    parser.addini('car_world', 'default world file (relative to the ini file); empty: car\'s empty world', default='')
    parser.addini('car_robot', 'default robot URDF / xacro / SDF (relative to the ini file)', default='')
    parser.addini('car_launch', 'default launch file of the nodes under test (relative to the ini file)', default='')
    parser.addini('car_rtf', 'default real-time factor (0: as fast as possible)', default='0')


def pytest_configure(config):
    config.addinivalue_line(
        'markers', 'car_sim(world=None, robot=None, name="robot", pose=(x, y, yaw), launch=None, launch_args=None, '
                   'nodes=[argv, ...], rtf=None, lockstep={trigger: response}, lockstep_timeout=5.0): the simulator of this module (or test, with --car-scope function); relative paths '
                   'are taken from the test file\'s folder')
    # rospy 1.15's threads call the deprecated notifyAll() thousands of times a run: not the user's to fix
    config.addinivalue_line('filterwarnings', 'ignore:notifyAll\\(\\) is deprecated:DeprecationWarning')
    raw = config.getoption('car_seed') or config.getini('car_seed') or '0'
    # a pytest-xdist worker takes the seed its controller chose (one "random" seed for the whole run)
    raw = getattr(config, 'workerinput', {}).get('car_seed', raw)
    if str(raw).lower() == 'random':
        seed = int.from_bytes(os.urandom(4), 'little') & 0x7fffffff
    else:
        try:
            seed = int(raw)
        except ValueError:
            raise pytest.UsageError('--car-seed: an integer or "random", got %r' % raw)
    setattr(config, _SEED_KEY, seed)


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node):
    """pytest-xdist (controller side): every worker gets the controller's seed."""
    node.workerinput['car_seed'] = str(getattr(node.config, _SEED_KEY))


def pytest_report_header(config):
    return 'car.testing: seed %d (replay: --car-seed %d)' % (getattr(config, _SEED_KEY), getattr(config, _SEED_KEY))


def pytest_unconfigure(config):
    import sys
    mod = sys.modules.get('car.testing.sim')
    if mod is not None:
        mod.shutdown_master()


def _scope(config):
    return config.getoption('car_scope') or config.getini('car_scope') or 'module'


def _resolve(path, base):
    if not path or path.lstrip().startswith('<'):
        return path or None
    path = os.path.expandvars(os.path.expanduser(path))
    return path if os.path.isabs(path) else os.path.normpath(os.path.join(base, path))


def sim_config(config, node):
    """The Sim keyword arguments for a test module or test: the car_sim marker, else the ini defaults."""
    ini_base = str(config.inipath.parent) if getattr(config, 'inipath', None) else str(config.rootpath)
    kw = {'world': _resolve(config.getini('car_world'), ini_base),
          'robot': _resolve(config.getini('car_robot'), ini_base),
          'launch': _resolve(config.getini('car_launch'), ini_base),
          'rtf': float(config.getini('car_rtf') or 0)}
    marker = node.get_closest_marker('car_sim')
    if marker is not None:
        base = os.path.dirname(str(node.path))
        for key, value in marker.kwargs.items():
            kw[key] = _resolve(value, base) if key in ('world', 'robot', 'launch') and isinstance(value, str) else value
    if config.getoption('car_rtf') is not None:
        kw['rtf'] = config.getoption('car_rtf')
    if kw.get('rtf') is None:
        kw['rtf'] = 0.0
    kw['seed'] = getattr(config, _SEED_KEY)
    kw['use_existing_master'] = config.getoption('car_use_master')
    return kw


@pytest.fixture(scope='module')
def _car_sim_module(request):
    """The module's simulator (module scope), or None when each test gets its own."""
    if _scope(request.config) != 'module':
        yield None
        return
    from car.testing.sim import Sim
    s = Sim(**sim_config(request.config, request.node))
    s._used = False
    yield s
    s.close()


@pytest.fixture
def sim(request, _car_sim_module):
    """A car simulator, paused at rtf 0 (by default) with the module's world and robot. Between tests of one
    module it is reset (sim time 0, models back at their first poses, spawned models deleted, recordings new)."""
    own = _car_sim_module is None
    if own:
        from car.testing.sim import Sim
        s = Sim(**sim_config(request.config, request.node))
    else:
        s = _car_sim_module
        s.forget_recordings()
        if s._used:
            s.reset()
    s._used = True
    request.node._car_sim = s
    yield s
    if own:
        s.close()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    rep = outcome.get_result()
    s = getattr(item, '_car_sim', None)
    if s is None or rep.when != 'call' or not rep.failed:
        return
    from car.testing import artifacts
    props = []
    lines = ['seed: %d (replay: pytest --car-seed %d %s)' % (s.seed, s.seed, item.nodeid)]
    out = artifacts.artifact_dir(item.config)
    os.makedirs(out, exist_ok=True)
    stem = os.path.join(out, artifacts.safe_name(item.nodeid))
    try:
        traj = s.trajectories.snapshot()
        n = artifacts.write_plot(stem + '.png', s.world, traj, title='%s  (seed %d)' % (item.nodeid, s.seed))
        lines.append('plot: %s (%d models)' % (stem + '.png', n))
        props.append(('car_plot', stem + '.png'))
    except Exception as e:  # the report must not hide the test's own failure
        lines.append('plot: not written: %s: %s' % (type(e).__name__, e))
    try:
        n = artifacts.write_bag(stem + '.bag', s.recordings)
        lines.append('bag: %s (%d messages of %s)' % (
            stem + '.bag', n, ', '.join(t for rec in s.recordings for t in rec.topics) or 'no recorded topic'))
        props.append(('car_bag', stem + '.bag'))
    except Exception as e:
        lines.append('bag: not written: %s: %s' % (type(e).__name__, e))
    if s.sim_proc.poll() is not None:
        lines.append('sim_node exited (%s); its log ends:\n%s' % (s.sim_proc.returncode, s.log_tail()))
    props.append(('car_seed', str(s.seed)))
    # junitxml writes the teardown report's properties, which come from the item's
    rep.user_properties.extend(props)
    item.user_properties.extend(props)
    rep.sections.append(('car.testing', '\n'.join(lines)))
