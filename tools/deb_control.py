#!/usr/bin/env python3
"""DEBIAN/control for one of tools/make_debs.sh's packages: its run dependencies from the catkin package's
package.xml (depend, exec_depend), as Debian's own packages of the ROS keys name them, plus the shared libraries
dpkg-shlibdeps found. A key with no Debian package in the table below stops the build, naming it."""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

# ROS key (package.xml) -> Debian's run-time package(s) for it. C++ libraries come from dpkg-shlibdeps; a message
# package's run-time half is its Python module (its C++ headers are build-time only). '' = nothing at run time.
RUN = {
    'rospy': 'python3-rospy', 'roslaunch': 'python3-roslaunch',
    'roscpp': '', 'rosparam': 'python3-rosparam', 'rosbag': 'python3-rosbag', 'message_runtime': 'python3-genpy',
    'message_generation': '', 'std_msgs': 'python3-std-msgs', 'std_srvs': 'python3-std-srvs',
    'geometry_msgs': 'python3-geometry-msgs', 'nav_msgs': 'python3-nav-msgs',
    'trajectory_msgs': 'python3-trajectory-msgs', 'sensor_msgs': 'python3-sensor-msgs',
    'roslib': 'python3-roslib', 'rosgraph_msgs': 'python3-rosgraph-msgs', 'tf2_ros': 'python3-tf2-ros', 'tf2_msgs': 'python3-tf2-msgs',
    'dynamic_reconfigure': 'python3-dynamic-reconfigure', 'actionlib': 'python3-actionlib',
    'actionlib_msgs': 'python3-actionlib-msgs', 'visualization_msgs': 'python3-visualization-msgs',
    'python3-rospkg': 'python3-rospkg', 'robot_state_publisher': 'ros-robot-state-publisher',
    'joint_state_publisher': 'joint-state-publisher', 'python3-yaml': 'python3-yaml',
    'python3-numpy': 'python3-numpy', 'python3-tqdm': 'python3-tqdm',
    # libraries: dpkg-shlibdeps names the run-time package of each
    'liburdfdom-dev': '', 'liburdfdom-headers-dev': '', 'libconsole-bridge-dev': '', 'tinyxml2': '', 'tinyxml': '', 'libsdformat-dev': '',
    'libbullet-dev': '', 'libembree-dev': '', 'libassimp-dev': '', 'topic_tools': '', 'libignition-math-dev': '',
    'boost': '',
    # this repository's own packages
    'car': 'ros-car', 'gazebo_msgs': 'ros-car-gazebo-msgs', 'controller_manager_msgs': 'ros-car-controller-manager-msgs',
    'control_msgs': 'ros-car-control-msgs', 'gazebo_ros': 'ros-car-gazebo-ros', 'gazebo': 'ros-car-gazebo',
    'xacro': 'ros-car-xacro', 'controller_manager': 'ros-car-controller-manager', 'gazebo_dev': 'ros-car-gazebo-dev',
    'gazebo_plugins': 'ros-car-gazebo-plugins', 'control_toolbox': 'ros-car-control-toolbox',
    'gazebo_ros_control': 'ros-car-gazebo-ros-control',
}
# What a user expects beside the simulator, not needed to run it: rviz (a display); matplotlib draws the plots of
# world_tool plot and of a failed car.testing test (it pulls a compiler in through pythran: a Recommends keeps it
# out of `apt-get install --no-install-recommends`).
RECOMMENDS = {'rviz': 'rviz', 'python3-matplotlib': 'python3-matplotlib'}
# Every package runs through catkin's setup files in /opt/car, and the command-line tools users run with it.
ALWAYS = ['ros-car-setup']
TOOLS = {'ros-car': ['rosbash', 'python3-rostopic', 'python3-rosnode', 'python3-rosservice', 'python3-rosmaster']}


def package_xml(root, deb):
    if deb == 'ros-car':
        return os.path.join(root, 'car', 'package.xml')
    name = deb[len('ros-car-'):].replace('-', '_')
    return os.path.join(root, 'compat', name, 'package.xml')


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--deb', required=True)
    ap.add_argument('--root', required=True)
    ap.add_argument('--version', required=True)
    ap.add_argument('--arch', required=True)
    ap.add_argument('--shlibs', default='')
    ap.add_argument('--installed-size', default='0')
    a = ap.parse_args(argv)
    depends, recommends = [], []
    if a.deb == 'ros-car-setup':
        desc = ('catkin workspace files of car\'s install in /opt/car\n'
                ' setup.bash and friends: `source /opt/car/setup.bash` puts car and its drop-in packages on the ROS\n'
                ' package path.')
        depends = ['python3']
        arch = 'all'
    else:
        tree = ET.parse(package_xml(a.root, a.deb)).getroot()
        keys = [e.text.strip() for e in tree if e.tag in ('depend', 'exec_depend', 'run_depend') and e.text]
        for k in keys:
            if k in RECOMMENDS:
                recommends.append(RECOMMENDS[k])
                continue
            if k not in RUN:
                sys.exit('deb_control: %s: package.xml run dependency %s has no Debian package in '
                         'tools/deb_control.py RUN' % (a.deb, k))
            if RUN[k]:
                depends.append(RUN[k])
        depends = ALWAYS + depends + TOOLS.get(a.deb, [])
        summary = ' '.join(tree.findtext('description').split())
        desc = '%s (car)\n %s' % (tree.findtext('name'), summary)
        arch = a.arch if a.shlibs else 'all'
    if a.shlibs:
        depends += [d.strip() for d in a.shlibs.split(',') if d.strip()]
    seen, dep = set(), []
    for d in depends:
        if d.split()[0] not in seen:
            seen.add(d.split()[0])
            dep.append(d)
    lines = [
        'Package: %s' % a.deb,
        'Version: %s' % a.version,
        'Architecture: %s' % arch,
        'Maintainer: car developers <car@example.org>',
        'Installed-Size: %s' % a.installed_size,
        'Section: misc',
        'Priority: optional',
        'Depends: %s' % ', '.join(dep),
    ]
    if recommends:
        lines.append('Recommends: %s' % ', '.join(recommends))
    lines.append('Description: %s' % desc)
    print('\n'.join(lines))


if __name__ == '__main__':
    main()
