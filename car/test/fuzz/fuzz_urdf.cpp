// libFuzzer target: URDF text with <gazebo> blocks and plug-in parameters, as spawn_model hands it to the node
// (load_urdf_string, the plug-ins resolved, spawned into Gazebo's empty world and stepped). Rule: fuzz_common.hpp.
#include <cstdint>
#include <string>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"
#include "car_sim/plugins.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  car_fuzz::run([&] {
    const car_sim::RobotModel model = car_sim::load_urdf_string(xml, "fuzz.urdf");
    car_sim::resolve_plugins(model);
    car_sim::World w(car_fuzz::empty());
    w.spawn(model, "robot", Eigen::Isometry3d::Identity());
    car_fuzz::step_and_check(w);
  });
  return 0;
}
