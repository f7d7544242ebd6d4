// A frictionless 10 kg box (izz 0.1 kg m^2) on the ground with force and f3d plug-ins on its one link, for the
// wrench kinds' tests.
#pragma once

#include <memory>
#include <string>

#include "car_sim/world.hpp"
#include "test_util.hpp"

namespace car_sim {
namespace test_support {

inline std::unique_ptr<World> wrench_box() {
  const std::string xml = R"(<robot name="box">
  <link name="body">
    <inertial><mass value="10"/><origin xyz="0 0 0.1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
  </link>
  <gazebo reference="body"><mu1>0</mu1><mu2>0</mu2></gazebo>
  <gazebo><plugin name="push" filename="libgazebo_ros_force.so"><bodyName>body</bodyName><topicName>push</topicName></plugin></gazebo>
  <gazebo><plugin name="felt" filename="libgazebo_ros_f3d.so"><bodyName>body</bodyName><topicName>felt</topicName></plugin></gazebo>
</robot>)";
  auto w = std::make_unique<World>(empty_world());
  w->spawn(load_urdf_string(xml, "box.urdf"), "box", at(0, 0, 0));
  return w;
}

}  // namespace test_support
}  // namespace car_sim
