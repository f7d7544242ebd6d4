"""car: the simulator's Python side. The core (car._core, no ROS) is reached as car.World and the names below,
imported on first use, so that `import car` and the tools that do not simulate stay light; `import car` imports no
rospy: what talks to a ROS master lives in car.ros (the nodes and clients), which
nothing here imports (world_tool map --publish excepted, when asked)."""

# the core's names offered at the top (car.World ...); the rest: `from car import _core`
_CORE_NAMES = ('World', 'step_worlds', 'LoadError', 'load_world_file', 'load_world_string', 'load_urdf_file',
               'load_urdf_string', 'flatten_world', 'resolve_uri', 'model_path')


def __getattr__(name):
    if name in _CORE_NAMES:
        from car import _core
        return getattr(_core, name)
    raise AttributeError('module %r has no attribute %r' % (__name__, name))
