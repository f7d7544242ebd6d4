#!/usr/bin/python3
"""Declared dependencies, checked: every Python module the code imports and every header or CMake package it uses
must map (through the table below) to a Debian package that tools/setup.sh installs and that the owning catkin
package's package.xml declares, or to a PyPI package pinned in a requirements file.

    tools/check_deps.py [--root DIR]      exit 0 when everything is declared, 1 with one line per gap

A module or header that is in no table is a gap too ("add it to the table"): nothing passes unseen.
"""
from __future__ import annotations

import argparse
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

# Python module (top level) -> (package.xml key, Debian package). The key is the rosdep / catkin name.
PY_DEBIAN = {
    'rospy': ('rospy', 'python3-rospy'),
    'rosgraph': ('rosgraph', 'python3-rosgraph'),
    'roslaunch': ('roslaunch', 'python3-roslaunch'),
    'rostest': ('rostest', 'python3-rostest'),
    'rosbag': ('rosbag', 'python3-rosbag'),
    'rospkg': ('python3-rospkg', 'python3-rospkg'),
    'roslib': ('roslib', 'python3-roslib'),
    'rosunit': ('rosunit', 'python3-rosunit'),
    'genmsg': ('genmsg', 'python3-genmsg'),
    'rosservice': ('rosservice', 'python3-rosservice'),
    'rostopic': ('rostopic', 'python3-rostopic'),
    'rosnode': ('rosnode', 'python3-rosnode'),
    'rosparam': ('rosparam', 'python3-rosparam'),
    'tf2_ros': ('tf2_ros', 'python3-tf2-ros'),
    'tf2_msgs': ('tf2_msgs', 'python3-tf2-msgs'),
    'geometry_msgs': ('geometry_msgs', 'python3-geometry-msgs'),
    'sensor_msgs': ('sensor_msgs', 'python3-sensor-msgs'),
    'nav_msgs': ('nav_msgs', 'python3-nav-msgs'),
    'std_msgs': ('std_msgs', 'python3-std-msgs'),
    'std_srvs': ('std_srvs', 'python3-std-srvs'),
    'rosgraph_msgs': ('rosgraph_msgs', 'python3-rosgraph-msgs'),
    'visualization_msgs': ('visualization_msgs', 'python3-visualization-msgs'),
    'trajectory_msgs': ('trajectory_msgs', 'python3-trajectory-msgs'),
    'actionlib': ('actionlib', 'python3-actionlib'),
    'actionlib_msgs': ('actionlib_msgs', 'python3-actionlib-msgs'),
    'dynamic_reconfigure': ('dynamic_reconfigure', 'python3-dynamic-reconfigure'),
    'numpy': ('python3-numpy', 'python3-numpy'),
    'matplotlib': ('python3-matplotlib', 'python3-matplotlib'),
    'tqdm': ('python3-tqdm', 'python3-tqdm'),
    'yaml': ('python3-yaml', 'python3-yaml'),
    'pytest': ('python3-pytest', 'python3-pytest'),
    'selenium': ('python3-selenium', 'python3-selenium'),
    'PIL': ('python3-pil', 'python3-pil'),
}

# Python module -> PyPI distribution, pinned in requirements.txt (installed by tools/setup.sh) or in
# bench/requirements.txt (installed by bench/run.sh; only bench/ may import these).
PY_PYPI = {
    'xacro': 'xacro',
    'pybullet': 'pybullet',
    'scipy': 'scipy',
    'mujoco': 'mujoco',
    'ray': 'ray',
    'pyarrow': 'pyarrow',
    'pandas': 'pandas',
    'gymnasium': 'gymnasium',
    'viser': 'viser',
    'trimesh': 'trimesh',
    'psutil': 'psutil',
}

# Modules of the build tooling itself (catkin's setup.py), installed with catkin.
PY_BUILD = {'setuptools', 'catkin_pkg', 'distutils'}

