// Fixed-joint lumping, massless-link dropping and world anchoring, as sdformat's URDF reader does them
// (sdformat parser_urdf.cc: ReduceFixedJoints, ReduceInertialToParent, ReduceCollisionsToParent,
// ReduceVisualsToParent, ReduceJointsToParent, ReduceSDFExtensionToParent, CreateSDF). Rules:
// docs/COMPAT-spawn.md.
#include "lumping.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <sstream>

#include <urdf_model/pose.h>

#include "xml_util.hpp"

namespace car_sim {

// ---- plug-in offsets at a lumping ----------------------------------------------------------------------------

namespace detail {
namespace {

// "x y z" as sdformat's ParseVector3 reads it, times scale; (0, 0, 0) unless three numbers.
Eigen::Vector3d parse_vector3(const std::string& text, double scale) {
  const auto v = detail::parse_numbers(text, 3);
  if (!v) return Eigen::Vector3d::Zero();
  return Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]) * scale;
}

// Three numbers as sdformat writes them: an ostream's defaults (6 significant digits).
std::string format3(double a, double b, double c) {
  std::ostringstream o;
  o << a << " " << b << " " << c;
  return o.str();
}

}  // namespace

// sdformat 9's ReduceSDFExtensionPluginFrameReplace, for one element of a robot-level plug-in: when `element`
// names the lumped link it names the parent, and the plug-in's offsets are rewritten, as sdformat 9 does it (its
// arithmetic kept, docs/COMPAT-spawn.md 11): the offset starts as the identity, takes xyzOffset [m] and rpyOffset
// read as *degrees* where given, goes through inverseTransformToParentFrame with the joint's origin T (position
// R^-1 p - t, rotation R^-1 q), and is written back as xyzOffset and rpyOffset [rad], appended.
void plugin_frame_replace(ParamList* params, const std::string& element, const std::string& link,
                          const std::string& parent, const Eigen::Isometry3d& T) {
  auto first = [&](const std::string& key) {
    return std::find_if(params->begin(), params->end(), [&](const auto& kv) { return kv.first == key; });
  };
  auto e = first(element);
  if (e == params->end() || e->second != link) return;
  params->erase(e);
  params->emplace_back(element, parent);
  Eigen::Vector3d pos = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rot = Eigen::Quaterniond::Identity();
  if (auto xyz = first("xyzOffset"); xyz != params->end()) {
    pos = parse_vector3(xyz->second, 1.0);
    params->erase(xyz);
  }
  if (auto rpy = first("rpyOffset"); rpy != params->end()) {
    const Eigen::Vector3d r = parse_vector3(rpy->second, M_PI / 180.0);
    rot = Eigen::Quaterniond(detail::rpy_to_matrix(r.x(), r.y(), r.z()));
    params->erase(rpy);
  }
  const Eigen::Quaterniond inverse = Eigen::Quaterniond(T.linear()).conjugate();
  pos = inverse * pos - T.translation();
  rot = inverse * rot;
  // urdfdom's Rotation::getRPY, as sdformat writes it
  double roll, pitch, yaw;
  urdf::Rotation(rot.x(), rot.y(), rot.z(), rot.w()).getRPY(roll, pitch, yaw);
  params->emplace_back("xyzOffset", format3(pos.x(), pos.y(), pos.z()));
  params->emplace_back("rpyOffset", format3(roll, pitch, yaw));
}

}  // namespace detail

// ---- RobotModel helpers for lumped links -----------------------------------------------------------------------

const LumpedLink* RobotModel::find_lumped(const std::string& n) const {
  for (const auto& l : lumped)
    if (l.name == n) return &l;
  return nullptr;
}

bool RobotModel::resolve_frame(const std::string& n, std::string* link, Eigen::Isometry3d* pose_in_link) const {
  if (find_link(n)) {
    if (link) *link = n;
    if (pose_in_link) *pose_in_link = Eigen::Isometry3d::Identity();
    return true;
  }
  if (const LumpedLink* l = find_lumped(n)) {
    if (link) *link = l->parent;
    if (pose_in_link) *pose_in_link = l->pose;
    return true;
  }
  return false;
}

const GazeboLinkExt& RobotModel::surface(const Link& l, const Shape& s) const {
  if (!s.lumped_from.empty())
    if (const LumpedLink* from = find_lumped(s.lumped_from)) return from->gazebo;
  return l.gazebo;
}

