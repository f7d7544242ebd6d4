#!/usr/bin/env bash
# Builds control_toolbox's own tests (ros-controls/control_toolbox noetic-devel, test/pid_tests.cpp) unchanged
# against car's control_toolbox drop-in (compat/control_toolbox) and runs them: a yardstick car did not write
# (docs/COMPAT-control.md "control_toolbox" has the last result). Not in CI (CI has no snapshot of upstream).
#
#   tools/upstream_control_toolbox.sh CT_SNAPSHOT
#
# CT_SNAPSHOT: a checkout of control_toolbox (a folder holding test/pid_tests.cpp) or a git directory of it (its
# noetic-devel branch is read). Needs car's workspace built (.ws/devel/lib/libcontrol_toolbox.so, tools/setup.sh).
set -euo pipefail
if [ $# -ne 1 ]; then sed -n '2,9p' "$0"; exit 2; fi
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SNAP="$(realpath "$1")"
DEVEL="$ROOT/.ws/devel"
[ -f "$DEVEL/lib/libcontrol_toolbox.so" ] || { echo "upstream_control_toolbox: build car's workspace first (tools/setup.sh)" >&2; exit 2; }
T="$(mktemp -d)"
trap 'rm -rf "$T"' EXIT
if [ -f "$SNAP/test/pid_tests.cpp" ]; then
  cp "$SNAP/test/pid_tests.cpp" "$T/"
  rev="$(git -C "$SNAP" rev-parse --short HEAD 2>/dev/null || echo "a folder")"
else
  git --git-dir="$SNAP" show noetic-devel:test/pid_tests.cpp > "$T/pid_tests.cpp"
  rev="noetic-devel @ $(git --git-dir="$SNAP" rev-parse --short noetic-devel)"
fi
# googletest's sources as Debian ships them (package googletest), built here as catkin builds them
g++ -O1 -std=c++17 -w -c /usr/src/googletest/googletest/src/gtest-all.cc -I/usr/src/googletest/googletest \
  -I/usr/src/googletest/googletest/include -o "$T/gtest-all.o"
g++ -O1 -std=c++17 -Wno-deprecated-declarations "$T/pid_tests.cpp" "$T/gtest-all.o" \
  -I/usr/src/googletest/googletest/include -I"$DEVEL/include" -I"$ROOT/compat/control_toolbox/include" \
  -L"$DEVEL/lib" -Wl,-rpath,"$DEVEL/lib" -lcontrol_toolbox -lroscpp -lrostime -lrosconsole \
  -lroscpp_serialization -lboost_system -lpthread -o "$T/pid_tests"
echo "upstream_control_toolbox: control_toolbox $rev, test/pid_tests.cpp unchanged against compat/control_toolbox"
"$T/pid_tests"
