#!/usr/bin/env bash
# Runs Kobuki as kobuki_gazebo launches it, with kobuki_desktop's own plug-in libgazebo_ros_kobuki.so built
# UNCHANGED against car's Gazebo API (docs/PLUGINS.md), and checks what the robot does (tools/kobuki_probe.py):
# /mobile_base/commands/velocity moves it, /odom and the IMU publish, the bumper reports against a wall, the cliff
# sensor reports no cliff at an edge, as in Gazebo 11 (kobuki#431).
# Fetches nothing: it takes git directories (or checkouts) of the repositories. Not in
# CI. docs/PLUGINS.md "Kobuki, with its own plug-in built unchanged" has the table of the last run.
#
#   tools/kobuki.sh MIRROR_DIR
#
# MIRROR_DIR holds one folder per repository, named OWNER+NAME, each a git directory, a folder with a git directory
# `repo`, or a checkout:
#   yujinrobot+kobuki_desktop (melodic: 0.5.7, its GAZEBO_MAJOR_VERSION >= 9 branches; no later branch)
#                                  kobuki_gazebo, kobuki_gazebo_plugins
#   yujinrobot+kobuki (melodic)    kobuki_description
#   yujinrobot+kobuki_msgs (noetic)  kobuki_msgs
# Needs car's workspace built and sourced (source .ws/devel/setup.bash), and two Debian packages tools/setup.sh does
# not install: liburdf-dev (kobuki_description's find_package(catkin COMPONENTS urdf): urdfConfig.cmake) and
# libtf-dev (the plug-in's tf/transform_broadcaster.h); without them it says so and stops. The scratch workspace
# goes to /tmp.
# robot.launch.xml's nodelet manager is not provided (roslaunch names it and goes on): nothing of the checks uses it.
set -u

if [ $# -lt 1 ]; then
  sed -n '2,21p' "$0"
  exit 2
fi
MIRROR=$(realpath "$1")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TOOL=kobuki
# shellcheck source=tools/mirror_ws.sh
source "$ROOT/tools/mirror_ws.sh"
require_debs "kobuki_description and kobuki_gazebo_plugins" urdf/model.h:liburdf-dev \
  tf/transform_broadcaster.h:libtf-dev
mirror_ws_begin

export_from yujinrobot+kobuki_desktop melodic "$SRC" kobuki_gazebo kobuki_gazebo_plugins
export_from yujinrobot+kobuki melodic "$SRC" kobuki_description
export_from yujinrobot+kobuki_msgs noetic "$SRC/kobuki_msgs" .
cat "$WS/sources.txt" "$WS/absent.txt" 2> /dev/null
mirror_ws_build

status=0
run_beside kobuki /usr/bin/python3 "$ROOT/tools/kobuki_probe.py" -- kobuki_gazebo kobuki_empty_world.launch || status=1
echo
cat "$WS/results-kobuki.txt"
tail -3 "$WS/probe-kobuki.log"
echo "kobuki: logs in $WS"
exit $status
