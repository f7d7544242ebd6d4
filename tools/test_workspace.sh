#!/usr/bin/env bash
# car the ROS way (docs/INSTALL.md), proven in a throwaway workspace:
#   1. clone:     this repository (tracked and untracked files, as `git clone` would give them) into WS/src/car
#   2. build:     `catkin_make` there; every package is found (car, compat/'s drop-ins)
#   3. commands:  roslaunch car sim.launch, roslaunch gazebo_ros empty_world.launch, rosrun car xacro,
#                 rosrun xacro xacro and roslaunch car empty_world.launch each run with no prompt and no error
#   3b. a user's package: a fresh workspace overlaying this one, with fixtures/user_ws/my_gazebo_plugin (its own
#                 Gazebo model plug-in, a CMakeLists as Gazebo users write it): catkin_make there, then its rostest
#                 (gazebo_ros' empty_world.launch, the plug-in's model spawned): it moves the model at the SDF's speed
#                 and sets ROS parameters through roscpp from car's node (docs/PLUGINS.md "Tested", issue 49)
#   4. isolated:  `catkin_make_isolated` builds the same packages (--no-isolated leaves it out)
#   5. install:   `catkin_make install -DCMAKE_INSTALL_PREFIX=T/opt/car`, then, in a mount namespace where this
#                 repository (its devel space and venv), WS/src, WS/build and WS/devel are empty folders, the five
#                 commands again and the suite's rostests (car/test/ros/*.test, copied into the installed
#                 share/car/test) against the install space alone
# Each check is one JUnit test case in --junit FILE (tools/test_slow.sh, run by .ci/run, counts and floors them).
# Usage: tools/test_workspace.sh [--junit FILE] [--keep] [--no-isolated] [--tests "a.test b.test"]
#        tools/test_workspace.sh --user-package-only [--junit FILE] [--keep]   (step 3b alone, over .ws/devel)
# A check of step 5 that never ran (the namespace run died partway) is recorded as a failure
# (CAR_WS_DIE_AFTER=N kills that run after N rostests, to see it).
# Needs root or user namespaces (unshare) for step 5, Debian's ROS packages and the venv (tools/setup.sh).
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
JUNIT="" KEEP=0 ISOLATED=1 TESTS="" INNER="" USER_ONLY=0
while [ $# -gt 0 ]; do
  case "$1" in
    --junit) JUNIT="$(realpath -m "$2")"; shift ;;
    --inner) INNER="$2"; shift ;;   # internal: step 5 inside the mount namespace, in the outer run's T
    --keep) KEEP=1 ;;
    --no-isolated) ISOLATED=0 ;;
    --tests) TESTS="$2"; shift ;;
    --user-package-only) USER_ONLY=1 ;;
    *) echo "test_workspace: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
if [ -n "$INNER" ]; then T="$INNER"; else T="$(mktemp -d /var/tmp/car-ws.XXXXXX)"; fi
WS="$T/ws" PREFIX="$T/opt/car" LOGS="$T/logs"
mkdir -p "$WS/src" "$LOGS"
cleanup() { [ $KEEP = 1 ] && echo "test_workspace: kept $T" || rm -rf "$T"; }
[ -n "$INNER" ] || trap cleanup EXIT

