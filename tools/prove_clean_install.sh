#!/usr/bin/env bash
# Proves the install on a truly clean Debian 12: makes a throwaway root with debootstrap from the Debian archive
# this machine's apt is configured with, puts a fresh `git clone` of this repository (its committed HEAD) in it,
# and inside that root runs the README's two commands as a new user would:
#   1. install:  bash tools/setup.sh   (Debian packages, venv, catkin build; needs the network)
#   2. test:     bash tools/test.sh    (with no network: nothing may be downloaded at run time)
#   3. run:      bash tools/run.sh     for RUN_S wall seconds (no network), failing on "process has died" or on
#                a launched node missing from `rosnode list`
# It prints how long each phase took and removes the root. Must run as root (debootstrap, chroot, unshare).
# Heavy: run it at low priority, e.g. `nice -n 19 bash tools/prove_clean_install.sh`.
#
# --debs proves the user's path instead (docs/INSTALL.md): tools/make_debs.sh builds the .debs here, and inside the
# root, with no compiler installed:
#   1. install:  apt-get install ./ros-car*.deb   (Debian's packages come from the archive; the time and the disk
#                space it took are printed)
#   2. run:      source /opt/car/setup.bash; roslaunch car sim.launch (no network), then /cmd_vel (0.5, 0.5)
#                drives the seed car: /odom must have moved 0.3 m or more
#   3. tutorial: the tutorial's 三.1 launch file as printed (fixtures/urdf_rviz01, not built: it holds no code):
#                its car drives 0.3 m or more for the same command
#
# Usage: bash tools/prove_clean_install.sh [--keep] [--debs]   (--keep leaves the root for inspection)
# Environment: RUN_S (default 90), SUITE (default bookworm), WORK (default /var/tmp), MIRROR (default: from apt)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
KEEP=0 DEBS=0
for a in "$@"; do
  case "$a" in
    --keep) KEEP=1 ;;
    --debs) DEBS=1 ;;
    *) echo "prove: unknown option $a (usage: prove_clean_install.sh [--keep] [--debs])"; exit 2 ;;
  esac
done
RUN_S="${RUN_S:-90}"
SUITE="${SUITE:-bookworm}"
WORK="${WORK:-/var/tmp}"

[ "$(id -u)" -eq 0 ] || { echo "prove: must run as root (debootstrap, chroot, unshare)"; exit 2; }
if ! command -v debootstrap >/dev/null; then
  echo "prove: installing debootstrap"
  DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends \
    debootstrap >/dev/null
fi

# The Debian archive this machine's apt uses: the first deb.debian.org-style URI of a Debian source
# (one-line .list or deb822 .sources), unless MIRROR is given.
sources=()
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
  [ -f "$f" ] && grep -qE '^[^#]*(debian\.org|/debian/?( |$))' "$f" && sources+=("$f")
done
if [ -z "${MIRROR:-}" ]; then
  MIRROR="$(grep -hoE '^[^#]*(URIs:|deb)[[:space:]]+[^[:space:]]*/debian/?([[:space:]]|$)' "${sources[@]}" 2>/dev/null |
            grep -oE '[a-z]+://[^[:space:]]*/debian/?' | head -n 1)"
fi
[ -n "$MIRROR" ] || { echo "prove: no Debian archive in /etc/apt/sources.list*; set MIRROR"; exit 2; }

R="$(mktemp -d "$WORK/car-clean-root.XXXXXX")"
LOGS="$R.logs"
mkdir -p "$LOGS"
cleanup() {
  # every mount lives in the namespaces below and is gone with them; refuse to delete through a mount anyway
  if [ "$KEEP" -eq 1 ]; then echo "prove: root kept at $R"; return; fi
  if grep -q " $R/" /proc/mounts; then echo "prove: $R still has mounts; not removing it"; return; fi
  rm -rf --one-file-system "$R"
  echo "prove: removed $R (logs in $LOGS)"
}
trap cleanup EXIT

declare -A took
phase() {  # phase NAME COMMAND...: runs it, records the wall time, stops the proof on failure
  local name="$1"; shift
  local t0=$SECONDS
  echo "prove: == $name =="
  if "$@"; then
    took[$name]=$((SECONDS - t0)); echo "prove: $name took ${took[$name]} s"
  else
    local rc=$?
    echo "prove: $name FAILED (exit $rc) after $((SECONDS - t0)) s; logs in $LOGS"
    exit 1
  fi
}

in_root() {  # in_root NET|NONET SCRIPT: runs SCRIPT with bash inside the root (own mount and pid namespace)
  local net="$1"
  printf '%s\n' "$2" > "$R/root/.prove_step.sh"
  # own UTS namespace too: the root's hostname is car-clean, which its /etc/hosts resolves (roslaunch and roscore
  # contact themselves by hostname; the host's name means nothing inside a root without a network)
  local unshare_args=(--mount --pid --uts --fork --propagation private)
  local pre=""
  if [ "$net" = NONET ]; then unshare_args+=(--net); pre="ip link set lo up;"; fi
  unshare "${unshare_args[@]}" bash -c "
    set -e; $pre
    hostname car-clean
    mount -t proc proc '$R/proc'
    mount --rbind /dev '$R/dev'
    mount --rbind /sys '$R/sys'
    mount -t tmpfs tmpfs '$R/tmp'
    exec chroot '$R' /usr/bin/env -i HOME=/root USER=root LANG=C.UTF-8 TERM=dumb \
      PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin bash /root/.prove_step.sh"
}