# <node pkg="..."> in launch and test files -> (package.xml key, Debian package).
LAUNCH = {
    'robot_state_publisher': ('robot_state_publisher', 'ros-robot-state-publisher'),
    'joint_state_publisher': ('joint_state_publisher', 'joint-state-publisher'),
    'rviz': ('rviz', 'rviz'),
    'rostopic': ('rostopic', 'python3-rostopic'),
    'rosbag': ('rosbag', 'ros-rosbag'),
    'nodelet': ('nodelet', 'libnodeletlib-tools'),
}

# #include prefix -> (package.xml key, Debian package). The longest matching prefix wins.
HEADERS = {
    'ros/': ('roscpp', 'libroscpp-dev'),
    'rosgraph_msgs/': ('rosgraph_msgs', 'libros-rosgraph-msgs-dev'),
    'geometry_msgs/': ('geometry_msgs', 'libgeometry-msgs-dev'),
    'sensor_msgs/': ('sensor_msgs', 'libsensor-msgs-dev'),
    'nav_msgs/': ('nav_msgs', 'libnav-msgs-dev'),
    'std_msgs/': ('std_msgs', 'libstd-msgs-dev'),
    'std_srvs/': ('std_srvs', 'libstd-srvs-dev'),
    'tf2_ros/': ('tf2_ros', 'libtf2-ros-dev'),
    'tf2_msgs/': ('tf2_msgs', 'libtf2-msgs-dev'),
    'visualization_msgs/': ('visualization_msgs', 'libvisualization-msgs-dev'),
    'trajectory_msgs/': ('trajectory_msgs', 'libtrajectory-msgs-dev'),
    'actionlib/': ('actionlib', 'libactionlib-dev'),
    'actionlib_msgs/': ('actionlib_msgs', 'libactionlib-msgs-dev'),
    'dynamic_reconfigure/': ('dynamic_reconfigure', 'libdynamic-reconfigure-config-init-mutex-dev'),
    'nodelet/': ('nodelet', 'libnodeletlib-dev'),
    'topic_tools/': ('topic_tools', 'libtopic-tools-dev'),
    'pluginlib/': ('pluginlib', 'libpluginlib-dev'),
    'urdf_parser/': ('liburdfdom-dev', 'liburdfdom-dev'),
    'urdf_model/': ('liburdfdom-headers-dev', 'liburdfdom-headers-dev'),
    'console_bridge/': ('libconsole-bridge-dev', 'libconsole-bridge-dev'),
    'tinyxml2.h': ('tinyxml2', 'libtinyxml2-dev'),
    'tinyxml.h': ('tinyxml', 'libtinyxml-dev'),
    'Eigen/': ('eigen', 'libeigen3-dev'),
    'pybind11/': ('pybind11-dev', 'pybind11-dev'),
    'sdf/': ('libsdformat-dev', 'libsdformat-dev'),
    'ignition/math': ('libignition-math-dev', 'libignition-math-dev'),
    'boost/': ('boost', 'libboost-dev'),
    'btBulletDynamicsCommon.h': ('libbullet-dev', 'libbullet-dev'),
    'BulletDynamics/': ('libbullet-dev', 'libbullet-dev'),
    'BulletCollision/': ('libbullet-dev', 'libbullet-dev'),
    'LinearMath/': ('libbullet-dev', 'libbullet-dev'),
    'embree3/': ('libembree-dev', 'libembree-dev'),
    'assimp/': ('libassimp-dev', 'libassimp-dev'),
    'gtest/': ('gtest', 'googletest'),
    'gmock/': ('gtest', 'googletest'),
    'omp.h': ('', ''),  # the compiler's own (libgomp, with gcc)
}

# #include prefix -> Debian package, for the peers under car/bench/ only (built by their own scripts, outside the
# catkin build); the script that builds them must install the package (an `apt-get ... install` line naming it).
BENCH_HEADERS = {
    'ode/': 'libode-dev',  # car/bench/peers/ode_skid.sh: stock ODE, the skid-steer reference
}

