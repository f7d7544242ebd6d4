// The cost of users' Gazebo plug-ins on a step (issue 49, docs/PLUGINS.md "Tested"): the seed car in box_house with
// 0, 1 and 10 copies of a model plug-in whose WorldUpdateBegin callback is empty (plugins/empty_update.cc), each
// world stepped in blocks, the three interleaved round after round (the order rotates) so the machine's load falls
// on all three alike. Time is the stepping thread's CPU time. Prints each count's median step cost [µs], the cost
// of one callback [µs] = (median(10) - median(0)) / 10, and ten plug-ins' overhead [%] of the seed car's step.
// usage: bench_gazebo URDF WORLD PLUGIN_DIR [ROUNDS] [STEPS_PER_BLOCK]
#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "car_sim/world.hpp"

namespace {

// [s] CPU time this thread has run (excludes time it waited for a core: the machine's other load)
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The URDF text with n <gazebo> blocks naming the empty plug-in added before </robot>.
std::string with_plugins(std::string urdf, int n) {
  std::string blocks;
  for (int i = 0; i < n; ++i)
    blocks += "  <gazebo><plugin name=\"empty_" + std::to_string(i) +
              "\" filename=\"libcar_bench_empty_update.so\"/></gazebo>\n";
  const size_t end = urdf.rfind("</robot>");
  if (end == std::string::npos) throw std::runtime_error("bench_gazebo: no </robot> in the URDF");
  return urdf.insert(end, blocks);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: bench_gazebo URDF WORLD PLUGIN_DIR [ROUNDS] [STEPS_PER_BLOCK]\n");
    return 2;
  }
  const int rounds = argc > 4 ? std::atoi(argv[4]) : 15;
  const long steps = argc > 5 ? std::atol(argv[5]) : 2000;
  // the plug-in's folder alone on the search path (docs/PLUGINS.md "Loading")
  setenv("GAZEBO_PLUGIN_PATH", argv[3], 1);
  std::ifstream f(argv[1]);
  std::stringstream text;
  text << f.rdbuf();
  const std::vector<int> counts = {0, 1, 10};
  std::vector<std::unique_ptr<car_sim::World>> worlds;
  for (int n : counts) {
    auto w = std::make_unique<car_sim::World>(car_sim::load_world_file(argv[2]));
    w->spawn(car_sim::load_urdf_string(with_plugins(text.str(), n), argv[1]), "mycar", Eigen::Isometry3d::Identity());
    // every plug-in loaded (a file not found leaves plugin-unknown, a failed load plugin-not-loaded), or the
    // figures would be of fewer; the call count below checks it again
    for (const auto& d : w->robot("mycar").config.diagnostics)
      if (d.code == "plugin-unknown" || d.code == "plugin-not-loaded") {
        std::fprintf(stderr, "bench_gazebo: %s\n", d.message.c_str());
        return 1;
      }
    w->set_cmd_vel("mycar", 1.0, 1.0);
    // settle: world objects fall asleep after 2 s at rest, as they would in a long run
    w->step(3000);
    std::printf("gazebo: %d plug-in(s) loaded\n", n);
    worlds.push_back(std::move(w));
  }
  // [µs] per step, one sample per round and count
  std::vector<std::vector<double>> us(counts.size());
  for (int r = 0; r < rounds; ++r) {
    for (size_t k = 0; k < counts.size(); ++k) {
      const size_t i = (k + static_cast<size_t>(r)) % counts.size();
      const double c0 = thread_cpu_seconds();
      worlds[i]->step(static_cast<uint64_t>(steps));
      us[i].push_back(1e6 * (thread_cpu_seconds() - c0) / static_cast<double>(steps));
    }
  }
  // every callback ran: the plug-in counts its calls (empty_update.cc); 11 plug-ins over the timed and settling steps
  const auto* calls = static_cast<const unsigned long*>(dlsym(RTLD_DEFAULT, "car_bench_empty_update_calls"));
  const unsigned long want = 11UL * static_cast<unsigned long>(3000 + rounds * steps);
  if (!calls || *calls != want) {
    std::fprintf(stderr, "bench_gazebo: the plug-ins' callbacks ran %lu times, not %lu\n", calls ? *calls : 0UL, want);
    return 1;
  }
  std::printf("gazebo: %lu callbacks ran, as many as 11 plug-ins times the steps\n", *calls);
  const double m0 = median(us[0]), m1 = median(us[1]), m10 = median(us[2]);
  std::printf("gazebo: step cost, median of %d interleaved rounds of %ld steps: 0 plug-ins %.2f us, 1 %.2f us, "
              "10 %.2f us\n", rounds, steps, m0, m1, m10);
  std::printf("gazebo: one empty WorldUpdateBegin callback %.3f us per step (1 plug-in: %.3f us); ten plug-ins "
              "%+.2f %% of the seed car's step\n", (m10 - m0) / 10.0, m1 - m0, 100.0 * (m10 - m0) / m0);
  return 0;
}
