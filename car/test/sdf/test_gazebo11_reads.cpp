// Issue 29 item 4: SDF that Gazebo 11 loads and car refused (test/data/worlds/gazebo11_reads.world, its comments
// give the expected values; docs/COMPAT-sdf.md and docs/COMPAT-validation.md give the rules).
#include <gtest/gtest.h>

#include "camera/camera.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"
#include "validate.hpp"

using namespace car_sim;

namespace {

const std::string kWorld = "worlds/gazebo11_reads.world";

const WorldModelDesc& model(const WorldDescription& d, const std::string& name) {
  const WorldModelDesc* m = d.find_model(name);
  if (!m) throw std::runtime_error("no model " + name);
  return *m;
}

}  // namespace

// <link><gravity> is a boolean: false, 0, 1 are read (not refused as "not a finite number").
TEST(Gazebo11Reads, LinkGravityIsABooleanSwitch) {
  const WorldDescription d = load_world_file(data_path(kWorld));
  EXPECT_FALSE(model(d, "floater").links[0].gravity);
  EXPECT_TRUE(model(d, "faller").links[0].gravity);
}

// A world body with gravity off stays put; its twin with gravity on falls z = 2 - g dt^2 n (n + 1) / 2 after n
// semi-implicit Euler steps: n = 500, dt = 1 ms, g = 5 m/s^2 gives 2 - 0.626 = 1.37375 m.
TEST(Gazebo11Reads, WorldBodyWithGravityOffFloats) {
  World w(load_world_file(data_path(kWorld)));
  w.step(500);
  EXPECT_NEAR(w.model_state("floater").pose.translation().z(), 2.0, 1e-9);
  EXPECT_NEAR(w.model_state("faller").pose.translation().z(), 1.37375, 1e-6);
}

// The same switch on a robot's links (SDF worlds' models with joints are robots): the robot stays at z = 2 m.
TEST(Gazebo11Reads, RobotLinksWithGravityOffFloat) {
  World w(load_world_file(data_path(kWorld)));
  w.step(500);
  EXPECT_NEAR(w.model_state("sonar_bot").pose.translation().z(), 2.0, 1e-9);
}

// SDF 1.4's bare-text script is read as the script's name, as Gazebo 11's sdformat did.
TEST(Gazebo11Reads, BareTextMaterialScriptIsItsName) {
  const WorldDescription d = load_world_file(data_path(kWorld));
  ASSERT_EQ(model(d, "floater").links[0].visuals.size(), 1u);
  EXPECT_EQ(model(d, "floater").links[0].visuals[0].script_name, "Gazebo/Green");
}

// The Pioneer 3-DX sonar's <box><size>0 0 0</size></box>: a warning naming the collision, the shape left out.
TEST(Gazebo11Reads, ZeroBoxOfARobotIsAWarningAndLeftOut) {
  World w(load_world_file(data_path(kWorld)));
  const RobotModel& m = w.robot("sonar_bot").model;
  const Diagnostic* d = nullptr;
  for (const auto& x : m.diagnostics)
    if (x.code == "shape-size") d = &x;
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_EQ(d->element, "model[sonar_bot]/link[sonar]/collision[sonar_collision]");
  EXPECT_EQ(d->message,
            "a size is not > 0; the collision is left out of the collision world (the model is simulated)");
  EXPECT_TRUE(m.find_link("sonar")->collisions.empty());
  EXPECT_EQ(m.find_link("base")->collisions.size(), 1u);
}

// <format>R16G16B16</format>, which libsdformat 12 refuses and Gazebo 11 reads: the world loads and the camera
// makes rgb16 images (4 x 2 pixels, 6 bytes each: step 24 bytes, 48 bytes in all).
TEST(Gazebo11Reads, R16G16B16CameraFormatMakesRgb16) {
  World w(load_world_file(data_path(kWorld)));
  w.set_sensor_active("eye16", "eye16_camera", true);
  w.step(100);
  const auto frames = w.take_outputs<CameraOut>();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].encoding, "rgb16");
  EXPECT_EQ(frames[0].step(), 24u);
  EXPECT_EQ(frames[0].image.size(), 48u);
}

// The rewrite keeps the element on its line (error line numbers stay right) and leaves other names as written.
TEST(Gazebo11Reads, PixelFormatRewriteIsInPlace) {
  bool changed = false;
  const std::string in = "<image>\n<format> R16G16B16 </format>\n<format>R8G8B8</format>\n</image>";
  EXPECT_EQ(detail::rewrite_pixel_formats(in, &changed),
            "<image>\n<format>RGB_INT16</format>\n<format>R8G8B8</format>\n</image>");
  EXPECT_TRUE(changed);
  EXPECT_EQ(detail::rewrite_pixel_formats("<format>R8G8B8</format>", &changed), "<format>R8G8B8</format>");
  EXPECT_FALSE(changed);
}
