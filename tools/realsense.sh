#!/usr/bin/env bash
# A lab's own sensor plug-in, built UNCHANGED against car's Gazebo API (docs/PLUGINS.md "RealSense D435"): PAL's
# realsense_gazebo_plugin (librealsense_gazebo_plugin.so: a model plug-in that takes the D435's four camera sensors
# through SensorManager, publishes their frames on Gazebo's transport and on ROS through image_transport and
# camera_info_manager) on the D435 of PAL's realsense2_description (its _d435.urdf.xacro macro sensor_d435, with
# _d435.gazebo.xacro), spawned through gazebo_ros' empty_world.launch and spawn_model as a user would. The robot is
# ours, two lines: base_link and <xacro:sensor_d435 parent="base_link">, since the package's own
# test_d435_camera.urdf.xacro calls the macro without the xacro: prefix, which Noetic's xacro (1.14: "Require all
# xacro commands to be prefixed with 'xacro:'") leaves unexpanded, so it holds one massless link in Noetic.
# tools/realsense_probe.py checks the four image topics, their camera_info and the depth to a wall. Fetches nothing;
# not in CI.
#
#   tools/realsense.sh MIRROR_DIR
#
# MIRROR_DIR holds one folder per repository, named OWNER+NAME, each a git directory, a folder with a git directory
# `repo`, or a checkout:
#   pal-robotics+realsense_gazebo_plugin (melodic-devel)   the plug-in
#   pal-robotics-forks+realsense (melodic-devel)           realsense2_description only
# Needs car's workspace built and sourced (source .ws/devel/setup.bash), and Debian's libimage-transport-dev and
# libcamera-info-manager-dev (the plug-in's own dependencies; tools/setup.sh does not install them): without them it
# says so and stops. The scratch workspace goes to /tmp.
set -u

if [ $# -lt 1 ]; then
  sed -n '2,21p' "$0"
  exit 2
fi
MIRROR=$(realpath "$1")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TOOL=realsense
# shellcheck source=tools/mirror_ws.sh
source "$ROOT/tools/mirror_ws.sh"
require_debs realsense_gazebo_plugin image_transport/image_transport.h:libimage-transport-dev \
  camera_info_manager/camera_info_manager.h:libcamera-info-manager-dev
mirror_ws_begin
export_from pal-robotics+realsense_gazebo_plugin melodic-devel "$SRC/realsense_gazebo_plugin" .
export_from pal-robotics-forks+realsense melodic-devel "$SRC" realsense2_description
cat "$WS/sources.txt" "$WS/absent.txt" 2> /dev/null
# ours: the robot and the launch file a user writes for a description without them (the camera 0.3 m up, facing +x)
mkdir -p "$SRC/car_realsense_run/launch" "$SRC/car_realsense_run/urdf"
cat > "$SRC/car_realsense_run/package.xml" << 'XML'
<?xml version="1.0"?>
<package format="2"><name>car_realsense_run</name><version>0.0.0</version>
  <description>tools/realsense.sh's launch file</description><maintainer email="car@example.invalid">car</maintainer>
  <license>BSD</license><buildtool_depend>catkin</buildtool_depend></package>
XML
printf 'cmake_minimum_required(VERSION 3.16)\nproject(car_realsense_run)\nfind_package(catkin REQUIRED)\ncatkin_package()\n' \
  > "$SRC/car_realsense_run/CMakeLists.txt"
cat > "$SRC/car_realsense_run/urdf/d435.urdf.xacro" << 'XML'
<?xml version="1.0"?>
<robot name="d435" xmlns:xacro="http://ros.org/wiki/xacro">
  <xacro:include filename="$(find realsense2_description)/urdf/_d435.urdf.xacro" />
  <link name="base_link" />
  <xacro:sensor_d435 parent="base_link"><origin xyz="0 0 0" rpy="0 0 0" /></xacro:sensor_d435>
</robot>
XML
cat > "$SRC/car_realsense_run/launch/d435.launch" << 'XML'
<launch>
  <include file="$(find gazebo_ros)/launch/empty_world.launch" />
  <param name="robot_description"
         command="$(find xacro)/xacro $(find car_realsense_run)/urdf/d435.urdf.xacro" />
  <node name="spawn" pkg="gazebo_ros" type="spawn_model" args="-param robot_description -urdf -model d435 -z 0.3" />
</launch>
XML
mirror_ws_build
echo "realsense: built unchanged: $(cd "$WS/devel/lib" && ls lib*.so | tr '\n' ' ')"

status=0
run_beside d435 /usr/bin/python3 "$ROOT/tools/realsense_probe.py" -- car_realsense_run d435.launch || status=1
echo
grep -h -i "realsense\|error" "$WS/launch-d435.log" | grep -v "^\s*\*\|ROS_MASTER\|process\[" | head -5
cat "$WS/results-d435.txt"
tail -n 3 "$WS/probe-d435.log"
echo "realsense: logs in $WS"
exit $status
