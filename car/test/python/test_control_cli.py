"""car's spawner / controller_manager scripts take upstream's (ros_control Noetic) arguments and service names."""
from car.ros.control import _services, parse_spawner_args


def test_spawner_arguments_as_upstream():
    a = parse_spawner_args(['--stopped', '--namespace', 'arm', '--timeout', '5', '--shutdown-timeout', '2',
                            'a', 'b.yaml'])
    assert (a.stopped, a.namespace, a.timeout, a.shutdown_timeout, a.controllers) == (True, 'arm', 5.0, '2',
                                                                                       ['a', 'b.yaml'])


def test_spawner_defaults_as_upstream():
    a = parse_spawner_args(['x'])
    assert (a.stopped, a.namespace, a.timeout, a.no_timeout, a.wait_for) == (False, None, 30, False, None)


def test_service_names_under_the_namespace():
    assert _services('arm')['load_controller'] == 'arm/controller_manager/load_controller'
    assert _services('/arm/')['switch_controller'] == '/arm/controller_manager/switch_controller'
    # no namespace: relative names, resolved in the node's namespace (a spawner inside <group ns>)
    assert _services('')['unload_controller'] == 'controller_manager/unload_controller'
