// The seed car in box_house, for the sensor kinds' tests.
#pragma once

#include <memory>
#include <string>

#include "car_sim/world.hpp"
#include "test_util.hpp"

namespace car_sim {
namespace test_support {

inline std::string car_xml(bool noise) {
  std::string xml = read_text("test/data/car_camera_lidar04.urdf");
  if (!noise) xml.replace(xml.find("<type>gaussian</type>"), 21, "<type>none</type>");
  return xml;
}

inline std::unique_ptr<World> world_with_car(bool noise, double x = 0, double y = 0, double yaw = 0, uint64_t seed = 0) {
  WorldOptions o;
  o.seed = seed;
  auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"), o);
  w->spawn(load_urdf_string(car_xml(noise), "car"), "mycar", at(x, y, yaw));
  return w;
}

}  // namespace test_support
}  // namespace car_sim
