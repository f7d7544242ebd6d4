#!/usr/bin/env bash
# Builds upstream gazebo_plugins' model plug-ins (gazebo_ros_pkgs noetic-devel) from their sources, unchanged, against
# car's Gazebo 11 API and car's gazebo_plugins drop-in (gazebo_ros_utils.h, PubQueue.h), then runs each on a test
# robot of car/test/data twice, as car's native kind and as the upstream library (CAR_UPSTREAM_PLUGINS), with the
# same commands, and compares what comes out: topics, services, frames, TF edges, and the trajectories within a
# tolerance derived per plug-in (below). Prints a table. Not in CI (CI has no snapshot of upstream). The table of the
# last run is in docs/PLUGINS.md "Upstream gazebo_plugins built unchanged".
#
#   tools/upstream_plugins.sh GZ_SNAPSHOT [PLUGIN ...]
#
# GZ_SNAPSHOT: a checkout of gazebo_ros_pkgs (a folder holding gazebo_plugins/) or a git directory of it (its
# noetic-devel branch is exported). PLUGIN: names from the list below (default: all). Needs car's workspace built
# and sourced (source .ws/devel/setup.bash), and Debian's libtf-dev (tf/transform_broadcaster.h) and
# libignition-common-core-dev (ignition/common/Profiler.hh, which Gazebo 11 exports and car's find_package(gazebo)
# adds where installed); without them it says so and stops.
#
# How it stays unedited: a throw-away catkin workspace holds a package of ours, car_upstream_plugins, whose
# CMakeLists compiles upstream's src/gazebo_ros_NAME.cpp files with upstream's include/ folder after car's (so that
# car's gazebo_plugins/gazebo_ros_utils.h and PubQueue.h are the ones used, as a Gazebo user's build would take
# gazebo_plugins' installed headers) into libgazebo_ros_NAME.so. Each plug-in is built as its own target: one that
# does not build is reported with its first compiler error (the API car lacks), and the others go on.
set -u

