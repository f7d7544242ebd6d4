// Rigid bodies of a robot: links joined by fixed joints merged into one body, as Gazebo's URDF import does
// (private header of the core).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "car_sim/model.hpp"

namespace car_sim {
namespace detail {

struct BodyShape {
  Shape shape;                      // shape.origin is in the link frame it came from
  Eigen::Isometry3d in_top;         // shape frame in the body's top-link frame
  double mu = 1.0;                  // friction of the link it came from
  const Link* link = nullptr;       // the link it holds the shape (after lumping)
  const GazeboLinkExt* gz = nullptr;  // <gazebo> surface settings of the link the shape came from
};

struct Body {
  std::string top;                  // link whose frame is the body frame
  std::vector<std::string> links;   // members, top first
  double mass = 0.0;                // [kg]
  Eigen::Vector3d com = Eigen::Vector3d::Zero();         // [m], top frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();     // [kg m^2] about com, top frame
  Eigen::Isometry3d top_to_com = Eigen::Isometry3d::Identity();  // principal frame at the com, in the top frame
  Eigen::Vector3d principal = Eigen::Vector3d::Zero();   // [kg m^2] principal moments
  std::vector<BodyShape> shapes;
  int parent = -1;                  // parent body index, -1 for the root body
  const Joint* joint = nullptr;     // moving joint to the parent body (child link = top)
};

struct BodyTree {
  std::vector<Body> bodies;                              // parents before children; bodies[0] is the root
  std::map<std::string, int> body_of_link;
  std::map<std::string, Eigen::Isometry3d> link_in_top;  // link frame in its body's top frame
};

// Rotation whose columns are the principal axes of an inertia tensor (a proper rotation), and the principal
// moments. A tensor that is already diagonal keeps its own axes, so frames stay readable.
Eigen::Matrix3d principal_axes(const Eigen::Matrix3d& inertia, Eigen::Vector3d* moments);

// Builds the bodies of a model. Throws LoadError for joints the simulator does not support (floating, planar)
// and for a body without mass.
BodyTree build_bodies(const RobotModel& m);

}  // namespace detail
}  // namespace car_sim
