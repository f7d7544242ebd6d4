// libFuzzer target: an SDF world file's text (load_world_string: sdformat, includes, <state>), simulated and stepped
// as sim_node would; then every model, static ones too, moved by set_model_state (0.25 m along x, 0.3 rad about
// z, as gazebo_ros's SetModelState would) and stepped again. Rule: fuzz_common.hpp; a model that model_names()
// lists must take its new state, and a static one must report it.
#include <cstdint>
#include <string>

#include "car_sim/description.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  car_fuzz::run([&] {
    car_sim::World w(car_sim::load_world_string(xml, "fuzz.world"));
    if (!car_fuzz::step_and_check(w, 500)) return;
    const Eigen::Isometry3d move = Eigen::Translation3d(0.25, 0.0, 0.0) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
    for (const auto& n : w.model_names()) {
      car_sim::ModelState s = w.model_state(n);
      s.pose = move * s.pose;
      if (!s.pose.matrix().allFinite()) continue;  // a pose near the largest double: the move overflows, not car
      try {
        w.set_model_state(n, s);
      } catch (const std::invalid_argument& e) {
        car_fuzz::broke("set_model_state('" + n + "') refused: " + e.what());
      }
      if (!w.model_properties(n).is_static) continue;
      const car_sim::ModelState now = w.model_state(n);
      if (!now.pose.isApprox(s.pose, 1e-9) || !now.linear.isZero(0.0) || !now.angular.isZero(0.0))
        car_fuzz::broke("static model '" + n + "' does not report the state it was given");
    }
    car_fuzz::step_and_check(w, 500);
  });
  return 0;
}