PLUGINS_ALL="diff_drive skid_steer_drive planar_move tricycle_drive p3d f3d force joint_state_publisher
joint_pose_trajectory template vacuum_gripper hand_of_god"
if [ $# -lt 1 ]; then
  sed -n '2,24p' "$0"
  exit 2
fi
SNAP=$(realpath "$1")
shift
PLUGINS=${*:-$PLUGINS_ALL}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
if [ -z "${CMAKE_PREFIX_PATH:-}" ] || ! rospack find car > /dev/null 2>&1; then
  echo "upstream_plugins: source car's workspace first (source $ROOT/.ws/devel/setup.bash)" >&2
  exit 2
fi
missing=""
[ -f /usr/include/tf/transform_broadcaster.h ] || missing+=" libtf-dev"
[ -f /usr/include/ignition/common4/ignition/common/Profiler.hh ] || missing+=" libignition-common-core-dev"
if [ -n "$missing" ]; then
  echo "upstream_plugins: upstream's sources include headers of Debian packages that are not installed:$missing" >&2
  echo "upstream_plugins: apt-get install$missing" >&2
  exit 2
fi
# UPSTREAM_PLUGINS_WS: a workspace of an earlier run to run again (its libraries are rebuilt only where changed)
WS=${UPSTREAM_PLUGINS_WS:-$(mktemp -d /tmp/car_upstream_plugins.XXXXXX)}
echo "upstream_plugins: workspace $WS"

# ---- upstream's sources --------------------------------------------------------------------------------------
if [ -d "$SNAP/gazebo_plugins/src" ]; then
  UP=$SNAP
  COMMIT=$(git -C "$SNAP" rev-parse HEAD 2> /dev/null || echo "a checkout")
else
  UP=$WS/upstream
  rm -rf "$UP"
  mkdir -p "$UP"
  git --git-dir="$SNAP" archive noetic-devel gazebo_plugins/src gazebo_plugins/include | tar -x -C "$UP" \
    || { echo "upstream_plugins: cannot export noetic-devel from $SNAP" >&2; exit 2; }
  COMMIT=$(git --git-dir="$SNAP" rev-parse noetic-devel)
fi
echo "upstream_plugins: gazebo_ros_pkgs noetic-devel $COMMIT"

# ---- the package that builds them -----------------------------------------------------------------------------
PKG=$WS/src/car_upstream_plugins
mkdir -p "$PKG"
cat > "$PKG/package.xml" <<'XML'
<?xml version="1.0"?>
<package format="2">
  <name>car_upstream_plugins</name>
  <version>0.0.0</version>
  <description>upstream gazebo_plugins' model plug-ins built unchanged against car (tools/upstream_plugins.sh)</description>
  <maintainer email="car@example.invalid">car</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <depend>gazebo_plugins</depend>
</package>
XML
cat > "$PKG/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.16)
project(car_upstream_plugins)
find_package(catkin REQUIRED COMPONENTS gazebo_dev gazebo_plugins gazebo_msgs roscpp tf tf2_ros nav_msgs
  geometry_msgs sensor_msgs std_msgs std_srvs trajectory_msgs)
catkin_package()
# car's folders first, upstream's include/ (the plug-ins' own headers) after them
include_directories(\${catkin_INCLUDE_DIRS} $UP/gazebo_plugins/include)
set(CMAKE_CXX_FLAGS "\${CMAKE_CXX_FLAGS} \${GAZEBO_CXX_FLAGS}")
# Boost 1.74 (Debian 12) keeps bind's _1 out of the global namespace unless asked (Ubuntu 20.04's 1.71 did not)
add_compile_definitions(BOOST_BIND_GLOBAL_PLACEHOLDERS)
add_compile_options(-include boost/bind.hpp)
foreach(p $(echo $PLUGINS_ALL))
  add_library(gazebo_ros_\${p} SHARED EXCLUDE_FROM_ALL $UP/gazebo_plugins/src/gazebo_ros_\${p}.cpp)
  target_link_libraries(gazebo_ros_\${p} \${catkin_LIBRARIES})
  set_target_properties(gazebo_ros_\${p} PROPERTIES LIBRARY_OUTPUT_DIRECTORY \${CATKIN_DEVEL_PREFIX}/lib)
endforeach()
CMAKE
(cd "$WS" && catkin_make -j2 > "$WS/configure.log" 2>&1) \
  || { echo "upstream_plugins: the workspace does not configure (see $WS/configure.log)" >&2; exit 1; }

declare -A BUILT WHY
for p in $PLUGINS; do
  if make -C "$WS/build" "gazebo_ros_$p" -j2 > "$WS/build_$p.log" 2>&1; then
    BUILT[$p]=yes
  else
    BUILT[$p]=no
    WHY[$p]=$(grep -m1 -E "error:" "$WS/build_$p.log" | sed -e "s|$UP/||" -e 's/^[^ ]*: error: //' | cut -c1-150)
  fi
done

# ---- each one on its robot, as car's kind and as the library ------------------------------------------------------
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"
PROBE=$ROOT/tools/upstream_plugins_probe.py
port=11611
run() {  # plug-in, mode (native|upstream): writes $WS/$1.$2.json and the node's log
  local p=$1 mode=$2 upstream=""
  [ "$mode" = upstream ] && upstream="libgazebo_ros_$p.so"
  port=$((port + 1))
  export ROS_MASTER_URI=http://localhost:$port
  # roslaunch starts the master on its own port (and ends it)
  CAR_UPSTREAM_PLUGINS=$upstream roslaunch -p "$port" car empty_world.launch rtf:=0 paused:=true \
    > "$WS/$p.$mode.node.log" 2>&1 &
  local node=$!
  timeout 900 /usr/bin/python3 "$PROBE" "$p" "$WS/$p.$mode.json" > "$WS/$p.$mode.probe.log" 2>&1
  local rc=$?
  kill -INT "$node" 2> /dev/null; wait "$node" 2> /dev/null
  return $rc
}
for p in $PLUGINS; do
  [ "${BUILT[$p]}" = yes ] || continue
  run "$p" native || echo "upstream_plugins: $p as car's kind: the probe failed ($WS/$p.native.probe.log)"
  run "$p" upstream || echo "upstream_plugins: $p from its library: the probe failed ($WS/$p.upstream.probe.log)"
done

# ---- the table ----------------------------------------------------------------------------------------------------
for p in $PLUGINS; do echo "$p|${BUILT[$p]}|${WHY[$p]:-}"; done > "$WS/built.txt"
echo
/usr/bin/python3 "$ROOT/tools/upstream_plugins_table.py" "$WS" $PLUGINS
