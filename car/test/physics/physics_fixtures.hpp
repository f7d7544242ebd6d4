// Small worlds and robots for the surface and joint physics tests (docs/COMPAT-physics.md). Gravity is 10 m/s^2
// and the step 1 ms throughout, so hand-derived values stay readable.
#pragma once

#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "../../src/physics/physics.hpp"
#include "car_sim/description.hpp"
#include "car_sim/model.hpp"

namespace car_sim {
namespace test_physics {

constexpr double kG = 10.0;    // [m/s^2]
constexpr double kDt = 0.001;  // [s]

inline std::string fmt(const char* f, double a = 0, double b = 0, double c = 0, double d = 0, double e = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d, e);
  return buf;
}

// A world with gravity -kG z and, unless `ground` is empty, one static model: `ground` is its <link> content.
inline WorldDescription world(const std::string& ground, double pitch = 0.0) {
  std::string xml = "<?xml version=\"1.0\"?><sdf version=\"1.7\"><world name=\"w\">" + fmt("<gravity>0 0 %g</gravity>", -kG) +
                    "<physics type=\"ode\"><max_step_size>0.001</max_step_size></physics>";
  if (!ground.empty())
    xml += "<model name=\"ground\"><static>true</static>" + fmt("<pose>0 0 0 0 %.17g 0</pose>", pitch) +
           "<link name=\"l\">" + ground + "</link></model>";
  return load_world_string(xml + "</world></sdf>", "physics-test.world");
}

// A ground plane z = 0 with friction mu, mu2.
inline WorldDescription flat(double mu = 1.0, double mu2 = 1.0) {
  return world(fmt("<collision name=\"c\"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane>"
                   "</geometry><surface><friction><ode><mu>%g</mu><mu2>%g</mu2></ode></friction></surface></collision>",
                   mu, mu2));
}

// A slope: a 20 m x 20 m x 1 m box whose top face passes through the origin, turned by `theta` about -y, so it
// rises towards +x. Its friction is 100: the robot's surface decides.
inline WorldDescription slope(double theta) {
  return world("<collision name=\"c\"><pose>0 0 -0.5 0 0 0</pose><geometry><box><size>20 20 1</size></box></geometry>"
               "<surface><friction><ode><mu>100</mu><mu2>100</mu2></ode></friction></surface></collision>",
               -theta);
}

// <inertial> of a solid box of mass m and edges x, y, z.
inline std::string box_inertial(double m, double x, double y, double z) {
  return fmt("<inertial><mass value=\"%g\"/>", m) +
         fmt("<inertia ixx=\"%.17g\" iyy=\"%.17g\" izz=\"%.17g\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>",
             m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12);
}

// A one-link robot: a box of mass m and edges x, y, z, with `gazebo` inside its <gazebo reference="base">.
inline RobotModel block(double m, double x, double y, double z, const std::string& gazebo) {
  return load_urdf_string("<robot name=\"block\"><link name=\"base\">" + box_inertial(m, x, y, z) +
                              fmt("<collision><geometry><box size=\"%g %g %g\"/></geometry></collision></link>", x, y, z) +
                              "<gazebo reference=\"base\">" + gazebo + "</gazebo></robot>",
                          "block.urdf");
}

inline physics::Options options() {
  physics::Options o;
  o.dt = kDt;
  return o;
}

inline Eigen::Isometry3d pose(double x, double y, double z, double yaw = 0.0, double pitch = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

inline void run(physics::Physics& p, int steps) {
  for (int i = 0; i < steps; ++i) p.step(kDt);
}

// box_house.world and a Physics over it (the Physics reads its world models from the description, which it keeps)
struct HousePhysics {
  std::unique_ptr<WorldDescription> desc;
  std::unique_ptr<physics::Physics> p;
};

inline HousePhysics box_house(const physics::Options& o) {
  HousePhysics h;
  h.desc = std::make_unique<WorldDescription>(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  h.p = std::make_unique<physics::Physics>(*h.desc, o, std::set<std::string>{});
  return h;
}

// The seed car with its camera and lidar (test/data/car_camera_lidar04.urdf).
inline RobotModel seed_car() {
  return load_urdf_file(std::string(CAR_SOURCE_DIR) + "/test/data/car_camera_lidar04.urdf");
}

// A state's values for a bit-for-bit comparison: rotation matrix, position, velocity, angular velocity.
inline void push_state(std::vector<double>& v, const ModelState& m) {
  const Eigen::Matrix3d R = m.pose.linear();
  v.insert(v.end(), R.data(), R.data() + 9);
  for (int i = 0; i < 3; ++i) v.push_back(m.pose.translation()[i]);
  for (int i = 0; i < 3; ++i) v.push_back(m.linear[i]);
  for (int i = 0; i < 3; ++i) v.push_back(m.angular[i]);
}

}  // namespace test_physics
}  // namespace car_sim
