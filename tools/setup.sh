#!/usr/bin/env bash
# Idempotent set-up on Debian 12: Debian's ROS packages, a venv with car's PyPI dependencies, and a catkin
# workspace in .ws/ (git-ignored) whose src/ links car/, the compat/ drop-ins and the fixtures' packages.
# Re-running with everything in place only rebuilds what changed.
# Usage: tools/setup.sh [--deps-only]
#   --deps-only  only the Debian packages and the venv (.venv/), for a clone inside a workspace of your own
#                (README "Your own catkin workspace"); then catkin_make there.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
deps_only=0
for a in "$@"; do
  case "$a" in
    --deps-only) deps_only=1 ;;
    *) echo "setup: unknown option $a (usage: tools/setup.sh [--deps-only])" >&2; exit 2 ;;
  esac
done

DEB_PACKAGES=(
  build-essential cmake pkg-config catkin python3-catkin-pkg python3-venv python3-pip python3-dev python3-numpy python3-yaml
  python3-matplotlib python3-tqdm
  ros-core-dev ros-base-dev libroscpp-dev python3-rospy python3-roslaunch python3-rostest python3-rosgraph
  python3-rospkg python3-roslib python3-rosbag
  liburdfdom-dev liburdfdom-headers-dev libconsole-bridge-dev libtinyxml2-dev libtinyxml-dev libeigen3-dev pybind11-dev
  libbullet-dev libsdformat-dev libembree-dev libassimp-dev libignition-math-dev libboost-dev
  libtf2-ros-dev python3-tf2-ros libsensor-msgs-dev python3-sensor-msgs libnav-msgs-dev python3-nav-msgs
  libgeometry-msgs-dev python3-geometry-msgs libstd-srvs-dev python3-std-srvs libros-rosgraph-msgs-dev python3-rosgraph-msgs
  ros-message-generation ros-message-runtime python3-tf2-msgs libtf2-msgs-dev
  libvisualization-msgs-dev python3-visualization-msgs
  libtrajectory-msgs-dev python3-trajectory-msgs python3-genmsg python3-rosservice python3-rosnode
  libactionlib-dev python3-actionlib libactionlib-msgs-dev python3-actionlib-msgs ros-actionlib-msgs
  python3-rosparam libstd-msgs-dev python3-std-msgs
  ros-robot-state-publisher joint-state-publisher rviz rosbash
  googletest python3-pytest
  chromium chromium-driver python3-selenium python3-pil
  python3-dynamic-reconfigure libdynamic-reconfigure-config-init-mutex-dev
  libtopic-tools-dev
)

missing=()
for p in "${DEB_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} Debian package(s): ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  # wait for another apt run (an unattended upgrade, a second set-up) rather than fail on its lock
  LOCK=(-o DPkg::Lock::Timeout=900)
  $SUDO apt-get "${LOCK[@]}" update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get "${LOCK[@]}" install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# venv: Debian's python with system site packages (rospy), plus the pinned PyPI packages.
VENV="$ROOT/.venv"
if [ ! -x "$VENV/bin/python3" ]; then
  echo "setup: creating venv $VENV"
  /usr/bin/python3 -m venv --system-site-packages "$VENV"
fi
STAMP="$VENV/.requirements.sha"
want="$(sha256sum car/requirements.txt | cut -d' ' -f1)"
if [ "$(cat "$STAMP" 2>/dev/null)" != "$want" ]; then
  echo "setup: installing PyPI requirements into the venv"
  "$VENV/bin/pip" install -q --disable-pip-version-check -r car/requirements.txt
  echo "$want" > "$STAMP"
fi
# `car COMMAND` (car batch, ...) on PATH wherever the venv is (the workspace's env hook puts it first)
ln -sfn "$ROOT/car/scripts/car" "$VENV/bin/car"
# PyPI xacro 2.x's own `xacro` command finds packages through ament (ROS 2): the venv's `xacro` (first on PATH
# once .ws/devel/setup.bash is sourced) runs car's instead, Noetic's dialect with catkin's $(find).
printf '#!%s\nimport sys\nsys.path.insert(0, %s)\nfrom car.xacro_tool import main\nsys.exit(main())\n' \
  "$VENV/bin/python3" "'$ROOT/car/python'" > "$VENV/bin/xacro"
chmod +x "$VENV/bin/xacro"

if [ $deps_only = 1 ]; then
  echo "setup: Debian packages and $VENV ready; build car in your workspace with catkin_make"
  exit 0
fi

# catkin workspace: .ws/src/car links car/, car's package. Each package of this repository sits in a folder of its
# own (car/, compat/NAME/, fixtures/NAME/), so catkin finds every one and roslaunch/rosrun never see two.
mkdir -p .ws/src
# a work tree set up before car/ existed holds .ws/src/car as a folder of links: replace it
if [ -d .ws/src/car ] && [ ! -L .ws/src/car ]; then
  find .ws/src/car -mindepth 1 -maxdepth 1 -type l -delete
  rmdir .ws/src/car
fi
ln -sfn ../../car .ws/src/car
# compat/: drop-in packages Debian lacks (gazebo_msgs), linked as .ws/src/NAME beside car. CAR_COMPAT=0 leaves
# them out, and so does a real package of that name installed on the system (its share/NAME/package.xml).
for pkg in "$ROOT"/compat/*/; do
  name="$(basename "$pkg")"
  real=""
  for prefix in /opt/ros/noetic /usr /usr/local; do [ -f "$prefix/share/$name/package.xml" ] && real="$prefix"; done
  if [ "${CAR_COMPAT:-1}" = 0 ] || [ -n "$real" ]; then
    [ -n "$real" ] && echo "setup: using the installed $name in $real, not compat/$name"
    rm -f ".ws/src/$name"
  else
    ln -sfn "../../compat/$name" ".ws/src/$name"
  fi
done
# fixtures/: test packages of their own (the tutorial's urdf_rviz01, so its launch files run verbatim). A
# CATKIN_IGNORE keeps them out of a user's workspace; here they are linked one by one.
for pkg in "$ROOT"/fixtures/*/; do
  [ -f "$pkg/package.xml" ] && ln -sfn "../../fixtures/$(basename "$pkg")" ".ws/src/$(basename "$pkg")"
done
for link in .ws/src/*; do
  [ -L "$link" ] && [ ! -e "$link" ] && rm -f "$link"
done
set +u
# shellcheck disable=SC1091
source /opt/ros/noetic/setup.bash 2>/dev/null || true
set -u
cd .ws
# ccache, where a developer installed it, shares objects between work trees; it is not needed.
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# paths relative to the clone, so that two clones share objects
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}"
if [ ! -f build/Makefile ]; then
  catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON \
    -DCAR_VENV="$VENV" "${launcher[@]}" -j2 > build.log 2>&1 || { tail -n 60 build.log; exit 1; }
else
  catkin_make -j2 > build.log 2>&1 || { tail -n 60 build.log; exit 1; }
fi
echo "setup: workspace ready; source $ROOT/.ws/devel/setup.bash"
