#include "bodies.hpp"

#include <Eigen/Eigenvalues>
#include <deque>

namespace car_sim {
namespace detail {

namespace {

// Adds a link's mass properties (its inertial frame given in the top frame) to running sums.
void accumulate(const Inertial& in, const Eigen::Isometry3d& top_to_link, std::vector<double>* masses,
                std::vector<Eigen::Vector3d>* coms, std::vector<Eigen::Matrix3d>* tensors) {
  const Eigen::Isometry3d f = top_to_link * in.origin;
  masses->push_back(in.mass);
  coms->push_back(f.translation());
  // each link's tensor as Gazebo 11's ODE takes it (the identity where it cannot be inverted)
  tensors->push_back(f.linear() * simulated_inertia(in.inertia) * f.linear().transpose());
}

}  // namespace

Eigen::Matrix3d principal_axes(const Eigen::Matrix3d& inertia, Eigen::Vector3d* moments) {
  const Eigen::Matrix3d off = inertia - Eigen::Matrix3d(inertia.diagonal().asDiagonal());
  if (off.norm() <= 1e-12 * inertia.norm()) {
    *moments = inertia.diagonal();
    return Eigen::Matrix3d::Identity();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(inertia);
  Eigen::Matrix3d R = es.eigenvectors();
  if (R.determinant() < 0) R.col(2) = -R.col(2);
  *moments = es.eigenvalues();
  return R;
}

BodyTree build_bodies(const RobotModel& m) {
  BodyTree t;
  // Children of each link, in URDF joint order.
  std::map<std::string, std::vector<const Joint*>> children;
  for (const auto& j : m.joints) children[j.parent].push_back(&j);

  // Breadth-first from the root: a fixed joint extends the current body, a moving one starts a new body.
  std::deque<std::pair<std::string, int>> todo;  // (link starting a body, parent body)
  std::map<std::string, const Joint*> joint_into;
  for (const auto& j : m.joints) joint_into[j.child] = &j;
  todo.emplace_back(m.root_link, -1);
  while (!todo.empty()) {
    const auto [top, parent] = todo.front();
    todo.pop_front();
    Body b;
    b.top = top;
    b.parent = parent;
    b.joint = parent < 0 ? nullptr : joint_into[top];
    const int index = static_cast<int>(t.bodies.size());
    std::vector<std::pair<std::string, Eigen::Isometry3d>> stack = {{top, Eigen::Isometry3d::Identity()}};
    while (!stack.empty()) {
      const auto [link, T] = stack.back();
      stack.pop_back();
      b.links.push_back(link);
      t.body_of_link[link] = index;
      t.link_in_top[link] = T;
      // reverse, so that the stack pops children in URDF order
      const auto& kids = children[link];
      for (auto it = kids.rbegin(); it != kids.rend(); ++it) {
        const Joint* j = *it;
        if (j->type == JointType::Fixed) {
          stack.emplace_back(j->child, T * j->origin);
        } else if (j->type == JointType::Floating || j->type == JointType::Planar) {
          throw LoadError(m.source, 0, "joint[" + j->name + "]",
                          std::string(to_string(j->type)) + " joints are not simulated by car");
        } else {
          todo.emplace_back(j->child, index);
        }
      }
    }
    // Mass properties of the merged links.
    std::vector<double> ms;
    std::vector<Eigen::Vector3d> cs;
    std::vector<Eigen::Matrix3d> is;
    for (const auto& link : b.links) {
      const Link* l = m.find_link(link);
      // a joint naming a link the model does not hold; the loader refuses the cases known to reach here
      if (!l) throw LoadError(m.source, 0, "link[" + link + "]", "is named by a joint but is not in the model");
      if (l->inertial) accumulate(*l->inertial, t.link_in_top[link], &ms, &cs, &is);
      // a lumped link's shapes keep its own surface settings (RobotModel::surface)
      for (const auto& s : l->collisions) {
        const GazeboLinkExt& gz = m.surface(*l, s);
        b.shapes.push_back({s, t.link_in_top[link] * s.origin, gz.mu1.value_or(1.0), l, &gz});
      }
    }
    for (double x : ms) b.mass += x;
    // an anchored model's root body is the world's: fixed, no mass of its own (Gazebo's `world` link)
    if (parent < 0 && top == "world" && m.anchored()) {
      t.bodies.push_back(std::move(b));
      continue;
    }
    if (!(b.mass > 0.0))
      throw LoadError(m.source, 0, "link[" + top + "]",
                      "the body of link '" + top + "' (with the links fixed to it) has no mass");
    for (size_t i = 0; i < ms.size(); ++i) b.com += ms[i] * cs[i];
    b.com /= b.mass;
    for (size_t i = 0; i < ms.size(); ++i) {
      const Eigen::Vector3d d = cs[i] - b.com;
      // parallel-axis theorem
      b.inertia += is[i] + ms[i] * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }
    b.top_to_com.linear() = principal_axes(b.inertia, &b.principal);
    b.top_to_com.translation() = b.com;
    t.bodies.push_back(std::move(b));
  }
  // links lumped into a kept one (RobotModel::lumped) stay frames of its body, for plug-ins naming them
  for (const auto& l : m.lumped) {
    const auto it = t.body_of_link.find(l.parent);
    if (it == t.body_of_link.end()) continue;
    t.body_of_link[l.name] = it->second;
    t.link_in_top[l.name] = t.link_in_top[l.parent] * l.pose;
  }
  return t;
}

}  // namespace detail
}  // namespace car_sim
