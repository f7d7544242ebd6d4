#!/usr/bin/env bash
# Builds Gazebo's tutorial plug-ins from their upstream sources, unchanged, against car's Gazebo 11 API and runs each
# in its own .world in car's simulator node (what car's gzserver runs), then prints a table (example, built, ran,
# what it did). Not in CI: the sources are upstream's, materialized by whoever runs it. docs/PLUGINS.md "Gazebo's
# tutorials, built unchanged" has the table of the last run.
#
#   tools/upstream_examples.sh DIR [EXAMPLE ...]
#
# DIR holds one folder per example, each with its upstream files as they are (gazebo-classic's
# examples/plugins/<name>/ and the velodyne tutorial's source):
#   hello_world/      hello_world.cc, hello.world        (a world plug-in printing "Hello World!")
#   model_push/       model_push.cc, model_push.world    (a model plug-in pushing a box at 0.3 m/s along x)
#   parameters/       parameters.cc, parameters.world    (a world plug-in printing its <plugin>'s values)
#   factory/          factory.cc, factory.world, models/ (a world plug-in inserting three models)
#   velodyne_plugin/  velodyne_plugin.cc, velodyne.world (a JointController turning the sensor's joint)
# EXAMPLE: folder names (default: every one present). Needs car's workspace built and sourced. Each source is built
# by a CMakeLists of ours (find_package(gazebo), as the tutorials' own) into <work>/<name>/build/lib<name>.so; the
# world runs with GAZEBO_PLUGIN_PATH=<work>/<name>:<work>/<name>/build and GAZEBO_MODEL_PATH=DIR/<name>/models.
set -u

