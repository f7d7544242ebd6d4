// What the ros_control gtests share: a fixture robot from test/data/control/ spawned in the empty world, its
// controller manager, and a strict switch that starts controllers.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "car_sim/world.hpp"
#include "ros_control/controllers.hpp"
#include "test_util.hpp"

namespace car_sim::control_test {

constexpr double kG = 9.8;  // [m/s^2], the empty world's gravity (SDF's default <gravity> 0 0 -9.8)

// test/data/control/`file` spawned as `name` at the origin of the empty world.
inline std::unique_ptr<World> world_with(const std::string& file, const std::string& name) {
  auto w = std::make_unique<World>(empty_world());
  w->spawn(load_urdf_file(data_path("control/" + file)), name, at(0, 0, 0));
  return w;
}

inline RosControl& manager(World& w, const std::string& robot) {
  return *dynamic_cast<RosControl*>(w.plugin(robot, "gazebo_ros_control"));
}

// Starts `names` with a strict switch (fails the test with the manager's reason).
inline void start(RosControl& rc, const std::vector<std::string>& names) {
  std::string why;
  ASSERT_TRUE(rc.switch_controllers(names, {}, true, &why)) << why;
}

}  // namespace car_sim::control_test