# ---- results: one line per check in T/results.tsv (name, exit, seconds, message) ------------------------------
record() {  # record NAME RC T0 MESSAGE
  local msg="${4//$'\t'/ }"
  printf '%s\t%s\t%s\t%s\n' "$1" "$2" "$((SECONDS - $3))" "${msg//$'\n'/ | }" >> "$T/results.tsv"
  if [ "$2" = 0 ]; then echo "test_workspace: ok   $1 ($((SECONDS - $3)) s)"; else echo "test_workspace: FAIL $1: ${4:0:400}"; fi
}
finish() {
  /usr/bin/python3 - "$T/results.tsv" "$JUNIT" <<'PY'
import re
import sys
from xml.sax.saxutils import escape, quoteattr
# a message as XML 1.0 text: terminal colour codes (roslaunch's errors) and other control characters left out
clean = lambda m: re.sub(r'[\x00-\x08\x0b\x0c\x0e-\x1f]', '', re.sub(r'\x1b\[[0-9;]*[A-Za-z]', '', m))
rows = [l.rstrip('\n').split('\t', 3) for l in open(sys.argv[1]) if l.strip()]
rows = [r[:3] + [clean(r[3]) if len(r) > 3 else ''] for r in rows]
failed = [r for r in rows if r[1] != '0']
print('test_workspace: %d passed, %d failed' % (len(rows) - len(failed), len(failed)))
if sys.argv[2]:
    with open(sys.argv[2], 'w') as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n<testsuite name="workspace" tests="%d" failures="%d" '
                'errors="0" skipped="0">\n' % (len(rows), len(failed)))
        for name, rc, s, msg in rows:
            f.write('  <testcase classname="car.workspace" name=%s time="%s">' % (quoteattr(name), s))
            if rc != '0':
                f.write('<failure message=%s>%s</failure>' % (quoteattr(msg[:300]), escape(msg)))
            f.write('</testcase>\n')
        f.write('</testsuite>\n')
sys.exit(1 if failed or not rows else 0)
PY
  local rc=$?
  echo "test_workspace: logs in $LOGS"
  exit $rc
}

# ---- 3. ROS's own tools, no prompt ------------------------------------------------------------------------------
port=$((21000 + RANDOM % 20000))
# launch_runs NAME SETUP ARGS...: roslaunch with its own master, stdin closed; passes once /clock has ticked and no
# node died, no file or executable was ambiguous (waits at most 180 s for the first /clock, then says so)
launch_runs() {
  local name="$1" setup="$2"; shift 2
  local log="$LOGS/$name.log" t0=$SECONDS rc=0 msg="" p=$((port++))
  (
    set +u; source "$setup"; set -u
    export ROS_MASTER_URI="http://localhost:$p" ROS_HOME="$T/ros_home"
    setsid roslaunch -p "$p" "$@" < /dev/null > "$log" 2>&1 &
    pid=$!
    ok=1
    for _ in $(seq 180); do
      if timeout 5 rostopic echo -n 1 /clock < /dev/null > "$log.clock" 2>&1 && grep -q secs "$log.clock"; then ok=0; break; fi
      kill -0 $pid 2>/dev/null || break
      sleep 1
    done
    kill -INT -- -$pid 2>/dev/null; sleep 3; kill -KILL -- -$pid 2>/dev/null
    wait $pid 2>/dev/null
    exit $ok
  )
  rc=$?
  [ $rc = 0 ] || msg="no /clock within 180 s of roslaunch $*"
  if grep -qE 'process has died|multiple files named|non-unique|please pick|RLException|ResourceNotFound' "$log"; then
    rc=1; msg="roslaunch $*: $(grep -m 3 -E 'process has died|multiple files named|non-unique|please pick|RLException|ResourceNotFound' "$log")"
  fi
  [ -n "$msg" ] && msg="$msg (log tail: $(tail -n 8 "$log"))"
  record "$name" $rc $t0 "$msg"
}
# rosrun_xacro NAME SETUP PKG: rosrun PKG xacro on the tutorial's car gives a URDF, with no prompt
rosrun_xacro() {
  local name="$1" setup="$2" pkg="$3" log="$LOGS/$1.log" t0=$SECONDS rc
  ( set +u; source "$setup"; set -u
    timeout 120 rosrun "$pkg" xacro "$(rospack find car)/urdf/car_camera_lidar04.xacro" < /dev/null > "$log" 2>&1 )
  rc=$?
  grep -q '<robot' "$log" && ! grep -qE 'non-unique|please pick' "$log" || rc=1
  record "$name" $rc $t0 "rosrun $pkg xacro exited $rc or printed no <robot>: $(head -c 600 "$log")"
}
five_commands() {  # five_commands SPACE SETUP
  launch_runs "$1_roslaunch_car_sim" "$2" car sim.launch rtf:=0
  launch_runs "$1_roslaunch_gazebo_ros_empty_world" "$2" gazebo_ros empty_world.launch
  rosrun_xacro "$1_rosrun_car_xacro" "$2" car
  rosrun_xacro "$1_rosrun_xacro_xacro" "$2" xacro
  launch_runs "$1_roslaunch_car_empty_world" "$2" car empty_world.launch
}

