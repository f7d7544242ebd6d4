// Sensor throughput of the core, seed car in box_house: lidar rays/s and depth frames/s (640 x 480), with every
// part of the Kinect's frames (colour, depth, cloud) and with its depth image alone (Plugin::set_parts).
// usage: bench_sensors URDF WORLD [SECONDS]   (OMP_NUM_THREADS sets the cores used)
#include <omp.h>

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "camera/camera.hpp"
#include "car_sim/world.hpp"
#include "laser/laser.hpp"

using clk = std::chrono::steady_clock;

// Wall seconds to simulate `seconds` with the given sensor plug-ins listened to.
static std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

static double run(const std::string& urdf_xml, const std::string& world, double seconds,
                  std::initializer_list<const char*> active, car_sim::OutputQueue* out, uint32_t parts = ~0u) {
  car_sim::World w(car_sim::load_world_file(world));
  w.spawn(car_sim::load_urdf_string(urdf_xml, "car"), "mycar", Eigen::Isometry3d::Identity());
  w.set_cmd_vel("mycar", 1.0, 1.0);
  for (const char* p : active) {
    w.set_sensor_active("mycar", p, true);
    w.plugin("mycar", p)->set_parts(parts);
  }
  w.step(3000);
  w.take_outputs();
  const auto t0 = clk::now();
  w.step(static_cast<uint64_t>(seconds / w.dt()));
  const double s = std::chrono::duration<double>(clk::now() - t0).count();
  *out = w.take_outputs();
  return s;
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_sensors URDF WORLD [SECONDS]\n");
    return 2;
  }
  // Camera frames are several MB each: keep freed blocks in the heap instead of returning them to the kernel,
  // so the next frame does not pay page faults (glibc otherwise mmaps blocks over 128 kB).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  const double T = argc > 3 ? std::atof(argv[3]) : 5.0;
  std::ifstream in(argv[1]);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string seed = ss.str();
  // a lidar of 100 000 beams (the validation limit per axis) measures the ray kernel (plus the scan's own work) rather than per-scan overhead
  const std::string wide = replace(seed, "<samples>360</samples>", "<samples>100000</samples>");
  // the full stack: depth at 10 Hz
  const std::string full10 = replace(replace(seed, "<update_rate>20.0</update_rate>", "<update_rate>10</update_rate>"),
                                     "<update_rate>20.0</update_rate>", "<update_rate>10</update_rate>");
  car_sim::OutputQueue o;
  // outputs of one type among a run's outputs
  auto of = [&o](auto* type) {
    using Out = std::remove_pointer_t<decltype(type)>;
    std::vector<const Out*> v;
    for (const auto& x : o)
      if (auto* p = dynamic_cast<const Out*>(x.get())) v.push_back(p);
    return v;
  };
  // The sensors' cost is a run's time less physics alone. Physics alone is timed before each sensor run and the
  // shortest of the three is subtracted: the machine's other load only lengthens a run, and a lengthened baseline
  // would flatter the sensors (bench_physics.py keeps the best of several processes of this bench).
  double physics = run(seed, argv[2], T, {}, &o);
  const double lidar = run(wide, argv[2], T, {"gazebo_rplidar"}, &o);
  const auto scan_list = of(static_cast<car_sim::LaserScanOut*>(nullptr));
  const size_t scans = scan_list.size(), rays = scans * (scans ? scan_list[0]->ranges.size() : 0);
  physics = std::min(physics, run(seed, argv[2], T, {}, &o));
  const double depth = run(seed, argv[2], T, {"kinect_camera_controller"}, &o);
  const size_t frames = of(static_cast<car_sim::CameraOut*>(nullptr)).size();
  physics = std::min(physics, run(seed, argv[2], T, {}, &o));
  const double depth_alone = run(seed, argv[2], T, {"kinect_camera_controller"}, &o, car_sim::kCameraDepth);
  const size_t frames_alone = of(static_cast<car_sim::CameraOut*>(nullptr)).size();
  physics = std::min(physics, run(seed, argv[2], T, {}, &o));
  const double full = run(full10, argv[2], T, {"gazebo_rplidar", "kinect_camera_controller"}, &o);
  std::printf("threads %d\n", omp_get_max_threads());
  std::printf("physics alone: %.1fx real time\n", T / physics);
  std::printf("lidar: %zu scans of 100000 rays in %.4f s over physics -> %.2f M rays/s\n", scans, lidar - physics,
              rays / std::max(1e-9, lidar - physics) / 1e6);
  std::printf("depth: %zu frames 640x480 in %.3f s over physics -> %.1f frames/s = %.1f M rays/s\n", frames,
              depth - physics, frames / (depth - physics), frames * 307200.0 / (depth - physics) / 1e6);
  std::printf("depth image alone: %zu frames 640x480 in %.3f s over physics -> %.1f frames/s\n", frames_alone,
              depth_alone - physics, frames_alone / (depth_alone - physics));
  std::printf("full stack (physics 1 kHz, lidar 5.5 Hz, depth 10 Hz): %.1fx real time\n", T / full);
  return 0;
}
