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
# Needs car's workspace built and sourced (source .ws/devel/setup.bash). The scratch workspace goes to /tmp.
# The launch file's rqt_joint_trajectory_controller (a GUI, not packaged by Debian) does not start: roslaunch names
# it and goes on; the probe commands the controller instead.
set -u

if [ $# -lt 1 ]; then
  sed -n '2,20p' "$0"
  exit 2
fi
MIRROR=$(realpath "$1")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
if [ -z "${CMAKE_PREFIX_PATH:-}" ] || ! rospack find car > /dev/null 2>&1; then
  echo "mimic: source car's workspace first (source $ROOT/.ws/devel/setup.bash)" >&2
  exit 2
fi
WS=$(mktemp -d /tmp/car_mimic.XXXXXX)
mkdir -p "$WS/src"
echo "mimic: workspace $WS"

# export_from OWNER+NAME: its default branch into WS/src/NAME
export_from() {
  local d=$MIRROR/$1 gitdir
  if [ -d "$d/repo" ]; then gitdir=$d/repo; elif [ -d "$d/.git" ]; then gitdir=$d/.git; else gitdir=$d; fi
  git --git-dir="$gitdir" archive --prefix="${1#*+}/" HEAD | tar -x -C "$WS/src" || {
    echo "mimic: cannot read $gitdir" >&2
    exit 2
  }
  echo "$1 @ $(git --git-dir="$gitdir" rev-parse --short HEAD) ($(git --git-dir="$gitdir" symbolic-ref --short HEAD))" \
    >> "$WS/sources.txt"
}
export_from mintar+mimic_joint_gazebo_tutorial
export_from roboticsgroup+roboticsgroup_gazebo_plugins
export_from roboticsgroup+roboticsgroup_upatras_gazebo_plugins
cat "$WS/sources.txt"
if ! (cd "$WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -j2 > "$WS/build.log" 2>&1); then
  echo "mimic: the scratch workspace did not build; the first errors ($WS/build.log):" >&2
  grep -m 10 -E "error|Error" "$WS/build.log" >&2
  exit 1
fi
echo "mimic: built unchanged: $(cd "$WS/devel/lib" && ls lib*.so | tr '\n' ' ')"
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"

# run LABEL PROBE_ARG: the tutorial's gazebo.launch with a fresh master, the probe beside it
status=0
run() {
  local port=$((11400 + RANDOM % 400)) core probe rl
  export ROS_MASTER_URI=http://localhost:$port
  roscore -p "$port" > "$WS/roscore-$1.log" 2>&1 &
  core=$!
  sleep 3
  rosparam set /use_sim_time true
  /usr/bin/python3 "$ROOT/tools/mimic_probe.py" "$2" > "$WS/results-$1.txt" 2> "$WS/probe-$1.log" &
  probe=$!
  roslaunch mimic_joint_gazebo_tutorial gazebo.launch > "$WS/launch-$1.log" 2>&1 &
  rl=$!
  wait "$probe" || status=1
  kill -INT "$rl" 2> /dev/null
  wait "$rl" 2> /dev/null
  kill -INT "$core" 2> /dev/null
  wait "$core" 2> /dev/null
  echo
  echo "== $1"
  grep -h "MimicJointPlugin loaded" "$WS/launch-$1.log" | sed 's/^.*\] //'
  cat "$WS/results-$1.txt"
  tail -n 3 "$WS/probe-$1.log"
}
run "as published (hasPID, roboticsgroup_gazebo_plugins)" pid
# the README's edit: has_pid="false"; and the maintained package's library
sed -i -e 's/has_pid="true"/has_pid="false"/' -e 's/libroboticsgroup_gazebo_mimic_joint_plugin/libroboticsgroup_upatras_gazebo_mimic_joint_plugin/' \
  "$WS/src/mimic_joint_gazebo_tutorial/urdf/mimic_joint_gazebo_tutorial.urdf.xacro"
run "README's edit: has_pid false (SetPosition each step), roboticsgroup_upatras_gazebo_plugins" nopid
echo "mimic: logs in $WS"
exit $status
