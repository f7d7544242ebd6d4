# Sourced by tools/sanitize.sh and tools/fuzz.sh: make_workspace DIR makes a catkin workspace DIR/ (git-ignored)
# whose src/ links this repository and its compat packages the way tools/setup.sh links .ws/, so an
# instrumented build lives beside .ws/ without touching it.
make_workspace() {
  local ws="$1" root entry pkg name
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
  mkdir -p "$ws/src/car"
  for entry in "$root"/*; do
    ln -sfn "$root/$(basename "$entry")" "$ws/src/car/$(basename "$entry")"
  done
  for pkg in "$root"/compat/*/; do
    name="$(basename "$pkg")"
    [ -f "/opt/ros/noetic/share/$name/package.xml" ] || [ -f "/usr/share/$name/package.xml" ] ||
      ln -sfn "$root/compat/$name" "$ws/src/$name"
  done
}