bootstrap() {
  debootstrap "$SUITE" "$R" "$MIRROR" > "$LOGS/debootstrap.log" 2>&1 || { tail -n 20 "$LOGS/debootstrap.log"; return 1; }
  # this machine's Debian sources and apt options; no services start inside the root
  rm -f "$R/etc/apt/sources.list"
  for f in "${sources[@]}"; do
    case "$f" in */sources.list) cp "$f" "$R/etc/apt/sources.list" ;; *) cp "$f" "$R/etc/apt/sources.list.d/" ;; esac
  done
  cp -n /etc/apt/apt.conf.d/* "$R/etc/apt/apt.conf.d/" 2>/dev/null || true
  cp /etc/resolv.conf "$R/etc/resolv.conf"
  printf '127.0.0.1 localhost\n127.0.1.1 car-clean\n::1 localhost ip6-localhost ip6-loopback\n' > "$R/etc/hosts"
  echo car-clean > "$R/etc/hostname"
  # pip inside the root trusts what this machine's pip trusts (a machine that reaches PyPI through a TLS proxy has
  # that proxy's CA there); nothing else of the host's Python set-up is copied
  local ca="${PIP_CERT:-$(pip3 config get global.cert 2>/dev/null || true)}"
  if [ -n "$ca" ] && [ -f "$ca" ]; then
    cp "$ca" "$R/etc/prove-host-ca.crt"
    printf '[global]\ncert = /etc/prove-host-ca.crt\n' > "$R/etc/pip.conf"
  fi
  printf '#!/bin/sh\nexit 101\n' > "$R/usr/sbin/policy-rc.d"
  chmod +x "$R/usr/sbin/policy-rc.d"
}

clone() {
  git clone -q "$ROOT" "$R/root/car"
  echo "prove: cloned $(git -C "$R/root/car" log -1 --format='%h %s' | cut -c1-100)"
}

install() {
  in_root NET "cd /root/car && bash tools/setup.sh" > "$LOGS/setup.log" 2>&1 || { tail -n 40 "$LOGS/setup.log"; return 1; }
  tail -n 3 "$LOGS/setup.log"
}

tests() {
  local rc=0
  in_root NONET "cd /root/car && bash tools/test.sh" > "$LOGS/test.log" 2>&1 || rc=$?
  tail -n 25 "$LOGS/test.log"
  return $rc
}

run_sim() {
  # roslaunch in the background; after RUN_S seconds the graph is listed and /clock read, then SIGINT
  in_root NONET "cd /root/car
    bash tools/run.sh > /tmp/run.log 2>&1 & launch=\$!
    sleep $RUN_S
    source .ws/devel/setup.bash
    rosnode list > /tmp/nodes.txt 2>&1 || true
    timeout 20 rostopic echo -n 2 /clock > /tmp/clock.txt 2>&1 || true
    kill -INT \$launch; wait \$launch || true
    cat /tmp/run.log; echo '--- rosnode list'; cat /tmp/nodes.txt; echo '--- /clock'; cat /tmp/clock.txt" \
    > "$LOGS/run.log" 2>&1 || true
  local ok=0
  if grep -n "process has died" "$LOGS/run.log"; then ok=1; fi
  for n in /gazebo /robot_state_publisher /support_depth_tf /world_markers; do
    grep -qx "$n" "$LOGS/run.log" || { echo "prove: node $n not running after $RUN_S s"; ok=1; }
  done
  grep -q "secs:" "$LOGS/run.log" || { echo "prove: no /clock on the graph"; ok=1; }
  [ $ok -eq 0 ] && echo "prove: tools/run.sh ran $RUN_S s with every node alive"
  return $ok
}

# ---- --debs: the .debs, installed into the clean root --------------------------------------------------------------
make_debs() {
  bash "$ROOT/tools/make_debs.sh" "$R.debs" > "$LOGS/make_debs.log" 2>&1 || { tail -n 30 "$LOGS/make_debs.log"; return 1; }
  grep '^make_debs: .*\.deb' "$LOGS/make_debs.log"
  mkdir -p "$R/root/debs" && cp "$R.debs"/*.deb "$R/root/debs/"
  cp -aL "$ROOT/fixtures/urdf_rviz01" "$R/root/urdf_rviz01"
}
install_debs() {
  local before after
  before=$(du -sk --exclude=./proc --exclude=./sys --exclude=./dev --exclude=./root/debs "$R" | cut -f1)
  in_root NET "export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends ./root/debs/*.deb 2>&1 | tail -n 5
    apt-get clean
    for c in cc gcc g++ c++ clang; do command -v \$c && { echo \"prove: a compiler is installed: \$c\"; exit 1; }; done
    echo 'prove: no compiler in the root'
    # rosbash (rosrun) depends on Debian's catkin, which brings cmake: present, but nothing here builds
    for c in make cmake; do command -v \$c > /dev/null && echo \"prove: \$c is present (through rosbash -> catkin)\"; done; true" > "$LOGS/install_debs.log" 2>&1 ||
    { tail -n 30 "$LOGS/install_debs.log"; return 1; }
  tail -n 3 "$LOGS/install_debs.log"
  after=$(du -sk --exclude=./proc --exclude=./sys --exclude=./dev --exclude=./root/debs "$R" | cut -f1)
  echo "prove: the .debs and what they pulled in take $(( (after - before) / 1024 )) MiB (debs: $(du -ch "$R.debs"/*.deb | tail -n 1 | cut -f1))"
}
# drove_debs LOG WHAT: /odom before and after a (0.5, 0.5) command, in LOG, moved 0.3 m or more
drove_debs() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
def xy(part):
    m = re.search(r'position:\s*\n\s*x: (\S+)\s*\n\s*y: (\S+)', part)
    return (float(m.group(1)), float(m.group(2))) if m else None
before = xy(text.split('--- odom before')[-1].split('--- odom after')[0])
after = xy(text.split('--- odom after')[-1])
if not before or not after:
    sys.exit('prove: no /odom from %s (before %s, after %s)' % (sys.argv[2], before, after))
d = ((after[0] - before[0]) ** 2 + (after[1] - before[1]) ** 2) ** 0.5
print('prove: %s drove the car %.2f m (odom %s -> %s)' % (sys.argv[2], d, before, after))
sys.exit(0 if d >= 0.3 else 1)
PY
}
# in_root_drive LAUNCH...: roslaunch it (no network), wait for /odom, command (0.5, 0.5) for 15 s, read /odom again
drive_script() {
  echo "source /opt/car/setup.bash
    export ROS_PACKAGE_PATH=/root/urdf_rviz01:\$ROS_PACKAGE_PATH
    roslaunch $* > /tmp/run.log 2>&1 & launch=\$!
    for i in \$(seq 120); do timeout 5 rostopic echo -n 1 /odom > /tmp/odom0.txt 2>/dev/null && break; sleep 1; done
    timeout 15 rostopic pub -r 10 /cmd_vel geometry_msgs/Twist '{linear: {x: 0.5}, angular: {z: 0.5}}' > /dev/null 2>&1 || true
    timeout 10 rostopic echo -n 1 /odom > /tmp/odom1.txt 2>&1 || true
    rosnode list > /tmp/nodes.txt 2>&1 || true
    kill -INT \$launch; wait \$launch || true
    cat /tmp/run.log; echo '--- rosnode list'; cat /tmp/nodes.txt
    echo '--- odom before'; cat /tmp/odom0.txt; echo '--- odom after'; cat /tmp/odom1.txt"
}
run_debs() {
  in_root NONET "$(drive_script car sim.launch rtf:=1)" > "$LOGS/run_debs.log" 2>&1 || true
  grep -n "process has died" "$LOGS/run_debs.log" && return 1
  drove_debs "$LOGS/run_debs.log" "the installed sim.launch"
}
tutorial_debs() {
  # 三.1 as printed: $(find xacro)/xacro, gazebo_ros's empty_world.launch with box_house, gazebo_ros spawn_model;
  # this chapter's car has no sensors yet, it drives
  in_root NONET "$(drive_script urdf_rviz01 car_camera_lidar03.launch)" > "$LOGS/tutorial_debs.log" 2>&1 || true
  grep -n "process has died" "$LOGS/tutorial_debs.log" && return 1
  drove_debs "$LOGS/tutorial_debs.log" "the tutorial's car_camera_lidar03.launch, as printed,"
}
if [ $DEBS = 1 ]; then
  echo "prove: root $R, $SUITE from $MIRROR (sources: ${sources[*]}), the .debs"
  phase debootstrap bootstrap
  phase make_debs make_debs
  phase install install_debs
  phase run run_debs
  phase tutorial tutorial_debs
  rm -rf "$R.debs"
  echo "prove: OK (debs) — debootstrap ${took[debootstrap]} s, make_debs ${took[make_debs]} s," \
       "install ${took[install]} s, run ${took[run]} s, tutorial ${took[tutorial]} s; total $SECONDS s"
  exit 0
fi

echo "prove: root $R, $SUITE from $MIRROR (sources: ${sources[*]})"
phase debootstrap bootstrap
phase clone clone
phase install install
phase test tests
phase run run_sim
echo "prove: OK — debootstrap ${took[debootstrap]} s, install ${took[install]} s, test ${took[test]} s," \
     "run ${took[run]} s; total $SECONDS s"
