"""Gazebo 11's server command line for car (docs/COMPAT-dropins.md): `gzserver [options] [WORLD]` becomes car's
sim_node with the same ROS name and remappings, the world and the options as its private parameters.

gazebo_ros's launch files run `gzserver [-u] [-r] [--verbose] -e ENGINE EXTRA_ARGS WORLD` as a node named
`gazebo`; the compat packages gazebo_ros and gazebo forward their `gzserver`, `gazebo`, `gzclient`, `debug` and
`perf` executables here.
"""
import json
import os
import signal
import sys

# gazebo_ros's own system plug-ins: car is both, so they are accepted without a word (any folder)
ROS_SYSTEM_PLUGINS = ('libgazebo_ros_api_plugin.so', 'libgazebo_ros_paths_plugin.so')
ENGINES = ('ode', 'bullet', 'simbody', 'dart')

USAGE = """usage: gzserver [options] [WORLD]   (car: Gazebo 11's server options, docs/COMPAT-dropins.md)
  WORLD                  SDF world file, or a name under GAZEBO_RESOURCE_PATH (e.g. worlds/empty.world)
  -u, --pause            start paused
  -e, --physics ENGINE   ode, bullet, simbody or dart: accepted; car's own physics runs
  -s, --server-plugin L  system plug-in: gazebo_ros's own accepted (car is them), others loaded from their library
  --seed N               random seed (integer)
  --iters N              stop after N steps
  --verbose              accepted (car always logs at INFO)
  -r, --record, --record_path P, --record_period T, --record_encoding E, --record_filter F, --record_resources
                         warned: car does not record state logs
  --minimal_comms, --lockstep, -o/--profile P   accepted
  -h, --help; -v, --version"""


class UsageError(Exception):
    """A bad command line: the argument and the reason."""


def _is_ros_arg(a):
    # roslaunch/rosrun remappings: __name:=x, __log:=f, _param:=v, from:=to
    return ':=' in a


def parse(argv, program='gzserver'):
    """Parse a gzserver/gazebo command line.

    Returns a dict: world (str or None), paused, seed, iters, engine, verbose, plugins (list), system_plugins (the
    -s libraries car loads), argv (the command line without ROS remappings), warnings (list of
    log lines), notes (list), ros_args (remappings passed through), help, version. Raises UsageError naming the
    argument on anything gzserver would refuse.
    """
    opts = {'world': None, 'paused': False, 'seed': None, 'iters': None, 'engine': None, 'verbose': False,
            'plugins': [], 'system_plugins': [], 'argv': [a for a in argv if not _is_ros_arg(a)], 'warnings': [], 'notes': [], 'ros_args': [], 'help': False, 'version': False}
    takes_value = {'-e', '--physics', '-s', '--server-plugin', '-g', '--gui-plugin', '--seed', '--iters',
                   '--record_path', '--record_period', '--record_encoding', '--record_filter', '-o', '--profile',
                   '-p', '--play'}
    i = 0
    while i < len(argv):
        a = argv[i]
        i += 1
        if a == '':
            continue
        if _is_ros_arg(a):
            opts['ros_args'].append(a)
            continue
        value = None
        if a.startswith('--') and '=' in a:
            a, value = a.split('=', 1)
        if a in takes_value and value is None:
            if i >= len(argv) or (argv[i].startswith('-') and a not in ('--seed', '--iters')):
                raise UsageError('%s: needs a value' % a)
            value = argv[i]
            i += 1
        if a in ('-h', '--help'):
            opts['help'] = True
        elif a in ('-v', '--version'):
            opts['version'] = True
        elif a in ('-u', '--pause'):
            opts['paused'] = True
        elif a == '--verbose':
            opts['verbose'] = True
        elif a in ('-e', '--physics'):
            if value not in ENGINES:
                raise UsageError('%s %s: unknown physics engine (one of %s)' % (a, value, ', '.join(ENGINES)))
            opts['engine'] = value
        elif a in ('-s', '--server-plugin', '-g', '--gui-plugin'):
            if (a in ('-g', '--gui-plugin')) and program == 'gzserver':
                raise UsageError('%s: gzserver takes no GUI plug-ins (gazebo and gzclient do)' % a)
            opts['plugins'].append(value)
            if os.path.basename(value) in ROS_SYSTEM_PLUGINS:
                pass
            elif a in ('-g', '--gui-plugin'):
                opts['warnings'].append('%s %s: not loaded: car is headless (no GUI plug-ins)' % (a, value))
            else:
                # a system plug-in from a library: car's node loads it (docs/COMPAT-plugins.md)
                opts['system_plugins'].append(value)
        elif a in ('--seed', '--iters'):
            try:
                n = int(value)
            except (TypeError, ValueError):
                raise UsageError('%s %s: not an integer' % (a, value))
            if n < 0:
                raise UsageError('%s %s: must be >= 0' % (a, value))
            opts[a[2:]] = n
        elif a in ('-r', '--record', '--record_resources', '--record_path', '--record_period', '--record_encoding',
                   '--record_filter'):
            opts['warnings'].append('%s: ignored: car does not record Gazebo state logs' % a)
        elif a in ('-p', '--play'):
            raise UsageError('%s %s: car cannot play back Gazebo state logs' % (a, value))
        elif a in ('--minimal_comms', '--lockstep', '-o', '--profile'):
            opts['notes'].append('%s%s: accepted, no effect in car' % (a, '' if value is None else ' ' + value))
        elif a.startswith('-'):
            raise UsageError('%s: unknown option (gzserver --help lists them)' % a)
        elif opts['world'] is not None:
            raise UsageError('%s: a second world file (the first is %s); gzserver takes one' % (a, opts['world']))
        else:
            opts['world'] = a
    return opts


