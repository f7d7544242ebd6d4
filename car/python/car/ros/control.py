"""controller_manager's command-line tools for car's ros_control layer, with upstream's (ros_control Noetic)
arguments and behaviour (docs/COMPAT-control.md):

    spawner [--stopped] [--namespace NS] [--timeout T] [--no-timeout] [--shutdown-timeout T] [--wait-for TOPIC]
            CONTROLLER|FILE.yaml ...
    unspawner [--namespace NS] CONTROLLER ...
    controller_manager load|unload|start|stop|spawn|kill NAME ...; controller_manager list|list-types
"""
from __future__ import annotations

import argparse
import os
import sys
import time


def _services(ns: str) -> dict:
    """Service names of the controller manager in namespace ns (relative names when ns is empty)."""
    if ns and not ns.endswith('/'):
        ns += '/'
    base = ns + 'controller_manager/'
    return {k: base + k for k in ('load_controller', 'unload_controller', 'switch_controller',
                                  'list_controllers', 'list_controller_types')}


def _proxies(ns: str, timeout):
    """ServiceProxies of the controller manager, after waiting for them (timeout [s], None = forever)."""
    import rospy
    from controller_manager_msgs.srv import (ListControllers, ListControllerTypes, LoadController, SwitchController,
                                             UnloadController)
    names = _services(ns)
    types = {'load_controller': LoadController, 'unload_controller': UnloadController,
             'switch_controller': SwitchController, 'list_controllers': ListControllers,
             'list_controller_types': ListControllerTypes}
    out = {}
    for key in ('load_controller', 'switch_controller', 'unload_controller', 'list_controllers',
                'list_controller_types'):
        rospy.loginfo('Controller Spawner: Waiting for service ' + names[key])
        rospy.wait_for_service(names[key], timeout=timeout)
        out[key] = rospy.ServiceProxy(names[key], types[key])
    return out


def parse_spawner_args(argv):
    """spawner's arguments, as upstream's parse_args."""
    p = argparse.ArgumentParser(prog='spawner', description='Controller spawner')
    p.add_argument('--stopped', action='store_true', help='loads controllers, but does not start them')
    p.add_argument('--wait-for', metavar='topic',
                   help='does not load or start controllers until it hears "True" on a topic (Bool)')
    p.add_argument('--namespace', metavar='ns', help='namespace of the controller_manager services')
    p.add_argument('--timeout', metavar='T', type=float, default=30,
                   help='how long to wait for controller_manager services [s] (default 30); <= 0 waits forever')
    p.add_argument('--no-timeout', action='store_true', help='wait for the services forever (as --timeout 0)')
    p.add_argument('--shutdown-timeout', help='DEPRECATED upstream: no effect')
    p.add_argument('controllers', metavar='controller', nargs='+', help='controllers (or YAML files) to load')
    return p.parse_args(argv)


def spawner_main(argv=None) -> int:
    """Loads (and, unless --stopped, starts) controllers; on shutdown stops and unloads what it loaded."""
    import rospy
    import rosparam
    import yaml
    argv = rospy.myargv(sys.argv)[1:] if argv is None else argv
    args = parse_spawner_args(argv)
    timeout = None if args.no_timeout or args.timeout <= 0 else args.timeout
    rospy.init_node('spawner', anonymous=True)
    if args.shutdown_timeout is not None:
        rospy.logwarn('DEPRECATION warning: --shutdown-timeout has no effect.')
    try:
        px = _proxies(args.namespace or '', timeout)
    except rospy.exceptions.ROSException:
        rospy.logwarn("Controller Spawner couldn't find the expected controller_manager ROS interface.")
        return 0
    if args.wait_for:
        from std_msgs.msg import Bool
        heard = [None]
        rospy.Subscriber(args.wait_for, Bool, lambda m: heard.__setitem__(0, m))
        while not rospy.is_shutdown() and not (heard[0] and heard[0].data):
            time.sleep(0.01)
    loaded = []

    def shutdown():
        if not loaded:
            return
        rospy.loginfo('Shutting down spawner. Stopping and unloading controllers...')
        try:
            px['switch_controller']([], loaded, 2, False, 0.0)
            for name in reversed(loaded):
                px['unload_controller'](name)
        except (rospy.ServiceException, rospy.exceptions.ROSException) as e:
            rospy.logwarn('Controller Spawner: could not unload %s: %s', loaded, e)

    rospy.on_shutdown(shutdown)
    names = []
    for name in args.controllers:
        if os.path.exists(name):
            # a YAML file: its keys go onto the parameter server (in the spawner's namespace) and are controllers
            with open(name) as f:
                rosparam.set_param('', f.read())
            with open(name) as f:
                names.extend(list(yaml.safe_load(f) or {}))
        else:
            names.append(name)
    for name in names:
        rospy.loginfo('Loading controller: ' + name)
        if px['load_controller'](name).ok:
            loaded.append(name)
        else:
            rospy.logerr('Failed to load %s' % name)
    rospy.loginfo('Controller Spawner: Loaded controllers: %s' % ', '.join(loaded))
    if rospy.is_shutdown():
        return 0
    if not args.stopped:
        if px['switch_controller'](loaded, [], 2, False, 0.0).ok:
            rospy.loginfo('Started controllers: %s' % ', '.join(loaded))
        else:
            rospy.logerr('Failed to start controllers: %s' % ', '.join(loaded))
    rospy.spin()
    return 0


