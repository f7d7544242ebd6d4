// Many robots in one process: N seed cars, each with its lidar (360 rays, 5.5 Hz) computing and its diff drive
// commanded, on a grid in the empty world; prints the real-time factor for each N and the largest N that
// holds >= 1x real time (issue 13's "many robots" row).
// usage: bench_many URDF [SIM_SECONDS] [MAX_N] [only]
// With `only`, it times MAX_N cars once (for profilers and alternated old/new runs) and also prints the wall time
// per car and step.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "car_sim/world.hpp"

// [x real time] of N cars for `seconds` of sim time, after one settling second.
static double rtf(const car_sim::RobotModel& car, int n, double seconds) {
  car_sim::World w(car_sim::empty_world());
  // a square grid, 1.5 m apart: each car drives a 0.25 m circle (v 0.25 m/s, w 1 rad/s) and never meets another
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  for (int i = 0; i < n; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(1.5 * (i % side), 1.5 * (i / side), 0.0);
    const std::string name = "car" + std::to_string(i);
    w.spawn(car, name, pose);
    w.set_cmd_vel(name, 0.25, 1.0);
    w.set_sensor_active(name, "gazebo_rplidar", true);
  }
  w.step(static_cast<uint64_t>(1.0 / w.dt()));
  w.take_outputs();
  const auto t0 = std::chrono::steady_clock::now();
  const uint64_t steps = static_cast<uint64_t>(seconds / w.dt());
  // outputs are taken every sim second, as a node would drain them
  for (uint64_t done = 0; done < steps;) {
    const uint64_t k = std::min<uint64_t>(steps - done, static_cast<uint64_t>(1.0 / w.dt()));
    w.step(k);
    w.take_outputs();
    done += k;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return seconds / wall;
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_many URDF [SIM_SECONDS] [MAX_N] [only]\n");
    return 2;
  }
  const double seconds = argc > 2 ? std::atof(argv[2]) : 5.0;
  const int max_n = argc > 3 ? std::atoi(argv[3]) : 512;
  const car_sim::RobotModel car = car_sim::load_urdf_file(argv[1]);
  if (argc > 4 && std::string(argv[4]) == "only") {
    const double r = rtf(car, max_n, seconds);
    // [us] of wall time per car and 1 ms step
    std::printf("cars %4d: %6.2fx real time, %.2f us per car and step\n", max_n, r, 1e3 / (r * max_n));
    return 0;
  }
  // doubling until below real time, then bisection between the last two down to a step of lo / 32 (4 cars between
  // 128 and 256, so that a target such as 200 is not judged by a step of 8)
  int lo = 0, hi = 0;
  for (int n = 8; n <= max_n; n *= 2) {
    const double r = rtf(car, n, seconds);
    std::printf("cars %4d: %6.2fx real time\n", n, r);
    std::fflush(stdout);
    if (r >= 1.0) {
      lo = n;
    } else {
      hi = n;
      break;
    }
  }
  if (lo > 0 && hi > 0) {
    while (hi - lo > std::max(1, lo / 32)) {
      const int mid = (lo + hi) / 2;
      const double r = rtf(car, mid, seconds);
      std::printf("cars %4d: %6.2fx real time\n", mid, r);
      std::fflush(stdout);
      (r >= 1.0 ? lo : hi) = mid;
    }
  }
  std::printf("many: %d cars at >= 1x real time\n", lo);
  return 0;
}