# ---- 3b. a user's package in a workspace of its own, overlaying car's ---------------------------------------------
# user_package UNDERLAY_SETUP: T/user_ws/src holds fixtures/user_ws/my_gazebo_plugin; catkin_make with the underlay
# sourced, as a user does, then `rostest my_gazebo_plugin push.test` with the overlay sourced
user_package() {
  local underlay="$1" uw="$T/user_ws" t0=$SECONDS rc log
  mkdir -p "$uw/src"
  cp -a "$ROOT/fixtures/user_ws/my_gazebo_plugin" "$uw/src/"
  log="$LOGS/user_catkin_make.log"
  ( set +u; source "$underlay"; set -u
    cd "$uw" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -j2 ) < /dev/null > "$log" 2>&1
  rc=$?
  [ $rc != 0 ] || [ -f "$uw/devel/lib/libmy_push.so" ] || { rc=1; echo "test_workspace: no devel/lib/libmy_push.so" >> "$log"; }
  record "user_package_catkin_make_builds_its_gazebo_plugin" $rc $t0 "catkin_make of my_gazebo_plugin over $underlay failed: $(grep -m 5 -E 'rror|Could not' "$log") $(tail -n 8 "$log")"
  [ $rc = 0 ] || return 0
  t0=$SECONDS
  log="$LOGS/user_rostest_push.log"
  ( set +u; source "$uw/devel/setup.bash"; set -u
    export ROS_HOME="$T/ros_home"
    timeout 600 rostest --text my_gazebo_plugin push.test ) < /dev/null > "$log" 2>&1
  rc=$?
  grep -q 'RESULT: SUCCESS' "$log" || rc=1
  record "user_package_plugin_acts_in_empty_world_launch" $rc $t0 "rostest my_gazebo_plugin push.test: $(grep -E 'FAIL|ERROR|Error|AssertionError|not within' "$log" | head -n 8)"
}
if [ $USER_ONLY = 1 ]; then
  user_package "$ROOT/.ws/devel/setup.bash"
  finish
fi

if [ -z "$INNER" ]; then
# ---- 1. the repository as a clone gives it ---------------------------------------------------------------------
t0=$SECONDS
mkdir -p "$WS/src/car"
(cd "$ROOT" && git ls-files -z --cached --others --exclude-standard | xargs -0 -r cp --parents -a -t "$WS/src/car" 2>/dev/null)
# the documented step, tools/setup.sh --deps-only: Debian's packages (here all present) and the clone's venv. So
# that nothing is downloaded again, the venv is made beforehand with this repository's site-packages (linked) and
# requirements stamp; setup.sh then only writes the clone's own bin/car and bin/xacro into it.
/usr/bin/python3 -m venv --system-site-packages --without-pip "$WS/src/car/.venv"
for sp in "$WS/src/car/.venv"/lib/python3*/site-packages; do
  rm -rf "$sp" && ln -s "$(echo "$ROOT/.venv"/lib/python3*/site-packages)" "$sp"
