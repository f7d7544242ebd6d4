#!/usr/bin/env bash
# Runs the real Husky and Jackal packages as their READMEs launch them, against car's drop-ins, and measures the
# ground truth: the rest height of Husky spawned at z = 0, the circle driven at (0.5 m/s, 0.5 rad/s) and the speed
# driven at (0.5 m/s, 0). Fetches nothing: it takes git directories (or checkouts) of the repositories. Not in CI.
# docs/ROBOTS.md "Husky and Jackal, as their packages launch them" has the numbers of the last run.
#
#   tools/real_robots.sh MIRROR_DIR [husky|jackal ...]
#
# MIRROR_DIR holds one folder per repository, named OWNER+NAME, each a git directory, a folder with a git directory
# `repo`, or a checkout:
#   husky+husky (noetic-devel)             husky_description, husky_control, husky_gazebo
#   jackal+jackal (noetic-devel)           jackal_description, jackal_control
#   jackal+jackal_simulator (melodic-devel, the branch Noetic releases)   jackal_gazebo
# and, for the xacro files that the descriptions include unconditionally (each becomes a package.xml of ours and
# those files, nothing else: see "stubs" below):
#   clearpathrobotics+LMS1xx (noetic-devel)                 lms1xx/urdf/sick_lms1xx.urdf.xacro
#   lmark1+velodyne_simulator (master)                      velodyne_description/urdf/{VLP-16,HDL-32E}.urdf.xacro
#   ros-drivers+flir_camera_driver (noetic-devel)           flir_camera_description/urdf/flir_blackflys.urdf.xacro
#   clearpathrobotics+fath_pivot_mount_description (main)   fath_pivot_mount_description/urdf/lockmount.urdf.xacro
#   uos+sick_tim (noetic)                                   sick_tim/urdf/sick_tim.urdf.xacro
#   ros-drivers+pointgrey_camera_driver (noetic-devel)      pointgrey_camera_description/urdf/pointgrey_*.urdf.xacro
# and the models jackal_race.world names (model://drc_practice_*), which Gazebo takes from its model database:
#   osrf+gazebo_models (master)                             put on GAZEBO_MODEL_PATH
# Needs car's workspace built and sourced (source .ws/devel/setup.bash). The scratch workspace goes to /tmp.
#
# Not provided (their nodes are not started; roslaunch names each one and goes on): robot_localization's
# ekf_localization_node, twist_mux, interactive_marker_twist_server, joy, teleop_twist_joy. So the probe
# commands the controller's own topic (husky_velocity_controller/cmd_vel, jackal_velocity_controller/cmd_vel),
# the topic twist_mux would forward /cmd_vel to.
set -u

