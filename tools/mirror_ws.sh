# Sourced by the out-of-CI scripts that build other people's packages unchanged over car's devel space
# (tools/kobuki.sh, tools/real_robots.sh, tools/mimic.sh): the scratch workspace, the export of a repository
# snapshot into it, its build, and one run of a launch file with a probe beside it on a fresh master.
# The caller sets TOOL (its name, for messages), MIRROR (the folder of OWNER+NAME snapshots) and ROOT (car's root).

# require_debs WHO HEADER:PACKAGE...: stops, naming the Debian packages to install, unless each HEADER (a path under
# /usr/include) is there; WHO says what needs them.
require_debs() {
  local who=$1 missing="" pair
  shift
  for pair in "$@"; do
    [ -f "/usr/include/${pair%%:*}" ] || missing+=" ${pair#*:}"
  done
  if [ -n "$missing" ]; then
    echo "$TOOL: $who need(s) Debian packages that are not installed:$missing" >&2
    echo "$TOOL: apt-get install$missing" >&2
    exit 2
  fi
}

# mirror_ws_begin: stops unless car's workspace is sourced; makes WS=/tmp/car_TOOL.XXXXXX with WS/src as SRC.
mirror_ws_begin() {
  if [ -z "${CMAKE_PREFIX_PATH:-}" ] || ! rospack find car > /dev/null 2>&1; then
    echo "$TOOL: source car's workspace first (source $ROOT/.ws/devel/setup.bash)" >&2
    exit 2
  fi
  WS=$(mktemp -d "/tmp/car_$TOOL.XXXXXX")
  SRC=$WS/src
  mkdir -p "$SRC"
  echo "$TOOL: workspace $WS"
}

# export_from OWNER+NAME BRANCH DEST PATH...: the files under PATH (. for all) at BRANCH into DEST, from
# MIRROR/OWNER+NAME (a git dir, a folder holding repo/, or a checkout), file by file: a snapshot may lack some large
# objects, which git archive stops at (each is listed in WS/absent.txt). BRANCH HEAD: the snapshot's default branch.
# Appends the commit to WS/sources.txt.
export_from() {
  local name=$1 branch=$2 dest=$3
  shift 3
  local d=$MIRROR/$name gitdir mode type sha path label
  if [ -d "$d/repo" ]; then gitdir=$d/repo; elif [ -d "$d/.git" ]; then gitdir=$d/.git; else gitdir=$d; fi
  if ! git --git-dir="$gitdir" rev-parse -q --verify "$branch^{commit}" > /dev/null; then
    echo "$TOOL: $gitdir has no branch $branch" >&2
    exit 2
  fi
  while IFS=$'\t' read -r meta path; do
    read -r mode type sha <<< "$meta"
    [ "$type" = blob ] || continue
    mkdir -p "$dest/$(dirname "$path")"
    if [ "$mode" = 120000 ]; then
      ln -sf "$(git --git-dir="$gitdir" cat-file blob "$sha")" "$dest/$path"
    elif ! git --git-dir="$gitdir" cat-file blob "$sha" > "$dest/$path" 2> /dev/null; then
      rm -f "$dest/$path"
      echo "$name: $path absent from the snapshot" >> "$WS/absent.txt"
    fi
    [ "$mode" = 100755 ] && [ -f "$dest/$path" ] && chmod +x "$dest/$path"
  done < <(git --git-dir="$gitdir" ls-tree -r "$branch" -- "$@")
  label=$branch
  [ "$branch" != HEAD ] || label=$(git --git-dir="$gitdir" symbolic-ref --short HEAD 2> /dev/null || echo HEAD)
  echo "$name @ $(git --git-dir="$gitdir" rev-parse --short "$branch") ($label)" >> "$WS/sources.txt"
}

# mirror_ws_build: catkin_make in WS (stops with the first errors when it fails), then sources its devel space.
mirror_ws_build() {
  if ! (cd "$WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -j2 > "$WS/build.log" 2>&1); then
    echo "$TOOL: the scratch workspace did not build; the first errors ($WS/build.log):" >&2
    grep -m 10 -E "error|Error" "$WS/build.log" >&2
    exit 1
  fi
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
}

# run_beside LABEL PROBE_COMMAND... -- ROSLAUNCH_ARGS...: a fresh master on a free port with /use_sim_time, the probe
# started first (its stdout to WS/results-LABEL.txt, stderr to WS/probe-LABEL.log), then roslaunch; when the probe
# ends, the launch and the master are stopped. Returns the probe's exit status.
run_beside() {
  local label=$1 probe_cmd=() core probe rl rc
  shift
  while [ $# -gt 0 ] && [ "$1" != -- ]; do probe_cmd+=("$1"); shift; done
  shift
  local port=$((11400 + RANDOM % 400))
  export ROS_MASTER_URI=http://localhost:$port
  roscore -p "$port" > "$WS/roscore-$label.log" 2>&1 &
  core=$!
  sleep 3
  rosparam set /use_sim_time true
  "${probe_cmd[@]}" > "$WS/results-$label.txt" 2> "$WS/probe-$label.log" &
  probe=$!
  sleep 2
  roslaunch "$@" > "$WS/launch-$label.log" 2>&1 &
  rl=$!
  wait "$probe"
  rc=$?
  kill -INT "$rl" 2> /dev/null
  wait "$rl" 2> /dev/null
  kill -INT "$core" 2> /dev/null
  wait "$core" 2> /dev/null
  return $rc
}
