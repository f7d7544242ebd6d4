#!/usr/bin/env bash
# Runs gazebo_ros_pkgs' (noetic-devel) own tests from gazebo_ros/test and gazebo_plugins/test against car's
# drop-ins, with no edit to any upstream file, and prints a table (test, result). Not in CI: CI has no network to
# fetch the snapshot. docs/COMPAT.md "Upstream's own tests" has the table of the last run.
#
#   tools/upstream_tests.sh GZ_SNAPSHOT [TEST ...]
#
# GZ_SNAPSHOT: a checkout of gazebo_ros_pkgs (a folder holding gazebo_ros/ and gazebo_plugins/), or a git
# directory of it (its noetic-devel branch is exported). TEST: test names from the list below (default: all).
# Needs car's workspace built and sourced (source .ws/devel/setup.bash). The C++ tests build against
# image_transport, cv_bridge, OpenCV and tf (Debian: libimage-transport-dev libcv-bridge-dev libopencv-dev
# libtf-dev); without them those tests are reported as "not built" and the others still run.
#
# How it stays unedited: a throw-away catkin workspace overlays two packages named as upstream's,
#   gazebo_plugins: upstream's test/ folder (a link) and a CMakeLists of ours that builds upstream's test sources
#                   as the executables the .test files name (camera-test, ...);
#   gazebo_ros:     car's compat launch files (a link) and upstream's test/ folder (a link), with a forwarder for
#                   upstream's ros_api_checker (its shebang names `python`, which Debian 12 lacks);
# and rostest runs upstream's .test files from those folders.
set -u

