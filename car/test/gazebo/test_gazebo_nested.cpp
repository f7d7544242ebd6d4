// A model plug-in on a model that only includes another model, as Gazebo's "Build a plugin" tutorial attaches its
// velodyne plug-in (docs/COMPAT-sdf.md 16a, docs/PLUGINS.md): Gazebo 11 flattens the include into the model, so the
// plug-in's Model has the included joint (GetJointCount() == 1, GetJoints()[0]) and its JointController turns it.
// The included model is test/data/nested_models/spinner, the plug-in test/gazebo/plugins/velocity_pid.cc.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;

// holder includes spinner and carries the plug-in, as the tutorial's my_velodyne; no gravity, 1 ms steps.
const char* kWorld = R"(<?xml version="1.0"?>
<sdf version="1.6">
  <world name="w">
    <gravity>0 0 0</gravity>
    <physics type="ode"><max_step_size>0.001</max_step_size><real_time_factor>1</real_time_factor></physics>
    <model name="holder">
      <pose>0 0 5 0 0 0</pose>
      <include><uri>model://spinner</uri></include>
      <plugin name="spin" filename="libvelocity_pid.so"><velocity>10</velocity></plugin>
    </model>
  </world>
</sdf>)";

// The test plug-ins' folder and test/data/nested_models (its one model, spinner: base (2 kg) and, 0.2 m above it on
// the continuous joint axle (about z), rotor (1 kg); Izz 0.5 kg m^2 each, both centres of mass on the axis) as the
// search paths for one test, put back after.
class GazeboNested : public ::testing::Test {
 protected:
  ScopedEnv env_{{"GAZEBO_PLUGIN_PATH", kDir}, {"GAZEBO_MODEL_PATH", data_path("nested_models")}};
};

}  // namespace

// velocity_pid returns from Load unless GetJointCount() > 0, then puts a P controller (p 0.1) towards 10 rad/s on
// GetJoints()[0]: spinner::axle, the model's only joint. Effort 0.1 (10 - v_k) each step turns base and rotor (Izz
// 0.5 each) apart, so the joint speeds up by 4 x effort x dt: v_k+1 = v_k + 0.0004 (10 - v_k), v_n = 10 (1 - 0.9996^n).
TEST_F(GazeboNested, AModelPluginTurnsTheJointOfTheModelItIncludes) {
  World w(load_world_string(kWorld, "holder.world"));
  ASSERT_EQ(w.model_names(), std::vector<std::string>{"holder"});
  w.step(1000);
  EXPECT_NEAR(w.joint_velocity("holder", "spinner::axle"), 10.0 * (1.0 - std::pow(0.9996, 1000)), 1e-9);  // 3.297
}