namespace detail {

namespace {

int line_in(const std::map<std::string, int>& lines, const std::string& link) {
  const auto it = lines.find(link);
  return it == lines.end() ? 0 : it->second;
}

bool massless(const Link& l) { return !l.inertial || l.inertial->mass == 0.0; }

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

// Inertial b (given in its link frame, placed at T in a's link frame) added to inertial a: the combined mass,
// centre of mass and inertia about it, in a's link frame (inertial frame axes = link axes).
Inertial combine(const std::optional<Inertial>& a, const Inertial& b, const Eigen::Isometry3d& T) {
  struct Part {
    double m;
    Eigen::Vector3d c;   // [m] link frame of a
    Eigen::Matrix3d I;   // [kg m^2] about c, link axes of a
  };
  std::vector<Part> parts;
  if (a && a->mass != 0.0)
    parts.push_back({a->mass, a->origin.translation(), a->origin.linear() * a->inertia * a->origin.linear().transpose()});
  const Eigen::Isometry3d fb = T * b.origin;
  parts.push_back({b.mass, fb.translation(), fb.linear() * b.inertia * fb.linear().transpose()});
  Inertial out;
  for (const auto& p : parts) out.mass += p.m;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : parts) c += p.m * p.c;
  c /= out.mass;
  for (const auto& p : parts) {
    const Eigen::Vector3d d = p.c - c;
    // parallel-axis theorem
    out.inertia += p.I + p.m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  out.origin = Eigen::Isometry3d::Identity();
  out.origin.translation() = c;
  return out;
}

std::string plural(size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

void find_world_anchor(RobotModel* m) {
  for (const auto& j : m->joints) {
    if (j.parent != "world") continue;
    m->world_joints.push_back(j.name);
    m->diagnostics.push_back(
        {Severity::Info, "world-anchor", "joint[" + j.name + "]",
         std::string(to_string(j.type)) + " joint '" + j.name + "' joins link '" + j.child +
             "' to the world: the model is anchored (fixed base; `world` has no mass)",
         0});
  }
}

void lump_fixed_joints(RobotModel* m, const std::map<std::string, int>& lines) {
  // Post-order over the tree as written: a link's fixed children are merged into it before it is merged up.
  std::map<std::string, std::vector<std::string>> kids;
  for (const auto& j : m->joints) kids[j.parent].push_back(j.child);
  std::vector<std::string> order;
  std::function<void(const std::string&)> visit = [&](const std::string& l) {
    for (const auto& c : kids[l]) visit(c);
    order.push_back(l);
  };
  visit(m->root_link);

  for (const auto& name : order) {
    const auto jit = std::find_if(m->joints.begin(), m->joints.end(), [&](const Joint& j) { return j.child == name; });
    if (jit == m->joints.end()) continue;  // the root
    if (jit->type != JointType::Fixed || jit->parent == "world" || m->preserved_fixed_joints.count(jit->name))
      continue;
    const Joint J = *jit;
    const auto lit = std::find_if(m->links.begin(), m->links.end(), [&](const Link& l) { return l.name == name; });
    const auto pit = std::find_if(m->links.begin(), m->links.end(), [&](const Link& l) { return l.name == J.parent; });
    if (lit == m->links.end() || pit == m->links.end()) continue;
    Link L = *lit;
    Link& P = *pit;
    const Eigen::Isometry3d& T = J.origin;  // L's frame in P's frame

    // mass properties (a child without mass adds none)
    if (!massless(L)) P.inertial = combine(P.inertial, *L.inertial, T);
    // shapes, with composed poses; they remember the link they were written on for its surface settings
    for (auto c : L.collisions) {
      c.origin = T * c.origin;
      if (c.lumped_from.empty()) c.lumped_from = L.name;
      P.collisions.push_back(std::move(c));
    }
    for (auto v : L.visuals) {
      v.shape.origin = T * v.shape.origin;
      if (v.shape.lumped_from.empty()) v.shape.lumped_from = L.name;
      P.visuals.push_back(std::move(v));
    }
    size_t n_sensors = 0;
    for (auto& s : m->sensors) {
      if (s.link != L.name) continue;
      s.link = P.name;
      s.pose = T * s.pose;
      if (s.lumped_from.empty()) s.lumped_from = L.name;
      ++n_sensors;
    }
    // links lumped into L earlier now live in P
    for (auto& e : m->lumped) {
      if (e.parent != L.name) continue;
      e.parent = P.name;
      e.pose = T * e.pose;
    }
    // joints below L hang from P (ReduceJointsToParent)
    for (auto& j : m->joints) {
      if (j.parent != L.name) continue;
      j.parent = P.name;
      j.origin = T * j.origin;
    }
    // robot-level plug-ins naming L as their body or frame name P, their offsets rewritten
    for (auto& p : m->plugins) {
      plugin_frame_replace(&p.params, "bodyName", L.name, P.name, T);
      plugin_frame_replace(&p.params, "frameName", L.name, P.name, T);
    }

    LumpedLink e;
    e.name = L.name;
    e.parent = P.name;
    e.joint = J.name;
    e.pose = T;
    e.gazebo = L.gazebo;
    e.line = line_in(lines, L.name);
    m->lumped.push_back(e);
    m->diagnostics.push_back(
        {Severity::Info, "link-lumped", "link[" + L.name + "]",
         "link '" + L.name + "' lumped into '" + P.name + "' (fixed joint '" + J.name + "'): " +
             plural(L.collisions.size(), "collision") + ", " + plural(L.visuals.size(), "visual") + ", " +
             plural(n_sensors, "sensor") + ", mass " + fmt(massless(L) ? 0.0 : L.inertial->mass) + " kg",
         e.line});
    m->joints.erase(std::find_if(m->joints.begin(), m->joints.end(), [&](const Joint& j) { return j.name == J.name; }));
    m->links.erase(std::find_if(m->links.begin(), m->links.end(), [&](const Link& l) { return l.name == L.name; }));
  }
}

void drop_massless_links(RobotModel* m, const std::map<std::string, int>& lines) {
  const Link* root = m->find_link(m->root_link);
  if (root && root->name != "world" && massless(*root)) {
    m->diagnostics.push_back({Severity::Error, "root-massless", "link[" + root->name + "]",
                              "root link '" + root->name +
                                  "' has no mass (no <inertial> or mass 0), also after lumping the links fixed to "
                                  "it; Gazebo models nothing of this robot",
                              line_in(lines, root->name)});
    return;
  }
  std::map<std::string, std::vector<const Joint*>> kids;
  for (const auto& j : m->joints) kids[j.parent].push_back(&j);
  std::set<std::string> gone_links, gone_joints;
  std::vector<DroppedLink> dropped;
  std::function<void(const std::string&, std::vector<std::string>*)> collect = [&](const std::string& l,
                                                                                   std::vector<std::string>* out) {
    for (const Joint* j : kids[l]) {
      out->push_back(j->child);
      gone_joints.insert(j->name);
      collect(j->child, out);
    }
  };
  std::function<void(const std::string&)> walk = [&](const std::string& l) {
    for (const Joint* j : kids[l]) {
      const Link* c = m->find_link(j->child);
      if (c && c->name != "world" && massless(*c)) {
        DroppedLink d;
        d.name = c->name;
        d.joint = j->name;
        d.line = line_in(lines, c->name);
        collect(c->name, &d.subtree);
        gone_links.insert(c->name);
        gone_joints.insert(j->name);
        for (const auto& s : d.subtree) gone_links.insert(s);
        dropped.push_back(std::move(d));
      } else {
        walk(j->child);
      }
    }
  };
  walk(m->root_link);
  for (const auto& d : dropped) {
    std::string below;
    for (const auto& s : d.subtree) below += (below.empty() ? "" : ", ") + s;
    const Joint* j = m->find_joint(d.joint);
    m->diagnostics.push_back(
        {Severity::Warning, "link-dropped", "link[" + d.name + "]",
         "link '" + d.name + "' has no mass (no <inertial> or mass 0) on " + (j ? to_string(j->type) : "") +
             " joint '" + d.joint + "': Gazebo does not model it; dropped with its joint" +
             (d.subtree.empty() ? std::string() : " and the links below it (" + below + ")"),
         d.line});
  }
  if (dropped.empty()) return;
  m->dropped.insert(m->dropped.end(), dropped.begin(), dropped.end());
  m->links.erase(std::remove_if(m->links.begin(), m->links.end(), [&](const Link& l) { return gone_links.count(l.name); }),
                 m->links.end());
  m->joints.erase(
      std::remove_if(m->joints.begin(), m->joints.end(), [&](const Joint& j) { return gone_joints.count(j.name); }),
      m->joints.end());
  m->sensors.erase(
      std::remove_if(m->sensors.begin(), m->sensors.end(), [&](const SensorSpec& s) { return gone_links.count(s.link); }),
      m->sensors.end());
  m->lumped.erase(
      std::remove_if(m->lumped.begin(), m->lumped.end(), [&](const LumpedLink& l) { return gone_links.count(l.parent); }),
      m->lumped.end());
}

}  // namespace detail
}  // namespace car_sim
