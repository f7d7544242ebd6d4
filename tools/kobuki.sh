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
if [ -z "${CMAKE_PREFIX_PATH:-}" ] || ! rospack find car > /dev/null 2>&1; then
  echo "kobuki: source car's workspace first (source $ROOT/.ws/devel/setup.bash)" >&2
  exit 2
fi
missing=""
[ -f /usr/include/urdf/model.h ] || missing+=" liburdf-dev"
[ -f /usr/include/tf/transform_broadcaster.h ] || missing+=" libtf-dev"
if [ -n "$missing" ]; then
  echo "kobuki: kobuki_description and kobuki_gazebo_plugins need Debian packages that are not installed:$missing" >&2
  echo "kobuki: apt-get install$missing" >&2
  exit 2
fi
WS=$(mktemp -d /tmp/car_kobuki.XXXXXX)
SRC=$WS/src
mkdir -p "$SRC"
echo "kobuki: workspace $WS"

# export_from OWNER+NAME BRANCH DEST PATH...: the files under PATH at BRANCH into DEST (as tools/real_robots.sh)
export_from() {
  local name=$1 branch=$2 dest=$3
  shift 3
  local d=$MIRROR/$name gitdir mode type sha path
  if [ -d "$d/repo" ]; then gitdir=$d/repo; elif [ -d "$d/.git" ]; then gitdir=$d/.git; else gitdir=$d; fi
  if ! git --git-dir="$gitdir" rev-parse -q --verify "$branch^{commit}" > /dev/null; then
    echo "kobuki: $gitdir has no branch $branch" >&2
    exit 2
  fi
  while IFS=$'\t' read -r meta path; do
    read -r mode type sha <<< "$meta"
    [ "$type" = blob ] || continue
    mkdir -p "$dest/$(dirname "$path")"
    if ! git --git-dir="$gitdir" cat-file blob "$sha" > "$dest/$path" 2> /dev/null; then
      rm -f "$dest/$path"
      echo "$name: $path absent from the snapshot" >> "$WS/absent.txt"
    fi
    [ "$mode" = 100755 ] && [ -f "$dest/$path" ] && chmod +x "$dest/$path"
  done < <(git --git-dir="$gitdir" ls-tree -r "$branch" -- "$@")
  echo "$name @ $(git --git-dir="$gitdir" rev-parse --short "$branch") ($branch)" >> "$WS/sources.txt"
}

export_from yujinrobot+kobuki_desktop melodic "$SRC" kobuki_gazebo kobuki_gazebo_plugins
export_from yujinrobot+kobuki melodic "$SRC" kobuki_description
export_from yujinrobot+kobuki_msgs noetic "$SRC/kobuki_msgs" .
cat "$WS/sources.txt" "$WS/absent.txt" 2> /dev/null

if ! (cd "$WS" && catkin_make -j2 > "$WS/build.log" 2>&1); then
  echo "kobuki: the scratch workspace did not build; the first errors ($WS/build.log):" >&2
  grep -m 10 -E "error|Error" "$WS/build.log" >&2
  exit 1
fi
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"

port=$((11400 + RANDOM % 400))
export ROS_MASTER_URI=http://localhost:$port
roscore -p "$port" > "$WS/roscore.log" 2>&1 &
core=$!
sleep 3
rosparam set /use_sim_time true
/usr/bin/python3 "$ROOT/tools/kobuki_probe.py" > "$WS/results.txt" 2> "$WS/probe.log" &
probe=$!
sleep 2
roslaunch kobuki_gazebo kobuki_empty_world.launch > "$WS/launch.log" 2>&1 &
rl=$!
status=0
wait "$probe" || status=1
kill -INT "$rl" 2> /dev/null
wait "$rl" 2> /dev/null
kill -INT "$core" 2> /dev/null
wait "$core" 2> /dev/null
echo
cat "$WS/results.txt"
tail -3 "$WS/probe.log"
echo "kobuki: logs in $WS"
exit $status