# find_package / pkg_check_modules names -> (package.xml key, Debian package).
CMAKE = {
    'catkin': ('catkin', 'catkin'),
    'urdfdom': ('liburdfdom-dev', 'liburdfdom-dev'),
    'tinyxml2': ('tinyxml2', 'libtinyxml2-dev'),
    'Eigen3': ('eigen', 'libeigen3-dev'),
    'pybind11': ('pybind11-dev', 'pybind11-dev'),
    'sdformat12': ('libsdformat-dev', 'libsdformat-dev'),
    'embree': ('libembree-dev', 'libembree-dev'),
    'OpenMP': ('', ''),
    'PkgConfig': ('', 'pkg-config'),
    'bullet-float64': ('libbullet-dev', 'libbullet-dev'),
    'assimp': ('libassimp-dev', 'libassimp-dev'),
    'GTest': ('gtest', 'googletest'),
    'ignition-math6': ('libignition-math-dev', 'libignition-math-dev'),
    'Boost': ('boost', 'libboost-dev'),
    # the pip build's entry (car/cmake/pip/): Python's headers, outside catkin
    'Python': ('', 'python3-dev'),
    # this repository's own packages, found by the drop-ins' CMake extras (compat/gazebo, compat/gazebo_dev)
    'car': ('car', ''),
    'gazebo': ('gazebo', ''),
}

# Python files that are not code of a catkin package's own (test helpers import each other by name).
SKIP_DIRS = {'.git', '.ws', '.venv', '__pycache__', 'bench/out', 'car/bench/out', 'node_modules', 'dist'}
# and every dot-folder: build trees (.ws-debs, .ws-asan, ...) hold generated code that is not the repository's

IMPORT_RE = re.compile(r'^\s*(?:from\s+([A-Za-z_][\w.]*)\s+import|import\s+([A-Za-z_][\w.]*(?:\s*,\s*[A-Za-z_][\w.]*)*))')
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*<([^>]+)>')
FIND_RE = re.compile(r'find_package\(\s*([\w.+-]+)')


def cmake_files(pkg_dir):
    """A package's CMakeLists.txt and the CMake files under its cmake/ (car/cmake/core.cmake, which CMakeLists.txt
    includes; cmake/pip/CMakeLists.txt, the pip build's entry)."""
    files = [os.path.join(pkg_dir, 'CMakeLists.txt')]
    files += sorted(glob.glob(os.path.join(pkg_dir, 'cmake', '**', '*.cmake'), recursive=True))
    files += sorted(glob.glob(os.path.join(pkg_dir, 'cmake', '**', 'CMakeLists.txt'), recursive=True))
    return [f for f in files if os.path.exists(f)]


def python_files(root):
    for d, dirs, files in os.walk(root):
        rel = os.path.relpath(d, root)
        dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith('.') and os.path.join(rel, x).lstrip('./') not in SKIP_DIRS]
        for f in files:
            p = os.path.join(d, f)
            if f.endswith('.py'):
                yield p
            elif '.' not in f and os.path.basename(d) == 'scripts':
                with open(p, 'rb') as fh:
                    first = fh.readline()
                if first.startswith(b'#!') and b'python' in first:
                    yield p


def cpp_files(root):
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith('.')]
        for f in files:
            if f.endswith(('.cpp', '.hpp', '.h', '.cc')):
                yield os.path.join(d, f)


def catkin_packages(root):
    """{folder: (name, set of declared keys)} for every package.xml in the repository."""
    out = {}
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith('.')]
        if 'package.xml' in files:
            tree = ET.parse(os.path.join(d, 'package.xml')).getroot()
            keys = {e.text.strip() for e in tree if e.text and e.tag.endswith('depend')}
            out[d] = (tree.findtext('name').strip(), keys)
    return out


def owner(path, packages):
    best = None
    for d in packages:
        if path.startswith(d + os.sep) and (best is None or len(d) > len(best)):
            best = d
    return best


