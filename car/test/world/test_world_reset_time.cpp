// World::reset_time (Gazebo's World::ResetTime): time to zero, nothing else reset; the time-reset hooks. Values by
// hand for the seed car in box_house (worlds/box_house.world), dt = 0.001 s.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

std::unique_ptr<World> box_house_with_car() {
  auto w = std::make_unique<World>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w->spawn(load_urdf_string(read_text("test/data/car_camera_lidar04.urdf"), "car04"), "mycar", at(0, 0, 0));
  return w;
}

}  // namespace

// Driving at 0.5 m/s for 1.005 s, then reset_time: tick and time 0, the car's pose and twist as they were, bit for bit.
TEST(WorldResetTime, TimeGoesToZeroAndTheModelsStayAsTheyAre) {
  auto w = box_house_with_car();
  w->set_cmd_vel("mycar", 0.5, 0.0);
  w->step(1005);
  const ModelState before = w->model_state("mycar");
  w->reset_time();
  EXPECT_EQ(w->tick(), 0u);
  EXPECT_EQ(w->time(), 0.0);
  const ModelState after = w->model_state("mycar");
  EXPECT_TRUE(after.pose.matrix() == before.pose.matrix());
  EXPECT_TRUE(after.linear == before.linear);
  EXPECT_TRUE(after.angular == before.angular);
}

// The diff drive's 100 Hz odometry restarts its schedule at tick 0 (Gazebo's time-reset event): ticks 10 and 20, as
// from a spawn (WorldPhysics.OdometryAtUpdateRate). Left at its last update (tick 1000), it would wait ~1 s.
TEST(WorldResetTime, ThePluginsSchedulesRestartFromZero) {
  auto w = box_house_with_car();
  w->step(1005);
  w->take_odometry();
  w->reset_time();
  w->step(20);
  const auto odom = w->take_odometry();
  ASSERT_EQ(odom.size(), 2u);
  EXPECT_EQ(odom[0].tick, 10u);
  EXPECT_EQ(odom[1].tick, 20u);
}

// The time-reset hooks (Gazebo's timeReset, raised by World::ResetTime only, which World::Reset calls): once for
// reset_time, none for reset_poses (reset_world leaves time alone), once for reset; each time at tick 0.
TEST(WorldResetTime, HooksRunForResetTimeAndResetNotResetPoses) {
  World w(empty_world());
  std::vector<uint64_t> ticks;
  w.add_time_reset_hook([&] { ticks.push_back(w.tick()); });
  w.step(5);
  w.reset_time();
  EXPECT_EQ(ticks, (std::vector<uint64_t>{0}));
  w.step(5);
  w.reset_poses();
  EXPECT_EQ(ticks.size(), 1u);
  w.reset();
  EXPECT_EQ(ticks, (std::vector<uint64_t>{0, 0}));
}

// A removed time-reset hook is not called again.
TEST(WorldResetTime, ARemovedHookIsNotCalled) {
  World w(empty_world());
  int calls = 0;
  const uint64_t id = w.add_time_reset_hook([&] { ++calls; });
  w.remove_step_hook(id);
  w.reset_time();
  w.reset();
  EXPECT_EQ(calls, 0);
}

// An empty time-reset hook is refused with its message.
TEST(WorldResetTime, AnEmptyHookIsRefused) {
  World w(empty_world());
  try {
    w.add_time_reset_hook(nullptr);
    FAIL() << "an empty hook was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "a time-reset hook needs a function");
  }
}
