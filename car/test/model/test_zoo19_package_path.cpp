// package:// as rospack resolves it (docs/COMPAT-spawn.md "package:// lookup"): a description package cloned
// into a catkin workspace (catkin_ws/src/REPO/PKG, ROS_PACKAGE_PATH = catkin_ws/src) is found by its
// package.xml <name>, as users of universal_robot, franka_ros, husky, jackal and turtlebot3 have it.
// Fixtures: test/data/zoo19/ws (src/zoo19_repo/description = zoo19_arm_description, src/zoo19_repo/zoo19_dup,
// src/ignored (CATKIN_IGNORE), src/.hidden) and test/data/zoo19/ws2/zoo19_dup.
#include <gtest/gtest.h>

#include <cstdlib>

#include "car_sim/description.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

// Sets ROS_PACKAGE_PATH for one test and puts the old value back.
class PackagePath : public ::testing::Test {
 protected:
  void use(const std::string& value) { env_.set("ROS_PACKAGE_PATH", value); }
  static std::string ws() { return data_path("zoo19/ws"); }

 private:
  ScopedEnv env_;
};

}  // namespace

TEST_F(PackagePath, NestedPackageIsFoundByItsNameFromTheWorkspaceSrc) {
  use(ws() + "/src");
  // the folder is "description"; the package.xml names it zoo19_arm_description
  EXPECT_EQ(resolve_uri("package://zoo19_arm_description/meshes/cube.obj"),
            ws() + "/src/zoo19_repo/description/meshes/cube.obj");
}

TEST_F(PackagePath, CatkinIgnoredFolderIsNotSearched) {
  use(ws() + "/src");
  EXPECT_EQ(resolve_uri("package://zoo19_ignored_pkg/marker.txt"), "");
}

TEST_F(PackagePath, DotFolderIsNotSearched) {
  use(ws() + "/src");
  EXPECT_EQ(resolve_uri("package://zoo19_hidden_pkg/marker.txt"), "");
}

TEST_F(PackagePath, FirstEntryWinsEvenWhenItsPackageIsNested) {
  // zoo19_dup is nested in ws/src and top-level in ws2: the entry written first decides, as in rospack
  use(ws() + "/src:" + data_path("zoo19/ws2"));
  EXPECT_EQ(resolve_uri("package://zoo19_dup/marker.txt"), ws() + "/src/zoo19_repo/zoo19_dup/marker.txt");
  use(data_path("zoo19/ws2") + ":" + ws() + "/src");
  EXPECT_EQ(resolve_uri("package://zoo19_dup/marker.txt"), data_path("zoo19/ws2/zoo19_dup/marker.txt"));
}

TEST_F(PackagePath, RobotWithANestedPackageMeshSpawnsAndRestsOnItsMesh) {
  use(ws() + "/src");
  World w(empty_world());
  w.spawn(load_urdf_file(data_path("zoo19/nested_mesh_bot.urdf")), "nested", at(0, 0, 0) * Eigen::Translation3d(0, 0, 0.2));
  w.step(2000);  // 2 s: dropped 0.1 m, settled
  // the 0.2 m cube centred on base_link: base_link at z = 0.1 m, plus Bullet's 0.0005 m hull margin, within 2 mm
  EXPECT_NEAR(w.link_pose("nested", "base_link").translation().z(), 0.1005, 0.002);
}