def setup_packages(root):
    text = open(os.path.join(root, 'tools', 'setup.sh')).read()
    m = re.search(r'DEB_PACKAGES=\((.*?)\)', text, re.S)
    return set(re.sub(r'#.*', '', m.group(1)).split()) if m else set()


def pinned(root, rel):
    p = os.path.join(root, rel)
    if not os.path.exists(p):
        return set()
    names = set()
    for line in open(p):
        line = line.split('#', 1)[0].strip()
        if line:
            names.add(re.split(r'[=<>!~\[; ]', line, 1)[0].lower())
    return names


def local_modules(root):
    """Modules the repository provides itself: top-level Python packages and modules under python/, test/ and
    scripts/, and the catkin packages' names (generated messages)."""
    names = set()
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith('.')]
        for f in files:
            if f.endswith('.py'):
                names.add(f[:-3])
        for x in dirs:
            if os.path.exists(os.path.join(d, x, '__init__.py')):
                names.add(x)
    return names


def check(root):
    gaps = []
    packages = catkin_packages(root)
    deb = setup_packages(root)
    # car's pins live in car/ (its package folder); a package at the root (the tests' fixtures) has them there
    req = pinned(root, 'requirements.txt') | pinned(root, 'car/requirements.txt')
    bench_req = pinned(root, 'bench/requirements.txt') | pinned(root, 'car/bench/requirements.txt')
    local = local_modules(root) | {name for name, _ in packages.values()}
    stdlib = set(sys.stdlib_module_names)

    def need(path, what, key, debian):
        d = owner(path, packages)
        rel = os.path.relpath(path, root)
        if debian and debian not in deb:
            gaps.append('%s: %s needs Debian package %s, which tools/setup.sh does not install' % (rel, what, debian))
        if key and d is not None and key not in packages[d][1]:
            gaps.append('%s: %s needs <depend>%s</depend> (or build/exec/test) in %s' %
                        (rel, what, key, os.path.relpath(os.path.join(d, 'package.xml'), root)))

    for path in python_files(root):
        rel = os.path.relpath(path, root)
        for n, line in enumerate(open(path, encoding='utf-8', errors='replace'), 1):
            m = IMPORT_RE.match(line)
            if not m:
                continue
            mods = [m.group(1)] if m.group(1) else [x.strip() for x in m.group(2).split(',')]
            for mod in mods:
                top = mod.split('.')[0]
                if top in stdlib or top in local or top == '__future__' or top in PY_BUILD:
                    continue
                what = 'line %d imports %s' % (n, top)
                if top in PY_DEBIAN:
                    need(path, what, *PY_DEBIAN[top])
                elif top in PY_PYPI:
                    dist = PY_PYPI[top].lower()
                    ok = dist in req or (rel.startswith(('bench' + os.sep, os.path.join('car', 'bench') + os.sep)) and dist in bench_req)
                    if not ok:
                        gaps.append('%s: %s (PyPI %s), which no requirements file it may use pins' % (rel, what, dist))
                else:
                    gaps.append('%s: %s, which is in no table of tools/check_deps.py; add it' % (rel, what))
    bench_deb = set()
    for d, _, files in os.walk(os.path.join(root, 'car', 'bench')):
        for f in files:
            if f.endswith('.sh'):
                for line in open(os.path.join(d, f), encoding='utf-8', errors='replace'):
                    if 'apt-get' in line and ' install' in line:
                        bench_deb |= set(line.split())
    for path in cpp_files(root):
        rel_path = os.path.relpath(path, root)
        for n, line in enumerate(open(path, encoding='utf-8', errors='replace'), 1):
            m = INCLUDE_RE.match(line)
            if not m:
                continue
            inc = m.group(1)
            if '/' not in inc and '.' not in inc:
                continue  # the C++ standard library
            if inc in ('malloc.h', 'sys/stat.h', 'unistd.h', 'sys/resource.h', 'sys/types.h', 'signal.h', 'fcntl.h',
                       'netinet/tcp.h', 'sys/socket.h', 'pthread.h', 'dlfcn.h', 'sys/mman.h', 'sys/wait.h',
                       'poll.h', 'immintrin.h', 'sys/syscall.h', 'dirent.h', 'time.h'):
                continue  # the C library and compiler intrinsics
            bench = next((p for p in BENCH_HEADERS if inc.startswith(p)), None)
            if bench and rel_path.startswith(os.path.join('car', 'bench') + os.sep):
                if BENCH_HEADERS[bench] not in bench_deb:
                    gaps.append('%s: line %d includes <%s>, from Debian package %s, which no script under car/bench/ '
                                'installs' % (rel_path, n, inc, BENCH_HEADERS[bench]))
                continue
            best = max((p for p in HEADERS if inc.startswith(p)), key=len, default=None)
            if best is None:
                pkg = inc.split('/')[0]
                if pkg in local:
                    continue  # a message header of a catkin package in this repository, or our own headers
                if os.path.exists(os.path.join(root, 'include', pkg)) or os.path.exists(os.path.join(root, 'car', 'include', pkg)) or inc.startswith(('car_sim/', 'car/')):
                    continue
                gaps.append('%s: line %d includes <%s>, which is in no table of tools/check_deps.py; add it' %
                            (os.path.relpath(path, root), n, inc))
                continue
            need(path, 'line %d includes <%s>' % (n, inc), *HEADERS[best])
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith('.')]
        for f in files:
            if not f.endswith(('.launch', '.test', '.xml')) or f == 'package.xml':
                continue
            path = os.path.join(d, f)
            for n, line in enumerate(open(path, encoding='utf-8', errors='replace'), 1):
                for pkg in re.findall(r'<node\b[^>]*\bpkg="([^"$]+)"', line):
                    if pkg in {name for name, _ in packages.values()}:
                        continue
                    if pkg in LAUNCH:
                        need(path, 'line %d starts a node of %s' % (n, pkg), *LAUNCH[pkg])
                    else:
                        gaps.append('%s: line %d starts a node of %s, which is in no table of tools/check_deps.py; '
                                    'add it' % (os.path.relpath(path, root), n, pkg))
    for d, (name, keys) in packages.items():
        for cm in cmake_files(d):
            # comments left out: they may name find_package() calls as prose
            text = re.sub(r'#[^\n]*', '', open(cm).read())
            for m in FIND_RE.finditer(text):
                pkg = m.group(1)
                if pkg in CMAKE:
                    need(cm, 'find_package(%s)' % pkg, *CMAKE[pkg])
                else:
                    gaps.append('%s: find_package(%s) is in no table of tools/check_deps.py; add it' %
                                (os.path.relpath(cm, root), pkg))
            for m in re.finditer(r'pkg_check_modules\(([^)]*)\)', text):
                for word in m.group(1).split()[1:]:
                    if word in ('REQUIRED', 'IMPORTED_TARGET', 'QUIET', 'NO_CMAKE_PATH', 'NO_CMAKE_ENVIRONMENT_PATH'):
                        continue
                    if word in CMAKE:
                        need(cm, 'pkg_check_modules(%s)' % word, *CMAKE[word])
                    else:
                        gaps.append('%s: pkg_check_modules(%s) is in no table of tools/check_deps.py; add it' %
                                    (os.path.relpath(cm, root), word))
            # catkin components: each must be declared (they are ROS packages of the same name)
            for m in re.finditer(r'find_package\(\s*catkin\s+REQUIRED\s+COMPONENTS([^)]*)\)', text):
                for comp in m.group(1).split():
                    if comp not in keys:
                        gaps.append('%s: catkin component %s is not declared in package.xml' % (os.path.relpath(cm, root), comp))
    return sorted(set(gaps))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--root', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    args = ap.parse_args(argv)
    gaps = check(args.root)
    for g in gaps:
        print(g)
    print('check_deps: %d undeclared dependenc%s' % (len(gaps), 'y' if len(gaps) == 1 else 'ies'))
    return 1 if gaps else 0


if __name__ == '__main__':
    sys.exit(main())