def node_argv(opts):
    """sim_node's arguments for parsed options: the ROS remappings, then private parameters (`_name:=value`)."""
    out = list(opts['ros_args'])
    if opts['world'] is not None:
        out.append('_world_name:=%s' % opts['world'])
    if opts['paused']:
        out.append('_paused:=true')
    if opts['seed'] is not None:
        out.append('_seed:=%d' % opts['seed'])
    if opts['iters'] is not None:
        out.append('_iters:=%d' % opts['iters'])
    if opts['system_plugins']:
        # YAML lists: the node's ~system_plugins and the command line they are loaded with (Load(argc, argv))
        out.append('_system_plugins:=%s' % json.dumps(opts['system_plugins']))
        out.append('_server_argv:=%s' % json.dumps(['gzserver'] + opts['argv']))
    return out


def _sim_node():
    import roslib.packages
    found = roslib.packages.find_node('car', 'sim_node')
    if not found:
        raise UsageError('car sim_node: not found (build the workspace: bash tools/setup.sh)')
    return found[0]


def main(argv=None, program='gzserver', note=None):
    """Run the server: parse, log what is ignored, exec car's sim_node. Returns an exit status on errors."""
    argv = sys.argv[1:] if argv is None else argv
    try:
        opts = parse(argv, program)
    except UsageError as e:
        print('%s: %s' % (program, e), file=sys.stderr)
        return 2
    if opts['help']:
        print(USAGE.replace('gzserver', program, 1))
        return 0
    if opts['version']:
        print('%s: car (headless Gazebo stand-in), Gazebo 11 command line' % program)
        return 0
    if note:
        print('%s: %s' % (program, note), flush=True)
    if opts['engine'] is not None:
        print('%s: physics engine "%s" requested: car simulates with its own physics (Bullet multibodies with '
              'ODE-style contacts)' % (program, opts['engine']), flush=True)
    for w in opts['warnings']:
        print('%s: warning: %s' % (program, w), file=sys.stderr, flush=True)
    for n in opts['notes']:
        print('%s: %s' % (program, n), flush=True)
    try:
        exe = _sim_node()
    except UsageError as e:
        print('%s: %s' % (program, e), file=sys.stderr)
        return 2
    args = node_argv(opts)
    os.execv(exe, [exe] + args)


def gazebo_main(argv=None):
    """`gazebo`: server and client in one; car has no client, so it is the server (GUI plug-ins accepted)."""
    return main(argv, program='gazebo', note='car is headless: the server runs, there is no GUI')


def client_main(argv=None):
    """`gzclient`: car has no GUI. Say so once and stay idle until shut down (SIGINT/SIGTERM), so launch files
    with gui:=true (and gui_required) start and stop as they do with Gazebo."""
    argv = sys.argv[1:] if argv is None else argv
    if any(a in ('-h', '--help') for a in argv):
        print('usage: gzclient [options]: car is headless; this process only waits until it is stopped')
        return 0
    print('gzclient: car is headless, there is no GUI; waiting until shutdown (rviz shows the robot and the world: '
          'README)', flush=True)
    stop = []
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, lambda *_: stop.append(True))
    while not stop:
        signal.pause()
    return 0


if __name__ == '__main__':
    sys.exit(main())
