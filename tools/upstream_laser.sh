#!/usr/bin/env bash
# Builds upstream gazebo_plugins' laser plug-in (gazebo_ros_pkgs noetic-devel, src/gazebo_ros_laser.cpp: a RayPlugin
# that subscribes to its ray sensor's Gazebo topic and publishes sensor_msgs/LaserScan) unchanged against car's
# Gazebo 11 API (RayPlugin, RaySensor::Topic, msgs::LaserScanStamped on car's transport) and car's gazebo_plugins
# drop-in, then runs the tutorial's car with its lidar twice with the same commands, once with car's laser kind and
# once with the library (CAR_UPSTREAM_PLUGINS), and compares every /scan stamped in [1, 2] s of sim time
# (tools/upstream_laser_probe.py). docs/PLUGINS.md "Sensor plug-in bases" has the last run. Not in CI.
#
#   tools/upstream_laser.sh GZ_SNAPSHOT
#
# GZ_SNAPSHOT: a checkout of gazebo_ros_pkgs (a folder holding gazebo_plugins/) or a git directory of it (its
# noetic-devel branch is exported). Needs car's workspace built and sourced, and Debian's libtf-dev (the plug-in's
# tf/tf.h).
set -u
if [ $# -ne 1 ]; then sed -n '2,14p' "$0"; exit 2; fi
SNAP=$(realpath "$1")
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TOOL=upstream_laser
# shellcheck source=tools/mirror_ws.sh
source "$ROOT/tools/mirror_ws.sh"
require_debs gazebo_ros_laser.cpp tf/tf.h:libtf-dev
mirror_ws_begin
UP=$WS/upstream
mkdir -p "$UP"
if [ -d "$SNAP/gazebo_plugins/src" ]; then
  cp -r "$SNAP/gazebo_plugins" "$UP/"
  echo "gazebo_ros_pkgs @ $(git -C "$SNAP" rev-parse --short HEAD 2> /dev/null || echo "a checkout")"
else
  git --git-dir="$SNAP" archive noetic-devel gazebo_plugins/src/gazebo_ros_laser.cpp gazebo_plugins/include \
    | tar -x -C "$UP" || { echo "upstream_laser: cannot export noetic-devel from $SNAP" >&2; exit 2; }
  echo "gazebo_ros_pkgs noetic-devel @ $(git --git-dir="$SNAP" rev-parse --short noetic-devel)"
fi
mkdir -p "$SRC/car_upstream_laser"
cat > "$SRC/car_upstream_laser/package.xml" << 'XML'
<?xml version="1.0"?>
<package format="2"><name>car_upstream_laser</name><version>0.0.0</version>
  <description>upstream gazebo_ros_laser built unchanged against car (tools/upstream_laser.sh)</description>
  <maintainer email="car@example.invalid">car</maintainer><license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend><depend>gazebo_plugins</depend></package>
XML
# as gazebo_plugins' own CMakeLists builds it: the laser links RayPlugin from GAZEBO_LIBRARY_DIRS
cat > "$SRC/car_upstream_laser/CMakeLists.txt" << CMAKE
cmake_minimum_required(VERSION 3.16)
project(car_upstream_laser)
find_package(catkin REQUIRED COMPONENTS gazebo_dev gazebo_plugins roscpp tf sensor_msgs)
find_package(gazebo REQUIRED)
catkin_package()
include_directories(\${catkin_INCLUDE_DIRS} $UP/gazebo_plugins/include)
link_directories(\${GAZEBO_LIBRARY_DIRS})
set(CMAKE_CXX_FLAGS "\${CMAKE_CXX_FLAGS} \${GAZEBO_CXX_FLAGS}")
add_library(gazebo_ros_laser SHARED $UP/gazebo_plugins/src/gazebo_ros_laser.cpp)
target_link_libraries(gazebo_ros_laser \${catkin_LIBRARIES} \${GAZEBO_LIBRARIES} RayPlugin)
CMAKE
mirror_ws_build
echo "upstream_laser: built unchanged: libgazebo_ros_laser.so"

status=0
for mode in native upstream; do
  if [ $mode = upstream ]; then
    export CAR_UPSTREAM_PLUGINS=libgazebo_ros_laser.so GAZEBO_PLUGIN_PATH=$WS/devel/lib
  else
    unset CAR_UPSTREAM_PLUGINS GAZEBO_PLUGIN_PATH
  fi
  run_beside "$mode" /usr/bin/python3 "$ROOT/tools/upstream_laser_probe.py" "$WS/$mode.json" -- \
    car empty_world.launch paused:=true world_name:="$(rospack find car)/worlds/box_house.world" \
    || { status=1; echo "upstream_laser: $mode: the probe failed ($WS/probe-$mode.log)"; }
done
unset CAR_UPSTREAM_PLUGINS GAZEBO_PLUGIN_PATH
grep -h "gazebo_rplidar" "$WS/launch-upstream.log" | sed 's/^.*\] //' | head -2
/usr/bin/python3 - "$WS/native.json" "$WS/upstream.json" << 'PY' || status=1
import json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
print("native %d scans, upstream %d scans, stamps %s" % (len(a), len(b), "equal" if [x["stamp"] for x in a] == [y["stamp"] for y in b] else "DIFFER"))
same = lambda p, q: p == q or (math.isnan(p) and math.isnan(q))
ok = len(a) == len(b) and len(a) > 0
for x, y in zip(a, b):
    meta = [k for k in x if k not in ("ranges", "intensities") and x[k] != y[k]]
    bits = len(x["ranges"]) == len(y["ranges"]) and all(same(p, q) for p, q in zip(x["ranges"], y["ranges"]))
    inten = x["intensities"] == y["intensities"]
    if meta or not bits or not inten:
        ok = False
        print("scan at %d.%09d: differs in %s%s%s" % (x["stamp"][0], x["stamp"][1], meta, "" if bits else " ranges",
                                                     "" if inten else " intensities"))
print("every /scan field equal, bit for bit" if ok else "upstream_laser: the scans differ")
sys.exit(0 if ok else 1)
PY
echo "upstream_laser: logs in $WS"
exit $status