if [ $# -lt 1 ]; then
  sed -n '2,12p' "$0"
  exit 2
fi
SNAP=$(realpath "$1")
shift
ROOT=$(cd "$(dirname "$0")/.." && pwd)
if [ -z "${CMAKE_PREFIX_PATH:-}" ] || ! rospack find car > /dev/null 2>&1; then
  echo "upstream_tests: source car's workspace first (source $ROOT/.ws/devel/setup.bash)" >&2
  exit 2
fi
WS=$(mktemp -d /tmp/car_upstream.XXXXXX)
echo "upstream_tests: workspace $WS"

# ---- upstream's files ----------------------------------------------------------------------------------------
if [ -d "$SNAP/gazebo_plugins/test" ]; then
  UP=$SNAP
else
  UP=$WS/upstream
  mkdir -p "$UP"
  git --git-dir="$SNAP" archive noetic-devel gazebo_ros/test gazebo_plugins/test gazebo_ros/package.xml \
    gazebo_plugins/package.xml gazebo_plugins/scripts \
    | tar -x -C "$UP" || { echo "upstream_tests: cannot export noetic-devel from $SNAP" >&2; exit 2; }
fi

# ---- the overlay packages ------------------------------------------------------------------------------------
COMPAT_ROS=$(rospack find gazebo_ros)
# car's gazebo_ros executables (gzserver, spawn_model, ...): the overlay's lib/gazebo_ros links them, because
# roslaunch looks for a package's executables only in the first workspace that has its lib folder
COMPAT_ROS_LIB=$(dirname "$(catkin_find --libexec gazebo_ros gzserver | head -1)")
mkdir -p "$WS/src/gazebo_plugins" "$WS/src/gazebo_ros"
ln -s "$UP/gazebo_plugins/test" "$WS/src/gazebo_plugins/test"
ln -s "$UP/gazebo_ros/test" "$WS/src/gazebo_ros/test"
ln -s "$COMPAT_ROS/launch" "$WS/src/gazebo_ros/launch"
cp "$COMPAT_ROS/package.xml" "$WS/src/gazebo_ros/package.xml"
cat > "$WS/src/gazebo_ros/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(gazebo_ros)
find_package(catkin REQUIRED)
catkin_package()
EOF
cat > "$WS/src/gazebo_plugins/package.xml" <<'EOF'
<?xml version="1.0"?>
<package format="2">
  <name>gazebo_plugins</name>
  <version>2.9.2</version>
  <description>car's overlay that builds gazebo_ros_pkgs' own gazebo_plugins tests (tools/upstream_tests.sh)</description>
  <maintainer email="car@example.invalid">car</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <depend>roscpp</depend>
  <depend>gazebo_msgs</depend>
</package>
EOF
cat > "$WS/src/gazebo_plugins/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(gazebo_plugins)
find_package(catkin REQUIRED COMPONENTS roscpp std_msgs sensor_msgs gazebo_msgs message_filters)
catkin_package()
# the image and tf packages are optional: without them the tests that need them are not built
foreach(p image_transport cv_bridge tf)
  find_package(${p} QUIET)
endforeach()
find_package(OpenCV QUIET)
include_directories(${catkin_INCLUDE_DIRS} ${image_transport_INCLUDE_DIRS} ${cv_bridge_INCLUDE_DIRS} ${tf_INCLUDE_DIRS}
  ${OpenCV_INCLUDE_DIRS})
set(UPSTREAM_LIBS ${catkin_LIBRARIES} ${image_transport_LIBRARIES} ${cv_bridge_LIBRARIES} ${tf_LIBRARIES} ${OpenCV_LIBRARIES})
# Boost 1.74 (Debian 12) keeps bind's _1, _2 out of the global namespace unless asked; Ubuntu 20.04's Boost 1.71
# put them there, and upstream's multicamera and distortion tests use them unqualified
add_compile_definitions(BOOST_BIND_GLOBAL_PLACEHOLDERS)
add_compile_options(-include boost/bind.hpp)
# name -> source, as upstream's CMakeLists names them
macro(upstream_test name src)
  catkin_add_executable_with_gtest(${name} ${src})
  if(TARGET ${name})
    target_link_libraries(${name} ${UPSTREAM_LIBS})
  endif()
endmacro()
if(tf_FOUND)
  upstream_test(set_model_state-test test/set_model_state_test/set_model_state_test.cpp)
endif()
if(image_transport_FOUND)
  upstream_test(camera-test test/camera/camera.cpp)
  upstream_test(camera16bit-test test/camera/camera16bit.cpp)
  upstream_test(depth_camera-test test/camera/depth_camera.cpp)
  upstream_test(triggered-camera-test test/camera/triggered_camera.cpp)
  upstream_test(multicamera-test test/camera/multicamera.cpp)
  if(cv_bridge_FOUND AND OpenCV_FOUND)
    upstream_test(distortion_barrel_test test/camera/distortion_barrel.cpp)
    upstream_test(distortion_pincushion_test test/camera/distortion_pincushion.cpp)
  endif()
endif()
EOF
(cd "$WS" && catkin_make -j2 -k > "$WS/build.log" 2>&1) || echo "upstream_tests: the overlay did not build fully (see $WS/build.log)"
# upstream's ros_api_checker (the file itself is not touched), run by python3 with Ubuntu 20.04's PyYAML 5
# semantics: it calls yaml.load(f) without a Loader, which PyYAML 6 (Debian 12) refuses
mkdir -p "$WS/devel/lib/gazebo_ros"
for exe in "$COMPAT_ROS_LIB"/*; do
  [ -x "$exe" ] && [ -f "$exe" ] && ln -sf "$exe" "$WS/devel/lib/gazebo_ros/$(basename "$exe")"
done
cat > "$WS/devel/lib/gazebo_ros/ros_api_checker" <<SHIM
#!/usr/bin/env python3
import runpy, sys, yaml
_load = yaml.load
yaml.load = lambda stream, Loader=yaml.SafeLoader: _load(stream, Loader)
sys.argv[0] = "$UP/gazebo_ros/test/ros_network/ros_api_checker"
runpy.run_path(sys.argv[0], run_name="__main__")
SHIM
chmod +x "$WS/devel/lib/gazebo_ros/ros_api_checker"
# upstream's Python test nodes (gazebo_plugins/scripts/test_*.py), run by python3: their shebang names `python`
mkdir -p "$WS/devel/lib/gazebo_plugins"
for script in test_range.py test_block_laser_clipping.py; do
  printf '#!/bin/sh\nexec python3 %s "$@"\n' "$UP/gazebo_plugins/scripts/$script" > "$WS/devel/lib/gazebo_plugins/$script"
  chmod +x "$WS/devel/lib/gazebo_plugins/$script"
done
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"

# ---- the tests ------------------------------------------------------------------------------------------------
# name | .test file | executable it needs in gazebo_plugins ("" = none)
TESTS="
api_on|gazebo_ros/test/ros_network/ros_network_default.test|
api_off|gazebo_ros/test/ros_network/ros_network_disabled.test|
range|gazebo_plugins/test/range/range_plugin.test|
block_laser_clipping|gazebo_plugins/test/block_laser_clipping.test|
set_model_state|gazebo_plugins/test/set_model_state_test/set_model_state_test.test|set_model_state-test
camera|gazebo_plugins/test/camera/camera.test|camera-test
camera16bit|gazebo_plugins/test/camera/camera16bit.test|camera16bit-test
depth_camera|gazebo_plugins/test/camera/depth_camera.test|depth_camera-test
multicamera|gazebo_plugins/test/camera/multicamera.test|multicamera-test
triggered_camera|gazebo_plugins/test/camera/triggered_camera.test|triggered-camera-test
distortion_barrel|gazebo_plugins/test/camera/distortion_barrel.test|distortion_barrel_test
distortion_pincushion|gazebo_plugins/test/camera/distortion_pincushion.test|distortion_pincushion_test
"
want=" $* "
results=""
pass=0
total=0
while IFS='|' read -r name file exe; do
  [ -z "$name" ] && continue
  if [ $# -gt 0 ] && [[ "$want" != *" $name "* ]]; then continue; fi
  total=$((total + 1))
  pkg=${file%%/*}
  rel=${file#*/}
  if [ -n "$exe" ] && [ ! -x "$WS/devel/lib/gazebo_plugins/$exe" ]; then
    results+="$name|not built (missing build dependencies, $WS/build.log)"$'\n'
    continue
  fi
  log="$WS/$name.log"
  if timeout 600 rostest "$WS/src/$pkg/$rel" > "$log" 2>&1 && grep -q "SUMMARY" "$log" && grep -q "\* RESULT: SUCCESS" "$log"; then
    results+="$name|passed"$'\n'
    pass=$((pass + 1))
  else
    why=$(grep -m1 -E "AssertionError|Failure|FAILURE|ERROR|error" "$log" | cut -c1-120)
    results+="$name|FAILED ($log${why:+: $why})"$'\n'
  fi
done <<< "$TESTS"

echo
printf '%-24s %s\n' "test" "result"
printf '%s' "$results" | while IFS='|' read -r n r; do printf '%-24s %s\n' "$n" "$r"; done
echo "upstream_tests: $pass of $total passed (logs in $WS)"
[ "$pass" -eq "$total" ]
