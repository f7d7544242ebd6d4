#!/usr/bin/env python3
"""xacro.py (the pre-Jade name) for car: car's xacro, with Noetic's deprecation warning."""
import sys

# sys.path[0] is this script's folder, which holds xacro.py: `import xacro` must find the library, not it
del sys.path[0]
from car.xacro_tool import main  # noqa: E402

if __name__ == "__main__":
    print("xacro.py is deprecated; please use xacro instead", file=sys.stderr)
    sys.exit(main())