if [ $# -lt 1 ]; then
  sed -n '2,19p' "$0"
  exit 2
fi
SRC=$(realpath "$1")
shift
ROOT=$(cd "$(dirname "$0")/.." && pwd)
if [ -z "${CMAKE_PREFIX_PATH:-}" ] || ! rospack find car > /dev/null 2>&1; then
  echo "upstream_examples: source car's workspace first (source $ROOT/.ws/devel/setup.bash)" >&2
  exit 2
fi
WORK=$(mktemp -d /tmp/car_examples.XXXXXX)
echo "upstream_examples: work folder $WORK"
if [ $# -gt 0 ]; then NAMES=("$@"); else NAMES=(hello_world model_push parameters factory velodyne_plugin); fi

declare -A BUILT
for n in "${NAMES[@]}"; do
  [ -d "$SRC/$n" ] || { BUILT[$n]="absent"; continue; }
  cc=$(ls "$SRC/$n"/*.cc 2>/dev/null | head -1)
  [ -n "$cc" ] || { BUILT[$n]="no .cc"; continue; }
  mkdir -p "$WORK/$n/build"
  cat > "$WORK/$n/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.16)
project(${n}_example CXX)
find_package(gazebo REQUIRED)
include_directories(\${GAZEBO_INCLUDE_DIRS})
link_directories(\${GAZEBO_LIBRARY_DIRS})
set(CMAKE_CXX_FLAGS "\${CMAKE_CXX_FLAGS} \${GAZEBO_CXX_FLAGS}")
add_library($n SHARED $cc)
target_link_libraries($n \${GAZEBO_LIBRARIES})
CMAKE
  if (cd "$WORK/$n/build" && cmake .. > cmake.log 2>&1 && make > make.log 2>&1); then
    BUILT[$n]="yes"
  else
    BUILT[$n]="no: $(grep -m1 -E 'error|Error' "$WORK/$n/build/"*.log | cut -c1-160)"
  fi
done

# ---- run each built example in its world, in car's node, through car.testing (a master of its own) -------------
/usr/bin/python3 - "$SRC" "$WORK" "${NAMES[@]}" <<'PY'
import glob, math, os, re, sys, tempfile
src, work, names = sys.argv[1], sys.argv[2], sys.argv[3:]
from car.testing.sim import Sim

def node_log(sim):
    text = ''
    for f in glob.glob(os.path.join(sim.log_dir, '*.log')):
        text += open(f, errors='replace').read()
    return text

def world_of(n):
    worlds = glob.glob(os.path.join(src, n, '*.world'))
    return worlds[0] if worlds else None

def check(n, sim):
    import rospy
    from gazebo_msgs.srv import GetWorldProperties, GetJointProperties
    if n == 'hello_world':
        sim.run_for(0.1)
        return 'prints "Hello World!" %d time(s)' % node_log(sim).count('Hello World!')
    if n == 'model_push':
        # SetLinearVel(0.3, 0, 0) each step; the ground's friction takes at most mu g dt = 0.0098 m/s of it within a
        # step (mu 1, dt 1 ms), so the box covers between 0.29 and 0.30 m in 1 s
        # A unit cube with mu 1 is at its tipping threshold (friction's moment mu m g h/2 equals gravity's m g w/2
        # about the front edge), so whether it tips is decided by rounding: the row says how far it tilted.
        x0 = sim.pose('box').x
        sim.run_for(1.0)
        p = sim.pose('box')
        return 'box moved %.4f m along x in 1 s (0.29..0.30 sliding flat); tilt %.1f deg' % (
            p.x - x0, math.degrees(math.hypot(p.roll, p.pitch)))
    if n == 'parameters':
        sim.run_for(0.1)
        lines = [l for l in node_log(sim).splitlines() if 'value' in l]
        return 'printed %d value line(s): %s' % (len(lines), ' | '.join(repr(l) for l in lines))
    if n == 'factory':
        sim.run_for(0.1)
        names = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)().model_names
        # the three inserted models at their poses: box (model://box's own pose), unique_sphere (1 0 0),
        # cylinder (the ~/factory message's 1 -2 0), each as it stands after 0.1 s
        return 'models: %s' % ', '.join(
            n if n == 'ground_plane' else '%s at (%.2f %.2f %.2f)' % ((n,) + tuple(getattr(sim.pose(n), a)
                                                                               for a in 'xyz'))
            for n in names)
    if n == 'velodyne_plugin':
        sim.run_for(3.0)
        props = rospy.ServiceProxy('/gazebo/get_joint_properties', GetJointProperties)
        js = [j for j in ('my_velodyne::velodyne_hdl-32::joint', 'velodyne_hdl-32::joint') if props(j).success]
        return 'joint rate %.3f rad/s after 3 s' % props(js[0]).rate[0] if js else 'no joint velodyne_hdl-32::joint'
    return 'ran'

rows = []
for n in names:
    lib = glob.glob(os.path.join(work, n, 'build', 'lib*.so'))
    world = world_of(n)
    if not lib or not world:
        rows.append((n, 'not run (%s)' % ('not built' if not lib else 'no .world')))
        continue
    os.environ['GAZEBO_PLUGIN_PATH'] = os.pathsep.join([os.path.join(work, n), os.path.join(work, n, 'build')])
    os.environ['GAZEBO_MODEL_PATH'] = os.pathsep.join(
        [os.path.join(src, n, 'models')] + [p for p in os.environ.get('GAZEBO_MODEL_PATH', '').split(os.pathsep) if p])
    try:
        sim = Sim(world=world)
        try:
            rows.append((n, check(n, sim)))
        finally:
            sim.close()
    except Exception as e:  # a run that fails is a row, not the end of the table
        refusal = [l for l in str(e).splitlines() if 'cannot load the world' in l]
        if not refusal:
            rows.append((n, 'failed: %s' % str(e).splitlines()[0][:160]))
            continue
        # The world refused as malformed (parameters.world: a Gazebo 1.2 file whose <world> is never closed, which
        # Gazebo 11's sdformat refuses too): the plug-in runs with its <plugin> elements, as written, in an
        # otherwise empty SDF 1.6 world.
        plugins = re.findall(r'<plugin\b.*?</plugin>|<plugin\b[^>]*/>', open(world).read(), re.S)
        wrapped = os.path.join(work, n, 'in_empty.world')
        with open(wrapped, 'w') as f:
            f.write('<?xml version="1.0"?>\n<sdf version="1.6"><world name="default">%s</world></sdf>\n'
                    % ''.join(plugins))
        what = 'its world refused (%s); ' % re.sub(r'\x1b\[[0-9;]*m', '', refusal[0]).split('cannot load the world: ')[-1][:120]
        try:
            sim = Sim(world=wrapped)
            try:
                rows.append((n, what + 'in an empty world: ' + check(n, sim)))
            finally:
                sim.close()
        except Exception as e2:
            rows.append((n, what + 'failed in an empty world too: %s' % str(e2).splitlines()[0][:160]))
with open(os.path.join(work, 'ran.txt'), 'w') as f:
    for n, what in rows:
        f.write('%s\t%s\n' % (n, what))
PY

echo
echo "| example | built | ran |"
echo "|---|---|---|"
for n in "${NAMES[@]}"; do
  ran=$(awk -F'\t' -v n="$n" '$1 == n {print $2}' "$WORK/ran.txt" 2>/dev/null)
  echo "| $n | ${BUILT[$n]} | ${ran:-not run} |"
done
