// Meshes (src/mesh): the three file formats, the URI rule's error, and mesh shapes in physics and the ray scene.
// Fixtures: test/data/meshes (make_meshes.py writes the same box as STL in mm, OBJ 1 m cube, DAE with a red material).
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/mesh.hpp"
#include "laser/laser.hpp"
#include "materials.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

// Axis-aligned bounds of a mesh's vertices.
std::pair<Eigen::Vector3f, Eigen::Vector3f> bounds(const TriMesh& m) {
  Eigen::Vector3f lo = m.vertices.front(), hi = m.vertices.front();
  for (const auto& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return {lo, hi};
}

// A one-link robot whose collision is the given mesh element.
std::string one_mesh_robot(const std::string& mesh) {
  return R"(<robot name="r"><link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry>)" + mesh + R"(</geometry></collision></link></robot>)";
}

}  // namespace

TEST(MeshFile, BinaryStlIsTwelveTrianglesWithTheWrittenBounds) {
  const auto m = load_mesh(data_path("meshes/box.stl"));
  EXPECT_EQ(m->indices.size(), 36u);
  // written in millimetres: 200 x 200 x 100
  const auto [lo, hi] = bounds(*m);
  EXPECT_TRUE(lo.isApprox(Eigen::Vector3f(-100, -100, -50)));
  EXPECT_TRUE(hi.isApprox(Eigen::Vector3f(100, 100, 50)));
}

TEST(MeshFile, ObjCubeHasHalfMetreHalfSizes) {
  const auto m = load_mesh(data_path("meshes/box.obj"));
  EXPECT_EQ(m->indices.size(), 36u);
  const auto [lo, hi] = bounds(*m);
  EXPECT_TRUE(lo.isApprox(Eigen::Vector3f(-0.5f, -0.5f, -0.5f)));
  EXPECT_TRUE(hi.isApprox(Eigen::Vector3f(0.5f, 0.5f, 0.5f)));
}

TEST(MeshFile, ColladaKeepsItsGeometryAndDiffuseColour) {
  const auto m = load_mesh(data_path("meshes/box.dae"));
  EXPECT_EQ(m->indices.size(), 36u);
  const auto [lo, hi] = bounds(*m);
  EXPECT_TRUE(lo.isApprox(Eigen::Vector3f(-0.1f, -0.1f, -0.05f)));
  EXPECT_TRUE(hi.isApprox(Eigen::Vector3f(0.1f, 0.1f, 0.05f)));
  ASSERT_TRUE(m->colour.has_value());
  EXPECT_TRUE(m->colour->isApprox(Eigen::Vector4d(1, 0, 0, 1)));
}

TEST(MeshFile, UnreadableFileIsALoadErrorNamingIt) {
  // a text file that is no mesh format assimp knows
  try {
    load_mesh(data_path("meshes/make_meshes.py"));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("make_meshes.py"), std::string::npos) << e.what();
  }
}

