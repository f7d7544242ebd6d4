// libFuzzer target: an SDF <model> document (spawn_model -sdf / -database), spawned into the empty world and stepped.
// Rule: fuzz_common.hpp.
#include <cstdint>
#include <string>

#include "car_sim/description.hpp"
#include "car_sim/sdf_model.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  car_fuzz::run([&] {
    const car_sim::SdfRobot robot = car_sim::load_sdf_model_string(xml, "fuzz.sdf");
    car_sim::World w(car_fuzz::empty());
    w.spawn_sdf(robot, "robot", Eigen::Isometry3d::Identity());
    car_fuzz::step_and_check(w);
  });
  return 0;
}