def unspawner_main(argv=None) -> int:
    """Stops the named controllers now and starts them again on shutdown (upstream's unspawner)."""
    import rospy
    argv = rospy.myargv(sys.argv)[1:] if argv is None else argv
    p = argparse.ArgumentParser(prog='unspawner', description='Controller unspawner')
    p.add_argument('--namespace', metavar='ns', help='namespace of the controller_manager services')
    p.add_argument('--timeout', metavar='T', type=float, default=30)
    p.add_argument('controllers', metavar='controller', nargs='+')
    args = p.parse_args(argv)
    rospy.init_node('unspawner', anonymous=True)
    px = _proxies(args.namespace or '', args.timeout if args.timeout > 0 else None)
    rospy.on_shutdown(lambda: px['switch_controller'](args.controllers, [], 2, False, 0.0))
    if px['switch_controller']([], args.controllers, 2, False, 0.0).ok:
        rospy.loginfo('Stopped controllers: %s' % ', '.join(args.controllers))
    else:
        rospy.logerr('Failed to stop controllers: %s' % ', '.join(args.controllers))
    rospy.spin()
    return 0


USAGE = '''Commands:
  load <name>       Load a controller
  unload <name>     Unload a controller
  start <name>      Start a controller
  stop <name>       Stop a controller
  spawn <name>      Load and start a controller
  kill <name>       Stop and unload a controller
  list              List active controllers
  list-types        List controller types
'''


def controller_manager_main(argv=None) -> int:
    """controller_manager COMMAND [NAME ...]: upstream's command-line client."""
    import rospy
    argv = rospy.myargv(sys.argv)[1:] if argv is None else argv
    if not argv:
        print(USAGE)
        return 0
    cmd, names = argv[0], argv[1:]
    needs_names = ('load', 'unload', 'start', 'stop', 'spawn', 'kill')
    if cmd not in needs_names + ('list', 'list-types') or (cmd in needs_names and not names):
        print(USAGE)
        return 1
    px = _proxies('', None)
    ok = True
    if cmd == 'list':
        for c in px['list_controllers']().controller:
            print('%s - %s ( %s )' % (c.name, ','.join(
                sorted({r for h in c.claimed_resources for r in h.resources})), c.state))
    elif cmd == 'list-types':
        for t in px['list_controller_types']().types:
            print(t)
    for n in names:
        if cmd in ('load', 'spawn'):
            r = px['load_controller'](n).ok
            print(('Loaded ' if r else 'Error when loading ') + n)
            ok = ok and r
        if cmd in ('start', 'spawn'):
            r = px['switch_controller']([n], [], 2, False, 0.0).ok
            print(('Started ' if r else 'Error when starting ') + n)
            ok = ok and r
        if cmd in ('stop', 'kill'):
            r = px['switch_controller']([], [n], 2, False, 0.0).ok
            print(('Stopped ' if r else 'Error when stopping ') + n)
            ok = ok and r
        if cmd in ('unload', 'kill'):
            r = px['unload_controller'](n).ok
            print(('Unloaded ' if r else 'Error when unloading ') + n)
            ok = ok and r
    return 0 if ok else 1
