// libFuzzer target: a ros_control controller's parameters, as controller_manager/load_controller hands them to the
// core (src/ros/adapters/ros_control.cpp flattens the YAML on the parameter server into control::Params: "pid/p" ->
// {"100"}, "joints" -> {"a", "b"}). The YAML text itself is parsed by rosparam (Python), not by car. The input is
// the flattened map, one key a line: `key: v1, v2, ...`. The controller is loaded into test/data/control/arm.urdf's
// manager, started, stepped 1000 steps and unloaded. Refusals: ControllerError (load), a false strict switch.
#include <cstdint>
#include <sstream>
#include <string>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"
#include "fuzz_common.hpp"
#include "ros_control/ros_control.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const car_sim::RobotModel arm = car_sim::load_urdf_file(CAR_SOURCE_DIR "/test/data/control/arm.urdf");
  car_sim::control::Params params;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  for (std::string l; std::getline(in, l);) {
    const auto colon = l.find(':');
    if (colon == std::string::npos) continue;
    auto& values = params[l.substr(0, colon)];
    std::istringstream vs(l.substr(colon + 1));
    for (std::string v; std::getline(vs, v, ',');) {
      const auto b = v.find_first_not_of(' '), e = v.find_last_not_of(' ');
      values.push_back(b == std::string::npos ? "" : v.substr(b, e - b + 1));
    }
  }
  const auto t = params.find("type");
  if (t == params.end() || t->second.size() != 1) return 0;  // the adapter refuses this itself
  car_fuzz::run([&] {
    car_sim::World w(car_fuzz::empty());
    w.spawn(arm, "arm", Eigen::Isometry3d::Identity());
    auto* rc = dynamic_cast<car_sim::RosControl*>(w.plugin("arm", "gazebo_ros_control"));
    if (!rc) car_fuzz::broke("the arm fixture has no gazebo_ros_control");
    try {
      rc->load("c", t->second[0], params);
    } catch (const car_sim::control::ControllerError& e) {
      if (std::string(e.what()).empty()) car_fuzz::broke("ControllerError without a reason");
      return;
    }
    std::string why;
    if (rc->switch_controllers({"c"}, {}, true, &why)) {
      car_fuzz::step_and_check(w);
      if (!rc->switch_controllers({}, {"c"}, true, &why)) car_fuzz::broke("the controller does not stop: " + why);
    } else if (why.empty()) {
      car_fuzz::broke("a refused switch without a reason");
    }
    rc->unload("c");
  });
  return 0;
}
