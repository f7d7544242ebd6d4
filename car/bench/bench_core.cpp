// Core physics steps/s for a robot (default: the seed car) in a world (default: box_house), no ROS.
// usage: bench_core URDF [WORLD|-] [STEPS] [ITERATIONS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "car_sim/world.hpp"

// [s] CPU time this thread has run (excludes time it waited for a core: the machine's other load)
static double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_core URDF [WORLD|-] [STEPS] [ITERATIONS]\n");
    return 2;
  }
  const std::string world = argc > 2 ? argv[2] : "-";
  const long steps = argc > 3 ? std::atol(argv[3]) : 20000;
  car_sim::WorldOptions o;
  if (argc > 4) o.solver_iterations = std::atoi(argv[4]);
  car_sim::World w(world == "-" ? car_sim::empty_world() : car_sim::load_world_file(world), o);
  w.spawn(car_sim::load_urdf_file(argv[1]), "mycar", Eigen::Isometry3d::Identity());
  w.set_cmd_vel("mycar", 1.0, 1.0);
  // settle: world objects fall asleep after 2 s at rest, as they would in a long run
  w.step(3000);
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu_seconds();
  w.step(static_cast<uint64_t>(steps));
  const double c = thread_cpu_seconds() - c0;
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double rate = static_cast<double>(steps) / s;
  // wall rate first (bench_physics.py reads the second word); then the rate per CPU second of the stepping thread
  std::printf("core: %.0f steps/s = %.1fx real time at dt %.4f s (%ld steps in %.3f s; %.0f steps per CPU second)\n",
              rate, rate * w.dt(), w.dt(), steps, s, static_cast<double>(steps) / std::max(c, 1e-9));
  return 0;
}
