#!/usr/bin/env bash
# A gripper's mimic joints, from their own Gazebo plug-in built UNCHANGED against car's Gazebo API and car's
# control_toolbox drop-in (docs/PLUGINS.md "Mimic joints"): mintar's mimic_joint_gazebo_tutorial launched as its
# README says, with roboticsgroup's MimicJointPlugin (the library its URDF names), then with the edit its README
# suggests (has_pid="false": the plug-in sets the joint's position each step) on the maintained
# roboticsgroup_upatras_gazebo_plugins. tools/mimic_probe.py moves the right finger through the tutorial's
# gripper_controller and checks that the left one follows. Fetches nothing; not in CI.
#
#   tools/mimic.sh MIRROR_DIR
#
# MIRROR_DIR holds one folder per repository, named OWNER+NAME, each a git directory, a folder with a git directory
# `repo`, or a checkout (their default branches are read):
#   mintar+mimic_joint_gazebo_tutorial (kinetic)          the tutorial: URDF, launch file, controller YAML
#   roboticsgroup+roboticsgroup_gazebo_plugins (master)   libroboticsgroup_gazebo_mimic_joint_plugin.so
#   roboticsgroup+roboticsgroup_upatras_gazebo_plugins (master)  libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so
# Needs car's workspace built and sourced (source .ws/devel/setup.bash). The scratch workspace goes to /tmp. Runs:
# "published" (the tutorial as published: <hasPID/>, roboticsgroup_gazebo_plugins) and "readme_edit" (has_pid="false":
# SetPosition each step, on roboticsgroup_upatras_gazebo_plugins).
# The launch file's rqt_joint_trajectory_controller (a GUI, not packaged by Debian) does not start: roslaunch names
# it and goes on; the probe commands the controller instead.
set -u

if [ $# -lt 1 ]; then
  sed -n '2,20p' "$0"
  exit 2
fi
MIRROR=$(realpath "$1")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TOOL=mimic
# shellcheck source=tools/mirror_ws.sh
source "$ROOT/tools/mirror_ws.sh"
mirror_ws_begin
export_from mintar+mimic_joint_gazebo_tutorial HEAD "$SRC/mimic_joint_gazebo_tutorial" .
export_from roboticsgroup+roboticsgroup_gazebo_plugins HEAD "$SRC/roboticsgroup_gazebo_plugins" .
export_from roboticsgroup+roboticsgroup_upatras_gazebo_plugins HEAD "$SRC/roboticsgroup_upatras_gazebo_plugins" .
cat "$WS/sources.txt" "$WS/absent.txt" 2> /dev/null
mirror_ws_build
echo "mimic: built unchanged: $(cd "$WS/devel/lib" && ls lib*.so | tr '\n' ' ')"

# run LABEL PROBE_ARG: the tutorial's gazebo.launch, the probe beside it, and what they printed
status=0
run() {
  run_beside "$1" /usr/bin/python3 "$ROOT/tools/mimic_probe.py" "$2" -- mimic_joint_gazebo_tutorial gazebo.launch \
    || status=1
  echo
  echo "== $1"
  grep -h "MimicJointPlugin loaded" "$WS/launch-$1.log" | sed 's/^.*\] //'
  cat "$WS/results-$1.txt"
  tail -n 3 "$WS/probe-$1.log"
}
run published pid
# the README's edit: has_pid="false"; and the maintained package's library
sed -i -e 's/has_pid="true"/has_pid="false"/' \
  -e 's/libroboticsgroup_gazebo_mimic_joint_plugin/libroboticsgroup_upatras_gazebo_mimic_joint_plugin/' \
  "$SRC/mimic_joint_gazebo_tutorial/urdf/mimic_joint_gazebo_tutorial.urdf.xacro"
run readme_edit nopid
echo "mimic: logs in $WS"
exit $status