done
cp "$ROOT/.venv/.requirements.sha" "$WS/src/car/.venv/"
t0=$SECONDS
bash "$WS/src/car/tools/setup.sh" --deps-only > "$LOGS/deps_only.log" 2>&1
rc=$?
[ ! -e "$WS/src/car/.ws" ] || rc=1
record "setup_deps_only_builds_nothing" $rc $t0 "tools/setup.sh --deps-only (exit $rc, or it made .ws): $(tail -n 5 "$LOGS/deps_only.log")"
found="$(cd "$WS/src" && /usr/bin/python3 -c 'from catkin_pkg.packages import find_packages; print(" ".join(sorted(p.name for p in find_packages(".").values())))')"
want="car control_msgs control_toolbox controller_manager controller_manager_msgs gazebo gazebo_dev gazebo_msgs gazebo_plugins gazebo_ros gazebo_ros_control xacro"
[ "$found" = "$want" ]; record "clone_finds_every_package" $? $t0 "catkin_pkg found [$found] in the clone, expected [$want]"

# ---- 2. catkin_make ---------------------------------------------------------------------------------------------
set +u; [ -f /opt/ros/noetic/setup.bash ] && source /opt/ros/noetic/setup.bash; set -u
launcher=(); command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
export CCACHE_BASEDIR="$T"
t0=$SECONDS
(cd "$WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" -j2 \
  > "$LOGS/catkin_make.log" 2>&1)
rc=$?
record "catkin_make_builds_every_package" $rc $t0 "catkin_make failed: $(tail -n 15 "$LOGS/catkin_make.log")"
[ $rc = 0 ] || finish

five_commands devel "$WS/devel/setup.bash"
user_package "$WS/devel/setup.bash"

# ---- 4. catkin_make_isolated ------------------------------------------------------------------------------------
if [ $ISOLATED = 1 ]; then
  t0=$SECONDS
  (cd "$WS" && catkin_make_isolated -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
    -j2 > "$LOGS/catkin_make_isolated.log" 2>&1)
  rc=$?
  [ $rc = 0 ] && [ -f "$WS/devel_isolated/car/lib/car/sim_node" ] || rc=1
  record "catkin_make_isolated_builds_every_package" $rc $t0 "catkin_make_isolated failed: $(tail -n 15 "$LOGS/catkin_make_isolated.log")"
fi

fi

# ---- 5. the install space, alone --------------------------------------------------------------------------------
if [ -n "$INNER" ]; then
  # in the mount namespace: the repository (its devel space and venv) and WS/src, WS/build, WS/devel are empty
  mount --make-rprivate / 2>/dev/null
  mount --bind "$ROOT/.venv" "$T/venv"
  for d in "$ROOT" "$WS/src" "$WS/build" "$WS/devel" "$WS/build_isolated" "$WS/devel_isolated"; do
    [ -d "$d" ] && mount -t tmpfs -o size=1m car-hidden "$d"
  done
  t0=$SECONDS
  n="$(ls -A "$ROOT" | wc -l)"
  [ "$n" = 0 ]; record "install_space_alone_the_source_tree_hidden" $? $t0 "the repository still shows $n entries"
  # the optional tools' PyPI packages (the web view's viser) from a venv outside the hidden tree: a user's CAR_VENV
  export CAR_VENV="$T/venv"
  # installed scripts start with `#!/usr/bin/env python3` (catkin_install_python), so python3 on PATH must be
  # Debian's, as on a plain Debian machine (here a pyenv shim may come first; the .debs pin /usr/bin/python3)
  export PATH="/usr/bin:$PATH"
  set +u; [ -f /opt/ros/noetic/setup.bash ] && source /opt/ros/noetic/setup.bash; set -u
  five_commands install "$PREFIX/setup.bash"
  set +u; source "$PREFIX/setup.bash"; set -u
  export ROS_PACKAGE_PATH="$ROS_PACKAGE_PATH:$T/fixtures" ROS_HOME="$T/ros_home"
  ran=0
  for t in $TESTS; do
    # test hook: CAR_WS_DIE_AFTER=N kills this run after N rostests, as a crash partway would
    [ "$ran" != "${CAR_WS_DIE_AFTER:-}" ] || kill -KILL $$
    ran=$((ran + 1))
    t0=$SECONDS
    log="$LOGS/rostest-$t.log"
    timeout 900 rostest --text "$PREFIX/share/car/test/ros/$t" < /dev/null > "$log" 2>&1
    rc=$?
    grep -q 'RESULT: SUCCESS' "$log" || rc=1
    record "install_rostest_${t%.test}" $rc $t0 "rostest $t against the install space: $(grep -E 'FAILURE|ERROR|Error|failed' "$log" | head -n 8)"
  done
  exit 0
