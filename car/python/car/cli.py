"""car COMMAND ...: the package's command-line tools under one name (car batch, car world_tool, car check_model).
The `car` program of a pip install (pyproject.toml) and of scripts/car (rosrun car car)."""
import importlib
import sys

COMMANDS = {
    'batch': ('car.batch', 'run a scenario sweep on Ray, results as Parquet'),
    'world_tool': ('car.world_cli', 'flatten, check, map and plot SDF worlds'),
    'check_model': ('car.model_check', 'check a URDF/xacro model as the simulator would load it'),
}


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv or argv[0] not in COMMANDS:
        print('usage: car COMMAND [ARGS]\n' + '\n'.join('  %-12s %s' % (k, v[1]) for k, v in COMMANDS.items()),
              file=sys.stderr)
        return 0 if argv and argv[0] in ('-h', '--help') else 2
    mod = importlib.import_module(COMMANDS[argv[0]][0])
    return mod.main(argv[1:])


if __name__ == '__main__':
    sys.exit(main())
