#!/usr/bin/env bash
# Debian packages of car and its drop-ins (docs/INSTALL.md "Debian packages"): builds the install space with
# prefix /opt/car in .ws-debs/ (git-ignored; re-runs only rebuild what changed), installs each catkin package on
# its own (its build folder's cmake_install.cmake, DESTDIR) and wraps it with dpkg-deb:
#   ros-car-setup                   /opt/car/setup.bash and catkin's workspace files
#   ros-car                         the simulator: sim_node, libcar_sim, car._core, the scripts, launch, worlds,
#                                   models, PyPI's xacro (vendored in /opt/car/lib/car/pypi)
#   ros-car-gazebo-ros, ros-car-gazebo, ros-car-xacro, ros-car-controller-manager
#                                   the drop-ins (forwarders into car, launch files)
#   ros-car-gazebo-dev, ros-car-gazebo-plugins, ros-car-gazebo-ros-control
#                                   catkin components for users' own Gazebo plug-ins (docs/PLUGINS.md)
#   ros-car-gazebo-msgs, ros-car-controller-manager-msgs, ros-car-control-msgs
#                                   the message packages Debian lacks
#   ros-car-control-toolbox         control_toolbox::Pid for users' plug-ins and controllers
# Depends: the Debian packages each one needs: dpkg-shlibdeps for its ELF files, its package.xml's run
# dependencies through the table below, and the ros-car-* packages it needs.
# Usage: tools/make_debs.sh [OUTDIR]      (default dist/; prints each .deb with its size)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="$(realpath -m "${1:-$ROOT/dist}")"
WS="$ROOT/.ws-debs"
PREFIX=/opt/car
STAGE="$WS/stage"
cd "$ROOT"
command -v dpkg-shlibdeps >/dev/null || { echo "make_debs: needs dpkg-dev (apt-get install dpkg-dev)"; exit 2; }

# ---- build: a workspace of its own, in an environment with no other workspace in it ------------------------------
# WS/ws/src/car is this repository, as a clone in a user's workspace (catkin skips the dot-folders .ws*; the same
# layout as tools/test_workspace.sh's, so that ccache, where installed, shares their objects)
mkdir -p "$WS/ws/src"
ln -sfn "$ROOT" "$WS/ws/src/car"
launcher=(); command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$WS"
echo "make_debs: building $WS/ws (prefix $PREFIX)"
(cd "$WS/ws" && env -u CMAKE_PREFIX_PATH -u ROS_PACKAGE_PATH -u PYTHONPATH -u LD_LIBRARY_PATH -u ROS_DISTRO \
  catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=OFF \
  -DCMAKE_INSTALL_PREFIX="$PREFIX" "${launcher[@]}" -j"${JOBS:-2}" > "$WS/build.log" 2>&1) ||
  { tail -n 40 "$WS/build.log"; exit 1; }

# ---- stage: each package's own install rules, into STAGE/<deb>/ ------------------------------------------------
rm -rf "$STAGE" && mkdir -p "$STAGE" "$OUT"
install_part() {  # install_part DEB CMAKE_INSTALL_FILE [extra cmake -D...]
  local deb="$1" file="$2"; shift 2
  DESTDIR="$STAGE/$deb" cmake -DCMAKE_INSTALL_PREFIX="$PREFIX" "$@" -P "$file" > "$STAGE/$deb.install.log" 2>&1 ||
    { tail -n 20 "$STAGE/$deb.install.log"; exit 1; }
}
# the workspace's own files (setup.bash, _setup_util.py, .catkin, env.sh): the top folder's rules only
install_part ros-car-setup "$WS/ws/build/cmake_install.cmake" -DCMAKE_INSTALL_LOCAL_ONLY=1
for pkg in car compat/*; do
  name="$(basename "$pkg")"
  deb="ros-car"; [ "$name" = car ] || deb="ros-car-${name//_/-}"
  install_part "$deb" "$WS/ws/build/car/$pkg/cmake_install.cmake"
done

# Python programs run on Debian's python3, as dh_python3 writes them (catkin_install_python leaves
# `#!/usr/bin/env python3`, which a pyenv or venv python3 on PATH would take)
grep -rlZ --include='*' -m1 '^#!/usr/bin/env python3' "$STAGE" 2>/dev/null |
  while IFS= read -r -d '' f; do
    [ "$(head -c 22 "$f")" = '#!/usr/bin/env python3' ] && sed -i '1s|^#!/usr/bin/env python3|#!/usr/bin/python3|' "$f"
  done

# ---- control files -------------------------------------------------------------------------------------------
VERSION="$(sed -n 's:.*<version>\(.*\)</version>.*:\1:p' car/package.xml | head -n 1)-1"
ARCH="$(dpkg --print-architecture)"
for dir in "$STAGE"/*/; do
  deb="$(basename "$dir")"
  # shared-library dependencies of its ELF files, as Debian's own packages compute them
  elfs=()
  while IFS= read -r -d '' f; do
    file -b "$f" | grep -q '^ELF' && elfs+=("$f")
  done < <(find "$dir" -type f -print0)
  shlibs=""
  if [ ${#elfs[@]} -gt 0 ]; then
    mkdir -p "$WS/shlibs/debian" && : > "$WS/shlibs/debian/control"
    printf 'Source: x\n\nPackage: x\nArchitecture: any\n' > "$WS/shlibs/debian/control"
    shlibs="$(cd "$WS/shlibs" && LD_LIBRARY_PATH="$STAGE/ros-car$PREFIX/lib" dpkg-shlibdeps -O --ignore-missing-info \
      -l"$STAGE/ros-car$PREFIX/lib" "${elfs[@]}" 2>/dev/null | sed -n 's/^shlibs:Depends=//p')"
  fi
  /usr/bin/python3 "$ROOT/tools/deb_control.py" --deb "$deb" --root "$ROOT" --version "$VERSION" --arch "$ARCH" \
    --shlibs "$shlibs" --installed-size "$(du -sk "$dir" | cut -f1)" > "$WS/control.$deb"
  mkdir -p "$dir/DEBIAN"
  cp "$WS/control.$deb" "$dir/DEBIAN/control"
  dpkg-deb --root-owner-group -Zxz --build "$dir" "$OUT/${deb}_${VERSION}_${ARCH}.deb" > /dev/null
  echo "make_debs: $OUT/${deb}_${VERSION}_${ARCH}.deb ($(du -h "$OUT/${deb}_${VERSION}_${ARCH}.deb" | cut -f1))"
done