fi
t0=$SECONDS
(cd "$WS" && catkin_make install -DCMAKE_INSTALL_PREFIX="$PREFIX" -j2 > "$LOGS/install.log" 2>&1)
rc=$?
for f in lib/car/sim_node lib/libcar_sim.so lib/car/xacro share/car/scripts/xacro share/car/worlds/box_house.world \
         share/car/config/gazebo_materials.txt share/gazebo_ros/launch/empty_world.launch share/xacro/xacro setup.bash \
         lib/car/pypi/xacro/__init__.py; do
  [ -e "$PREFIX/$f" ] || { rc=1; echo "test_workspace: the install lacks $f" >> "$LOGS/install.log"; }
done
ls "$PREFIX"/lib/python3/dist-packages/car/_core*.so > /dev/null 2>&1 ||
  { rc=1; echo "test_workspace: the install lacks car._core" >> "$LOGS/install.log"; }
record "catkin_make_install_gives_a_whole_tree" $rc $t0 "$(tail -n 15 "$LOGS/install.log")"
[ $rc = 0 ] || finish
# the suite's rostests and the tutorial's fixture package beside the install (tests are not installed)
cp -a "$ROOT/car/test" "$PREFIX/share/car/test"
cp -a "$ROOT/docs" "$PREFIX/share/car/docs"   # dropin_api.test compares the graph with docs/COMPAT-dropins.md
mkdir -p "$T/fixtures" "$T/venv" && cp -aL "$ROOT/fixtures/urdf_rviz01" "$T/fixtures/"
# (gazebo_plugin.test, gazebo_world_plugin.test and gazebo_ros_threads.test run plug-ins the test build makes, which an
# install does not have)
[ -n "$TESTS" ] || TESTS="$(cd "$ROOT/car/test/ros" && ls ./*.test | sed 's#^\./##' | grep -vx -e 'gazebo_plugin.test' -e 'gazebo_world_plugin.test' -e 'gazebo_ros_threads.test' | tr '\n' ' ')"
inner_args=(--inner "$T" --tests "$TESTS")
if [ "$(id -u)" -eq 0 ]; then unshare -m bash "$0" "${inner_args[@]}" 2>&1 | tee "$LOGS/inner.log"
else unshare -rm bash "$0" "${inner_args[@]}" 2>&1 | tee "$LOGS/inner.log"; fi
grep -q install_space_alone "$T/results.tsv" ||
  record "install_space_alone_the_source_tree_hidden" 1 $SECONDS "no mount namespace (root or user namespaces needed): $(tail -n 5 "$LOGS/inner.log")"
# the namespace run records each check only once it has finished: one that never ran (the run died partway, or
# never started) is a failure too, so that a run cut short cannot pass with fewer checks
planned=(install_roslaunch_car_sim install_roslaunch_gazebo_ros_empty_world install_rosrun_car_xacro
  install_rosrun_xacro_xacro install_roslaunch_car_empty_world)
for t in $TESTS; do planned+=("install_rostest_${t%.test}"); done
for name in "${planned[@]}"; do
  cut -f1 "$T/results.tsv" | grep -qxF "$name" ||
    record "$name" 1 $SECONDS "never ran: the install-space run in the mount namespace ended before it (inner.log: $(tail -n 5 "$LOGS/inner.log"))"
done
finish