TEST(MeshUri, MissingPackageMeshNamesLinkUriAndWhereItLooked) {
  World w(empty_world());
  try {
    w.spawn(load_urdf_string(one_mesh_robot(R"(<mesh filename="package://no_such_pkg/meshes/m.stl"/>)"), "r"), "r",
            at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(e.element().find("link[base_link]"), std::string::npos) << what;
    EXPECT_NE(what.find("package://no_such_pkg/meshes/m.stl"), std::string::npos) << what;
    EXPECT_NE(what.find("ROS_PACKAGE_PATH"), std::string::npos) << what;
  }
}

TEST(MeshUri, MissingRelativeMeshNamesTheFileItLookedFor) {
  World w(empty_world());
  try {
    w.spawn(load_urdf_file(data_path("meshes/mesh_robot.urdf")), "ok", at(0, 0, 0));
    w.spawn(load_urdf_string(one_mesh_robot(R"(<mesh filename="not_here.stl"/>)"), "r"), "r", at(1, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("not_here.stl"), std::string::npos) << e.what();
  }
}

TEST(MeshColour, VisualMeshMaterialWhereTheUrdfGivesNone) {
  RobotModel m = load_urdf_file(data_path("meshes/mesh_robot.urdf"));
  load_meshes(&m, data_path("meshes"));
  EXPECT_TRUE(link_colour(m.links.front()).isApprox(Eigen::Vector4d(1, 0, 0, 1)));
}

// The mesh box is 0.1 m tall, centred on the link origin: at rest on the ground the origin is 0.05 m up
// (+ 0.5 mm of convex-hull margin, inside the 2 mm tolerance).
TEST(MeshPhysics, DynamicMeshRestsAtItsMeshHeight) {
  World w(empty_world());
  w.spawn(load_urdf_file(data_path("meshes/mesh_robot.urdf")), "bot", at(0, 0, 0) * Eigen::Translation3d(0, 0, 0.2));
  w.step(2000);
  const ModelState s = w.model_state("bot");
  EXPECT_NEAR(s.pose.translation().z(), 0.05, 0.002);
  EXPECT_NEAR(s.pose.translation().x(), 0.0, 0.002);
}

// The static mesh cube's top is z = 1: the box robot dropped on it rests with its origin at 1.05 m.
TEST(MeshPhysics, StaticTriangleMeshCarriesABody) {
  World w(load_world_file(data_path("meshes/mesh_block.world")));
  w.spawn(load_urdf_file(data_path("meshes/mesh_robot.urdf")), "bot", at(2, 0, 0) * Eigen::Translation3d(0, 0, 1.2));
  w.step(2000);
  EXPECT_NEAR(w.model_state("bot").pose.translation().z(), 1.05, 0.002);
}

// The seed car at the origin facing +x; the cube's near face is the plane x = 1.5. A level beam at angle th from
// the lidar at x = lx meets it after (1.5 - lx) / cos(th).
TEST(MeshRays, LidarSeesTheMeshCubeAtItsFace) {
  World w(load_world_file(data_path("meshes/mesh_block.world")));
  w.spawn(load_urdf_string(car_xml(false), "car"), "mycar", at(0, 0, 0));
  w.set_sensor_active("mycar", "gazebo_rplidar", true);
  w.step(200);
  const auto scans = w.take_outputs<LaserScanOut>();
  ASSERT_FALSE(scans.empty());
  const LaserScanOut& s = scans.back();
  const Eigen::Isometry3d laser = w.link_pose("mycar", "laser");
  const double yaw = std::atan2(laser.linear()(1, 0), laser.linear()(0, 0));
  for (int i : {179, 180}) {
    const double th = yaw + s.angle_min + i * s.angle_increment;
    EXPECT_NEAR(s.ranges[i], (1.5 - laser.translation().x()) / std::cos(th), 0.01) << "beam " << i;
  }
}

// Issue 29 item 3: a visual's mesh missing is a warning naming the element and the file; the robot spawns and its
// collision (box.stl, 0.1 m tall) carries it at 0.05 m as in DynamicMeshRestsAtItsMeshHeight.
TEST(MeshMissing, VisualMeshMissingIsAWarningAndTheRobotSpawns) {
  World w(empty_world());
  w.spawn(load_urdf_file(data_path("meshes/visual_mesh_missing.urdf")), "bot",
          at(0, 0, 0) * Eigen::Translation3d(0, 0, 0.2));
  std::vector<Diagnostic> found;
  for (const auto& d : w.robot("bot").model.diagnostics)
    if (d.code == "visual-mesh-missing") found.push_back(d);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].severity, Severity::Warning);
  EXPECT_EQ(found[0].element, "link[base_link]/visual[body]/mesh");
  EXPECT_EQ(found[0].message, "mesh 'waffle_base.stl' not found (looked in " + data_path("meshes") +
                                  "/waffle_base.stl); the visual is not drawn (the model is simulated: physics and "
                                  "sensors use its collisions)");
  w.step(2000);
  EXPECT_NEAR(w.model_state("bot").pose.translation().z(), 0.05, 0.002);
}

// A collision's mesh missing stays the spawn's load error: file, element and reason.
TEST(MeshMissing, CollisionMeshMissingIsALoadError) {
  World w(empty_world());
  const std::string file = data_path("meshes/collision_mesh_missing.urdf");
  try {
    w.spawn(load_urdf_file(file), "bot", at(0, 0, 0));
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_EQ(std::string(e.what()), file + ": link[base_link]/collision[0]/mesh: mesh 'waffle_base.stl' not found "
                                            "(looked in " + data_path("meshes") + "/waffle_base.stl)");
  }
  EXPECT_FALSE(w.has_model("bot"));
}
