#!/usr/bin/env bash
# Builds bench/peers/ode_skid.cpp against stock ODE (Debian: libode-dev, 0.16) and prints the skid-steer reference
# of docs/COMPAT-physics.md ("Skid steering against stock ODE"): each configuration run with SEEDS seeds of ODE's
# random constraint order (default 16), the circle's radius R = speed / yaw rate, its speed and yaw rate, as
# mean, standard deviation, min and max over the seeds. About 5 s of CPU per run.
# usage: bench/peers/ode_skid.sh [SEEDS]            the table
#        bench/peers/ode_skid.sh run ARGS...        one run of ode_skid (ARGS: see ode_skid.cpp's header)
# Not part of the catkin build.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
out="${TMPDIR:-/tmp}/car-ode_skid"
# stock ODE from Debian, installed when missing (as tools/setup.sh installs the rest)
if ! pkg-config --exists ode; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "ode_skid.sh: installing libode-dev (stock ODE)" >&2
  $sudo apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends libode-dev >/dev/null
fi
mkdir -p "$out"
if [[ ! -x "$out/ode_skid" || "$here/ode_skid.cpp" -nt "$out/ode_skid" ]]; then
  g++ -O2 -std=c++17 -Wall -o "$out/ode_skid" "$here/ode_skid.cpp" $(pkg-config --cflags --libs ode)
fi
if [[ "${1:-}" == run ]]; then
  shift
  exec "$out/ode_skid" "$@"
fi
seeds="${1:-16}"
echo "stock ODE $(pkg-config --modversion ode), $seeds seeds each; circle (0.5 m/s, 0.5 rad/s), last 10 s of 14 s"
# robot and the chassis' centre of mass offset [m] added to the fixture's (husky_description's inertial origin
# -0.00065 -0.085; jackal_description's 0.012 0.002), with Gazebo's cylinder wheels and with spheres (car's rule);
# then with the world's correction cap at the surfaces' max_vel 0.01 m/s (stock ODE has no split: the tyres sink)
while read -r label args; do
  for s in $(seq 0 $((seeds - 1))); do "$out/ode_skid" $args seed=$s; done |
    awk -v label="$label" '
      { match($0, /speed [0-9.]+ m\/s, yaw rate [-0-9.]+ rad\/s, R = [-0-9.]+/); split(substr($0, RSTART, RLENGTH), f, " ")
        v[NR] = f[2]; w[NR] = f[6]; r[NR] = f[10] }
      function stat(x, n,   i, m, s, lo, hi) { m = 0; lo = x[1]; hi = x[1]
        for (i = 1; i <= n; i++) { m += x[i]; if (x[i] < lo) lo = x[i]; if (x[i] > hi) hi = x[i] }
        m /= n; s = 0; for (i = 1; i <= n; i++) s += (x[i] - m) ^ 2; s = sqrt(s / (n - 1))
        return sprintf("%.4f sd %.4f [%.4f, %.4f]", m, s, lo, hi) }
      END { printf "%-36s R %s  speed %s  yaw rate %s\n", label, stat(r, NR), stat(v, NR), stat(w, NR) }'
done <<'EOF'
husky_centred_cylinder husky
husky_offset_cylinder husky com_x=-0.00065 com_y=-0.085
husky_centred_sphere husky wheel=sphere
husky_offset_sphere husky wheel=sphere com_x=-0.00065 com_y=-0.085
jackal_centred_cylinder jackal
jackal_real_com_cylinder jackal com_x=0.012 com_y=0.002
jackal_centred_sphere jackal wheel=sphere
husky_centred_cylinder_cap0.01 husky max_vel=0.01
husky_offset_cylinder_cap0.01 husky com_x=-0.00065 com_y=-0.085 max_vel=0.01
husky_centred_sphere_cap0.01 husky wheel=sphere max_vel=0.01
husky_offset_sphere_cap0.01 husky wheel=sphere com_x=-0.00065 com_y=-0.085 max_vel=0.01
jackal_centred_cylinder_cap0.01 jackal max_vel=0.01
EOF
