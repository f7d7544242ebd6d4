// hector_gazebo_plugins' sonar: the nearest hit of the cone through hector's sensor model, at the plug-in's rate.
#include <gtest/gtest.h>

#include <cmath>

#include "../range/ray_world.hpp"
#include "range/range.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

// A wall with its face on the plane x = 2.0 m (0.2 m thick, 4 m wide, 1 m high).
WorldDescription wall_world() { return ray_world(box_model("wall", 2.1, 0, 0.5, 0.2, 4, 1)); }

// 0.1 m ahead of the cube's centre, 0.4 m above it; 5 x 3 rays over +-0.2 rad horizontally, +-0.05 vertically.
std::string sonar(const std::string& extra = "") {
  return ray_sensor("ray", "sonar", "0.1 0 0.4 0 0 0", scan_axis(5, -0.2, 0.2), scan_axis(3, -0.05, 0.05), 0.03, 3.0,
                    "<plugin name='hector_sonar' filename='libhector_gazebo_ros_sonar.so'><topicName>sonar</topicName>"
                    "<frameId>sonar_link</frameId>" + extra + "</plugin>");
}

std::vector<RangeOut> ranges(const std::string& extra, double yaw = 0, uint64_t steps = 1000) {
  auto w = world_with_cube(wall_world(), sonar(extra), 0, 0, yaw);
  w->set_sensor_active("cube", "hector_sonar", true);
  w->step(steps);
  return w->take_outputs<RangeOut>();
}

}  // namespace

// No model errors: the perpendicular ray reads 2.0 - 0.1 = 1.9 m; the field of view is the narrower span,
// min(0.4, 0.1) = 0.1 rad; 10 Hz by default (not the sensor's update_rate of 10 Hz either way: see the next test).
TEST(HectorSonar, ReadsTheWallAndTheNarrowerSpan) {
  const auto rs = ranges("");
  ASSERT_EQ(rs.size(), 10u);  // 1 s at 10 Hz
  EXPECT_NEAR(rs.back().range, 1.9, 2e-3);
  EXPECT_NEAR(rs.back().field_of_view, 0.1, 1e-6);
  EXPECT_EQ(rs.back().radiation, 0);
  EXPECT_FLOAT_EQ(rs.back().max_range, 3.0f);
}

// updatePeriod is sdf::Time "SEC NSEC" (test_update_timer.cpp has the rest of hector's timer).
TEST(HectorSonar, UpdateRateAndPeriodSetTheRate) {
  EXPECT_EQ(ranges("<updateRate>50</updateRate>").size(), 50u);
  EXPECT_EQ(ranges("<updatePeriod>0 250000000</updatePeriod>").size(), 4u);
}

// scaleError 1.1 and offset 0.05: 1.9 x 1.1 + 0.05 = 2.14 m.
TEST(HectorSonar, ScaleErrorAndOffset) {
  const auto rs = ranges("<scaleError>1.1</scaleError><offset>0.05</offset>");
  EXPECT_NEAR(rs.back().range, 1.9 * 1.1 + 0.05, 3e-3);
}

// A reading pushed beyond range.max is clamped to it: 1.9 + 5 -> 3.0.
TEST(HectorSonar, ClampedToTheSensorsRange) {
  EXPECT_FLOAT_EQ(ranges("<offset>5</offset>").back().range, 3.0f);
}

// gaussianNoise 0.02 m: 500 readings at 50 Hz spread by 0.02 around 1.9 m.
TEST(HectorSonar, GaussianNoiseSpread) {
  const auto rs = ranges("<gaussianNoise>0.02</gaussianNoise><updateRate>50</updateRate>", 0, 10000);
  ASSERT_EQ(rs.size(), 500u);
  double sum = 0, sum2 = 0;
  for (const auto& r : rs) {
    sum += r.range - 1.9;
    sum2 += (r.range - 1.9) * (r.range - 1.9);
  }
  EXPECT_NEAR(sum / 500, 0.0, 4 * 0.02 / std::sqrt(500.0) + 2e-3);
  EXPECT_NEAR(std::sqrt(sum2 / 500), 0.02, 0.003);
}

// hector's kernel draws sigma * X: gaussianNoise -0.02 draws the same numbers as 0.02 with the sign turned, so
// each reading is the mirror image of the positive run's about the noise-free reading (same seed; 1e-6 m: the
// readings are floats).
TEST(HectorSonar, NegativeNoiseMirrorsThePositive) {
  const auto clean = ranges("<updateRate>50</updateRate>");
  const auto pos = ranges("<gaussianNoise>0.02</gaussianNoise><updateRate>50</updateRate>");
  const auto neg = ranges("<gaussianNoise>-0.02</gaussianNoise><updateRate>50</updateRate>");
  ASSERT_EQ(pos.size(), 50u);
  ASSERT_EQ(neg.size(), pos.size());
  ASSERT_EQ(clean.size(), pos.size());
  for (size_t i = 0; i < pos.size(); ++i) {
    const double r0 = clean[i].range;
    EXPECT_NEAR(neg[i].range - r0, -(pos[i].range - r0), 1e-6) << i;
  }
  // the noise is there
  EXPECT_GT(std::abs(pos[0].range - clean[0].range), 1e-4);
}

// ... and loads with a warning saying so.
TEST(HectorSonar, NegativeNoiseWarns) {
  const ModelConfig c = resolve_plugins(load_urdf_string(cube_robot(sonar("<gaussianNoise>-0.02</gaussianNoise>")), "cube"));
  ASSERT_EQ(c.plugins.size(), 1u);
  bool found = false;
  for (const auto& d : c.diagnostics)
    if (d.code == "negative-noise")
      found = d.message == "<gaussianNoise> '-0.02' is negative: hector's GaussianKernel draws sigma * X, so it "
                           "spreads as its absolute value";
  EXPECT_TRUE(found);
}

// A negative driftFrequency would make upstream's drift NaN (sqrt(2 f)): refused.
TEST(HectorSonar, NegativeDriftFrequencyIsALoadError) {
  try {
    World w(wall_world());
    w.spawn(load_urdf_string(cube_robot(sonar("<driftFrequency>-1</driftFrequency>")), "cube"), "cube", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("plugin[hector_sonar]/driftFrequency: must be >= 0: hector's drift takes "
                                         "sqrt(2 driftFrequency), NaN for a negative one"),
              std::string::npos)
        << e.what();
  }
}

// A gpu_ray sensor is no RaySensor: hector's Load throws "GazeboRosSonar requires a Ray Sensor as its parent". The model loads without the plug-in.
TEST(HectorSonar, OnAGpuRaySensorThePluginDoesNotLoad) {
  EXPECT_EQ(not_loaded_on("gpu_ray", "<plugin name='p' filename='libhector_gazebo_ros_sonar.so'/>"),
            "libhector_gazebo_ros_sonar.so needs a sensor of type ray, not 'gpu_ray'; the plug-in is not loaded");
}