if [ $# -lt 1 ]; then
  sed -n '2,28p' "$0"
  exit 2
fi
MIRROR=$(realpath "$1")
shift
ROBOTS=${*:-husky jackal}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TOOL=real_robots
# shellcheck source=tools/mirror_ws.sh
source "$ROOT/tools/mirror_ws.sh"
mirror_ws_begin

# A stub: our package.xml and CMakeLists, and the named xacro files from the package's own repository
stub() {
  local pkg=$1 from=$2
  mkdir -p "$SRC/$pkg"
  cat > "$SRC/$pkg/package.xml" <<EOF
<?xml version="1.0"?>
<package format="2">
  <name>$pkg</name>
  <version>0.0.0</version>
  <description>Stub for car's tools/real_robots.sh: only the xacro files that Husky's and Jackal's descriptions
    include, from $from. No driver, no meshes.</description>
  <maintainer email="car@example.invalid">car</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
</package>
EOF
  printf 'cmake_minimum_required(VERSION 3.16)\nproject(%s)\nfind_package(catkin REQUIRED)\ncatkin_package()\n' "$pkg" \
    > "$SRC/$pkg/CMakeLists.txt"
  echo "stub $pkg: package.xml, CMakeLists.txt (ours) + $(cd "$SRC/$pkg" && find . -name '*.xacro' | sort | tr '\n' ' ')" >> "$WS/stubs.txt"
}

# ---- the robots' own packages, unchanged ---------------------------------------------------------------------
export_from husky+husky noetic-devel "$SRC" husky_description husky_control husky_gazebo
export_from jackal+jackal noetic-devel "$SRC" jackal_description jackal_control
export_from jackal+jackal_simulator melodic-devel "$SRC" jackal_gazebo

# ---- stubs: the description files the xacros include ---------------------------------------------------------
export_from clearpathrobotics+LMS1xx noetic-devel "$SRC/lms1xx" urdf/sick_lms1xx.urdf.xacro
stub lms1xx "clearpathrobotics/LMS1xx"
export_from lmark1+velodyne_simulator master "$WS/velodyne" velodyne_description/urdf/VLP-16.urdf.xacro \
  velodyne_description/urdf/HDL-32E.urdf.xacro
mv "$WS/velodyne/velodyne_description" "$SRC/"
stub velodyne_description "lmark1/velodyne_simulator"
export_from ros-drivers+flir_camera_driver noetic-devel "$WS/flir" flir_camera_description/urdf/flir_blackflys.urdf.xacro
mv "$WS/flir/flir_camera_description" "$SRC/"
stub flir_camera_description "ros-drivers/flir_camera_driver"
export_from clearpathrobotics+fath_pivot_mount_description main "$SRC/fath_pivot_mount_description" urdf/lockmount.urdf.xacro
stub fath_pivot_mount_description "clearpathrobotics/fath_pivot_mount_description"
export_from uos+sick_tim noetic "$SRC/sick_tim" urdf/sick_tim.urdf.xacro
stub sick_tim "uos/sick_tim"
export_from ros-drivers+pointgrey_camera_driver noetic-devel "$WS/pg" \
  pointgrey_camera_description/urdf/pointgrey_flea3.urdf.xacro pointgrey_camera_description/urdf/pointgrey_bumblebee2.urdf.xacro
mv "$WS/pg/pointgrey_camera_description" "$SRC/"
stub pointgrey_camera_description "ros-drivers/pointgrey_camera_driver"
rm -rf "$WS/velodyne" "$WS/flir" "$WS/pg"
export_from osrf+gazebo_models master "$WS/models" drc_practice_orange_jersey_barrier drc_practice_white_jersey_barrier \
  drc_practice_blue_cylinder drc_practice_angled_barrier_135
export GAZEBO_MODEL_PATH=$WS/models${GAZEBO_MODEL_PATH:+:$GAZEBO_MODEL_PATH}

mirror_ws_build
cat "$WS/sources.txt" "$WS/stubs.txt" "$WS/absent.txt" 2> /dev/null

# ---- the runs -------------------------------------------------------------------------------------------------
PROBE=$ROOT/tools/real_robots_probe.py
status=0
for robot in $ROBOTS; do
  case $robot in
    husky)
      launch=(husky_gazebo empty_world.launch)
      topic=/husky_velocity_controller/cmd_vel ;;
    jackal)
      launch=(jackal_gazebo jackal_world.launch)
      topic=/jackal_velocity_controller/cmd_vel ;;
    *) echo "real_robots: unknown robot $robot" >&2; exit 2 ;;
  esac
  log=$WS/$robot.launch.log
  port=$((11400 + RANDOM % 400))
  ROS_MASTER_URI=http://localhost:$port roscore -p "$port" > "$WS/$robot.roscore.log" 2>&1 &
  core=$!
  sleep 3
  # the probe listens from before the spawn, on sim time (the launch file sets /use_sim_time true as well)
  ROS_MASTER_URI=http://localhost:$port rosparam set /use_sim_time true
  ROS_MASTER_URI=http://localhost:$port /usr/bin/python3 "$PROBE" --robot "$robot" --topic "$topic" \
    --v 0.5 --w 0.5 >> "$WS/results.txt" 2> "$WS/$robot.probe.log" &
  probe=$!
  sleep 2
  # shellcheck disable=SC2086
  ROS_MASTER_URI=http://localhost:$port roslaunch "${launch[@]}" ${LAUNCH_ARGS:-} > "$log" 2>&1 &
  rl=$!
  wait "$probe" || { status=1; tail -3 "$WS/$robot.probe.log"; }
  kill -INT "$rl" 2> /dev/null
  wait "$rl" 2> /dev/null
  kill -INT "$core" 2> /dev/null
  wait "$core" 2> /dev/null
done
echo
cat "$WS/results.txt"
echo "real_robots: logs in $WS"
exit $status
