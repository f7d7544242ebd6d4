# Sourced by tools/sanitize.sh and tools/fuzz.sh: make_workspace DIR makes a catkin workspace DIR/ (git-ignored)
# whose src/ links car/ and its compat packages the way tools/setup.sh links .ws/, so an
# instrumented build lives beside .ws/ without touching it.
make_workspace() {
  local ws="$1" root entry pkg name
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
  mkdir -p "$ws/src"
  ln -sfn "$root/car" "$ws/src/car"
  for pkg in "$root"/compat/*/; do
    name="$(basename "$pkg")"
    [ -f "/opt/ros/noetic/share/$name/package.xml" ] || [ -f "/usr/share/$name/package.xml" ] ||
      ln -sfn "$root/compat/$name" "$ws/src/$name"
  done
}

# Debian's clang 14 with its sanitizer and libFuzzer runtimes and its OpenMP (car_sim's islands under clang):
# installed when missing, as tools/setup.sh installs the rest.
ensure_clang() {
  local p missing=()
  for p in clang-14 libclang-rt-14-dev libomp-14-dev; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "sanitizers: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get -o DPkg::Lock::Timeout=900 update -qq &&
    DEBIAN_FRONTEND=noninteractive $sudo apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends \
      "${missing[@]}" >/dev/null
}
