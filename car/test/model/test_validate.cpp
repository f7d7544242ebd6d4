// Limits and validation before allocation (src/model/validate.cpp, the plug-in schemas' limits) and the physics
// guard: each error names file, line, element and the value as written. Expectations worked out from the
// fixtures in test/data/bad/ (line numbers counted in the files).
#include <gtest/gtest.h>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

std::string urdf_error(const std::string& file) {
  try {
    load_urdf_file(data_path("bad/" + file));
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

std::string world_error(const std::string& file) {
  try {
    load_world_file(data_path("bad/" + file));
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

std::string spawn_error(const std::string& file) {
  World w(empty_world());
  try {
    w.spawn(load_urdf_file(data_path("bad/" + file)), "robot", at(0, 0, 0));
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Validate, NanMassIsReportedWithItsValueAndLine) {
  // <mass> is on line 7 of the template; urdfdom alone would report "mass 0"
  EXPECT_EQ(urdf_error("mass_nan.urdf"),
            data_path("bad/mass_nan.urdf") + ":7: link[base_link]/inertial/mass: mass 'nan' is not a finite number");
}

// Issue 29 item 4: Gazebo 11 warns about a shape size <= 0 and simulates the model (BoxShape::SetSize and kin);
// car warns and leaves the collision out.
TEST(Validate, NegativeCylinderRadiusIsAWarningAndTheCollisionIsLeftOut) {
  const RobotModel m = load_urdf_file(data_path("bad/cylinder_radius_negative.urdf"));
  const Diagnostic* d = nullptr;
  for (const auto& x : m.diagnostics)
    if (x.code == "shape-size") d = &x;
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->severity, Severity::Warning);
  EXPECT_EQ(d->line, 15);
  EXPECT_EQ(d->element, "link[wheel]/collision[0]/geometry/cylinder");
  EXPECT_EQ(d->message,
            "radius -0.1 m is not > 0; the collision is left out of the collision world (the model is simulated)");
  EXPECT_TRUE(m.find_link("wheel")->collisions.empty());
}

TEST(Validate, ZeroCylinderRadiusIsAWarningAndTheRobotSpawns) {
  World w(empty_world());
  w.spawn(load_urdf_file(data_path("bad/cylinder_radius_zero.urdf")), "robot", at(0, 0, 0));
  EXPECT_TRUE(w.robot("robot").model.find_link("wheel")->collisions.empty());
}

TEST(Validate, NanInAJointOriginNamesTheJointNotAColour) {
  EXPECT_EQ(urdf_error("joint_origin_nan.urdf"),
            data_path("bad/joint_origin_nan.urdf") +
                ":19: joint[wheel_joint]/origin: xyz 'nan 0.1 0': 'nan' is not a finite number");
}

TEST(Validate, HugeMassIsAWarningNotAnError) {
  const RobotModel m = load_urdf_file(data_path("bad/mass_huge.urdf"));
  ASSERT_FALSE(m.diagnostics.empty());
  EXPECT_EQ(m.diagnostics[0].code, "mass-range");
  EXPECT_EQ(m.diagnostics[0].message,
            "mass 1e+300 kg is outside 1e-06..1e+06 kg (a unit mistake? the solver loses accuracy at such masses)");
}

TEST(Validate, EntityDeclarationsAreRefused) {
  EXPECT_NE(urdf_error("billion_laughs.urdf").find("DTD entity declarations are refused"), std::string::npos);
  EXPECT_NE(urdf_error("external_entity.urdf").find("DTD entity declarations are refused"), std::string::npos);
}

TEST(Validate, LidarSamplesAboveTheLimitFailBeforeAllocation) {
  // line 25: <sensor> in the template's extra block
  EXPECT_EQ(spawn_error("lidar_samples_huge.urdf"),
            data_path("bad/lidar_samples_huge.urdf") +
                ":25: sensor[laser]/ray/scan/horizontal/samples: ray/scan/horizontal/samples 1000000000 is above the "
                "limit 100000");
}

TEST(Validate, CameraAboveTheSideLimitFailsBeforeAllocation) {
  EXPECT_EQ(spawn_error("camera_huge.urdf"),
            data_path("bad/camera_huge.urdf") +
                ":25: sensor[cam]/camera/image/width: camera/image/width 100000 is above the limit 8192 px");
}

TEST(Validate, CameraPixelsAboveTheLimitFail) {
  // 4096 x 4096 = 16777216 px > 2048 x 2048 = 4194304 px
  EXPECT_NE(spawn_error("camera_pixels.urdf").find("width x height = 16777216 px is above the limit 4194304 px"),
            std::string::npos);
}

// Issue 29 item 5: an SDF world's sensors have the URDF's limits (camera_huge.urdf, lidar_samples_huge.urdf): the
// same element and reason, the world file's line.
TEST(Validate, WorldCameraAboveTheSideLimitIsRefusedAsInAUrdf) {
  try {
    World w(load_world_file(data_path("bad/camera_huge.world")));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(std::string(e.what()),
              data_path("bad/camera_huge.world") +
                  ":11: sensor[cam]/camera/image/width: camera/image/width 100000 is above the limit 8192 px");
  }
}

TEST(Validate, WorldLidarSamplesAboveTheLimitAreRefusedAsInAUrdf) {
  try {
    World w(load_world_file(data_path("bad/lidar_samples_huge.world")));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(std::string(e.what()),
              data_path("bad/lidar_samples_huge.world") +
                  ":11: sensor[laser]/ray/scan/horizontal/samples: ray/scan/horizontal/samples 1000000000 is above the "
                  "limit 100000");
  }
}

TEST(Validate, WorldStepSizeZeroIsRefusedWithItsValue) {
  EXPECT_EQ(world_error("step_zero.world"),
            data_path("bad/step_zero.world") + ": world/physics/max_step_size: step size 0 s is not finite and > 0");
}

TEST(Validate, WorldStepSizeNanNamesTheLine) {
  // <physics> is on line 6 of the world template
  EXPECT_EQ(world_error("step_nan.world"),
            data_path("bad/step_nan.world") +
                ":6: sdf/world[step_nan]/physics/max_step_size: max_step_size 'nan' is not a finite number");
}

TEST(Validate, WorldGravityNanIsRefused) {
  EXPECT_NE(world_error("gravity_nan.world").find(":5: sdf/world[gravity_nan]/gravity: gravity '0 0 nan': 'nan' is not"),
            std::string::npos);
}

TEST(Validate, WorldNegativeBoxIsAWarningAndTheCollisionIsLeftOut) {
  const WorldDescription d = load_world_file(data_path("bad/box_negative.world"));
  ASSERT_EQ(d.diagnostics.size(), 1u);
  EXPECT_EQ(d.diagnostics[0].element, "model[crate]/link[body]/collision[c]");
  EXPECT_EQ(d.diagnostics[0].message,
            "size -1 m is not > 0; the collision is left out of the collision world (the model is simulated)");
  ASSERT_NE(d.find_model("crate"), nullptr);
  EXPECT_TRUE(d.find_model("crate")->links[0].collisions.empty());
}

// Positions beyond 1e18 m overflow single precision when squared: still refused, with the new limit.
TEST(Validate, JointOriginBeyondTheFloatLimitIsRefused) {
  EXPECT_EQ(urdf_error("joint_origin_huge.urdf"),
            data_path("bad/joint_origin_huge.urdf") +
                ":19: joint[wheel_joint]/origin: xyz '1e300 0 0' is beyond the limit 1e+18 m (its square overflows "
                "the ray scene's single precision)");
}

TEST(Validate, IncludeLoopIsRefusedBeforeSdformatRecursesForever) {
  ScopedEnv env{{"GAZEBO_MODEL_PATH", data_path("bad/models")}};
  const std::string e = world_error("include_loop.world");
  EXPECT_NE(e.find("include loop: "), std::string::npos) << e;
  EXPECT_NE(e.find("loop_a/model.sdf -> "), std::string::npos) << e;
}

TEST(Guard, ABodyThatBlowsUpStopsTheWorldNamingIt) {
  // a 1e300 kg wheel on a 1 kg base: the solver's arithmetic overflows within the first steps
  World w(empty_world());
  w.spawn(load_urdf_file(data_path("bad/mass_huge.urdf")), "robot", at(0, 0, 0));
  std::string what;
  try {
    w.step(1000);
  } catch (const SimulationError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find(": robot/"), std::string::npos) << what;
  EXPECT_NE(what.find("is not finite; the world stops here"), std::string::npos) << what;
  // stopped: the next step throws again
  EXPECT_THROW(w.step(1), SimulationError);
}
