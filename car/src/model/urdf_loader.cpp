// URDF loading: urdfdom reads links and joints; a tinyxml2 pass over the same text reads what urdfdom
// ignores (<gazebo> extensions) or silently drops (out-of-range colours, axes of fixed joints).
#include <console_bridge/console.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "car_sim/model.hpp"
#include "lumping.hpp"
#include "validate.hpp"
#include "xml_util.hpp"

namespace car_sim {

using detail::parse_number;
using detail::parse_numbers;
using detail::text_of;
using detail::trim;

const char* to_string(Severity s) {
  switch (s) {
    case Severity::Info: return "info";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "?";
}

const char* to_string(ShapeType t) {
  switch (t) {
    case ShapeType::Box: return "box";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Mesh: return "mesh";
    case ShapeType::Plane: return "plane";
  }
  return "?";
}

const char* to_string(JointType t) {
  switch (t) {
    case JointType::Fixed: return "fixed";
    case JointType::Continuous: return "continuous";
    case JointType::Revolute: return "revolute";
    case JointType::Prismatic: return "prismatic";
    case JointType::Floating: return "floating";
    case JointType::Planar: return "planar";
  }
  return "?";
}

// Control characters written as \xNN (newline and tab kept): what() is a C string, so a NUL in a name (a ROS
// string may hold one, found by test/fuzz/fuzz_spawn) would cut the message short.
static std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      static const char* kHex = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xf];
    } else {
      out += ch;
    }
  }
  return out;
}

static std::string format_error(const std::string& file, int line, const std::string& element,
                                const std::string& reason) {
  std::ostringstream os;
  os << file;
  if (line > 0) os << ":" << line;
  if (!element.empty()) os << ": " << element;
  os << ": " << reason;
  return printable(os.str());
}

// An error always names its source: a document given without a name (an empty SpawnModel model_name, found by
// test/fuzz/fuzz_spawn) is "<string>", the loaders' default name, not "" (": malformed XML: ...").
static std::string source_or_default(const std::string& file) { return file.empty() ? "<string>" : printable(file); }

LoadError::LoadError(std::string file, int line, std::string element, std::string reason)
    : std::runtime_error(format_error(source_or_default(file), line, element, reason)),
      file_(source_or_default(file)),
      line_(line),
      element_(printable(element)),
      reason_(printable(reason)) {}

const std::string* find_param(const ParamList& params, const std::string& key) {
  const std::string* found = nullptr;
  for (const auto& kv : params)
    if (kv.first == key) found = &kv.second;
  return found;
}

const Link* RobotModel::find_link(const std::string& n) const {
  for (const auto& l : links)
    if (l.name == n) return &l;
  return nullptr;
}

const Joint* RobotModel::find_joint(const std::string& n) const {
  for (const auto& j : joints)
    if (j.name == n) return &j;
  return nullptr;
}

const Joint* RobotModel::parent_joint(const std::string& link) const {
  for (const auto& j : joints)
    if (j.child == link) return &j;
  return nullptr;
}

Eigen::Isometry3d RobotModel::link_pose_in_root(const std::string& link) const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  std::string cur = link;
  if (const LumpedLink* l = find_lumped(link)) {
    T = l->pose;
    cur = l->parent;
  }
  // A URDF tree has at most links.size() joints on any path to the root.
  for (size_t guard = 0; guard <= links.size(); ++guard) {
    const Joint* j = parent_joint(cur);
    if (!j) return T;
    T = j->origin * T;
    cur = j->parent;
  }
  return T;
}

namespace {
std::string fmt(double v) { return detail::short_number(v); }

std::string fmt3(const Eigen::Vector3d& v) { return fmt(v.x()) + " " + fmt(v.y()) + " " + fmt(v.z()); }

}  // namespace

std::string inertial_problem(double mass, const Eigen::Matrix3d& /*inertia*/, std::string* code) {
  if (mass > 0.0) return "";
  if (code) *code = "mass-nonpositive";
  return "mass " + fmt(mass) + " kg is not > 0";
}

namespace {
// ODE's test in dBodySetMass: dInvertPDMatrix's Cholesky factorisation fails at a pivot <= 0, as Eigen's LLT does.
bool invertible(const Eigen::Matrix3d& inertia) {
  return Eigen::LLT<Eigen::Matrix3d>(inertia).info() == Eigen::Success;
}
}  // namespace

Eigen::Matrix3d simulated_inertia(const Eigen::Matrix3d& inertia) {
  return invertible(inertia) ? inertia : Eigen::Matrix3d::Identity();
}

std::string inertial_warning(const Eigen::Matrix3d& inertia, std::string* code) {
  auto say = [&](const char* c, const std::string& why) {
    if (code) *code = c;
    return why;
  };
  const Eigen::Vector3d p = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();  // ascending
  if (!invertible(inertia))
    return say("inertia-not-positive-definite",
               "principal moments (" + fmt3(p) + ") kg m^2 are not all > 0: Gazebo 11 (ODE's dBodySetMass) cannot "
               "invert the tensor and simulates the body with 1 kg m^2 about every axis; car does the same");
  if (p(0) + p(1) < p(2) * (1.0 - 1e-9))
    return say("inertia-triangle", "principal moments (" + fmt3(p) + ") kg m^2 break the triangle inequality "
                                   "I1 + I2 >= I3 (no rigid body has them); simulated as written, as in Gazebo 11");
  return "";
}

namespace {

// Collects what urdfdom reports through console_bridge, so a failed parse can say why.
class CaptureHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
  std::vector<std::string> errors;
};

Eigen::Isometry3d to_iso(const urdf::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  T.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).normalized()
                   .toRotationMatrix();
  return T;
}

Shape urdf_shape(const urdf::GeometrySharedPtr& g, const urdf::Pose& origin) {
  Shape s;
  s.origin = to_iso(origin);
  switch (g->type) {
    case urdf::Geometry::BOX: {
      const auto b = std::static_pointer_cast<urdf::Box>(g);
      s.type = ShapeType::Box;
      s.size = Eigen::Vector3d(b->dim.x, b->dim.y, b->dim.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto c = std::static_pointer_cast<urdf::Cylinder>(g);
      s.type = ShapeType::Cylinder;
      s.radius = c->radius;
      s.length = c->length;
      break;
    }
    case urdf::Geometry::SPHERE: {
      s.type = ShapeType::Sphere;
      s.radius = std::static_pointer_cast<urdf::Sphere>(g)->radius;
      break;
    }
    case urdf::Geometry::MESH: {
      const auto m = std::static_pointer_cast<urdf::Mesh>(g);
      s.type = ShapeType::Mesh;
      s.mesh_uri = m->filename;
      s.mesh_scale = Eigen::Vector3d(m->scale.x, m->scale.y, m->scale.z);
      break;
    }
  }
  return s;
}

JointType to_joint_type(int t) {
  switch (t) {
    case urdf::Joint::REVOLUTE: return JointType::Revolute;
    case urdf::Joint::CONTINUOUS: return JointType::Continuous;
    case urdf::Joint::PRISMATIC: return JointType::Prismatic;
    case urdf::Joint::FLOATING: return JointType::Floating;
    case urdf::Joint::PLANAR: return JointType::Planar;
    default: return JointType::Fixed;
  }
}

// Everything the raw pass and the checks need to report findings with line numbers.
class Loader {
 public:
  Loader(std::string source, RobotModel* model) : source_(std::move(source)), m_(model) {}

  void add(Severity sev, const std::string& code, const std::string& element, const std::string& msg,
           int line) {
    m_->diagnostics.push_back({sev, code, element, msg, line});
  }

  int line_of(const char* tag, const std::string& name) const {
    const auto it = lines_.find(std::string(tag) + "[" + name + "]");
    return it == lines_.end() ? 0 : it->second;
  }

  void index_lines(const tinyxml2::XMLElement* robot) {
    for (auto* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const char* name = e->Attribute("name");
      if (name) lines_[std::string(e->Name()) + "[" + name + "]"] = e->GetLineNum();
    }
  }

  // Colour components outside [0, 1]: urdfdom drops such a colour with only a console message.
  void check_colours(const tinyxml2::XMLElement* e, const std::string& path) {
    for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string name = c->Name();
      if (name == "gazebo") continue;
      const char* attr_name = c->Attribute("name");
      const std::string here = path.empty() ? (attr_name ? name + "[" + attr_name + "]" : name)
                                            : path + "/" + (attr_name ? name + "[" + attr_name + "]" : name);
      if (name == "color") {
        const char* rgba = c->Attribute("rgba");
        const auto v = parse_numbers(rgba ? rgba : "", 4);
        if (!v) {
          add(Severity::Warning, "colour-malformed", here,
              std::string("rgba '") + (rgba ? rgba : "") + "' is not 4 numbers; urdfdom drops this colour",
              c->GetLineNum());
          continue;
        }
        std::vector<std::string> bad;
        for (double x : *v)
          if (x < 0.0 || x > 1.0) bad.push_back(fmt(x));
        if (!bad.empty()) {
          std::string list;
          for (const auto& b : bad) list += (list.empty() ? "" : ", ") + b;
          add(Severity::Warning, "colour-range", here,
              std::string("rgba '") + rgba + "' has component(s) " + list +
                  " outside [0, 1]; urdfdom drops this colour, so rviz shows the link without it",
              c->GetLineNum());
        }
        continue;
      }
      check_colours(c, here);
    }
  }

  // Axes written on fixed joints are ignored by urdfdom; a zero one there is harmless but worth a note.
  void check_fixed_axes(const tinyxml2::XMLElement* robot) {
    for (auto* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
      const char* type = j->Attribute("type");
      const char* name = j->Attribute("name");
      if (!type || !name || std::string(type) != "fixed") continue;
      if (auto* a = j->FirstChildElement("axis")) {
        const char* xyz = a->Attribute("xyz");
        add(Severity::Info, "axis-ignored", std::string("joint[") + name + "]/axis",
            std::string("axis '") + (xyz ? xyz : "") + "' on a fixed joint is ignored", a->GetLineNum());
      }
    }
  }

  void convert(const urdf::ModelInterface& u, const tinyxml2::XMLElement* robot) {
    m_->name = u.getName();
    m_->root_link = u.getRoot() ? u.getRoot()->name : "";
    // Document order, so listings follow the file.
    for (auto* e = robot->FirstChildElement("link"); e; e = e->NextSiblingElement("link")) {
      const char* n = e->Attribute("name");
      if (!n) continue;
      const auto ul = u.getLink(n);
      if (!ul || m_->find_link(n)) continue;
      m_->links.push_back(convert_link(*ul));
    }
    for (auto* e = robot->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) {
      const char* n = e->Attribute("name");
      if (!n) continue;
      const auto it = u.joints_.find(n);
      if (it == u.joints_.end() || m_->find_joint(n)) continue;
      m_->joints.push_back(convert_joint(*it->second));
    }
  }

  Link convert_link(const urdf::Link& ul) {
    Link l;
    l.name = ul.name;
    if (ul.inertial) {
      Inertial in;
      in.mass = ul.inertial->mass;
      in.origin = to_iso(ul.inertial->origin);
      const auto& i = *ul.inertial;
      in.inertia << i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz;
      l.inertial = in;
    }
    for (const auto& c : ul.collision_array)
      if (c && c->geometry) l.collisions.push_back(urdf_shape(c->geometry, c->origin));
    for (const auto& v : ul.visual_array) {
      if (!v || !v->geometry) continue;
      Visual vis;
      vis.name = v->name;
      vis.shape = urdf_shape(v->geometry, v->origin);
      vis.material.name = v->material_name;
      if (v->material) {
        vis.material.name = v->material->name;
        vis.material.texture = v->material->texture_filename;
        const auto& c = v->material->color;
        // urdfdom leaves colour at 0 0 0 0 when only a texture or only a name was given.
        if (c.r != 0.f || c.g != 0.f || c.b != 0.f || c.a != 0.f) {
          vis.material.has_rgba = true;
          vis.material.rgba = Eigen::Vector4d(c.r, c.g, c.b, c.a);
        }
      }
      l.visuals.push_back(std::move(vis));
    }
    return l;
  }

  Joint convert_joint(const urdf::Joint& uj) {
    Joint j;
    j.name = uj.name;
    j.type = to_joint_type(uj.type);
    j.parent = uj.parent_link_name;
    j.child = uj.child_link_name;
    j.origin = to_iso(uj.parent_to_joint_origin_transform);
    j.axis_as_written = Eigen::Vector3d(uj.axis.x, uj.axis.y, uj.axis.z);
    if (uj.limits) j.limits = JointLimits{uj.limits->lower, uj.limits->upper, uj.limits->effort,
                                          uj.limits->velocity};
    if (uj.dynamics) {
      j.damping = uj.dynamics->damping;
      j.friction = uj.dynamics->friction;
    }
    const std::string where = "joint[" + j.name + "]/axis";
    const int line = line_of("joint", j.name);
    if (j.type == JointType::Fixed || j.type == JointType::Floating) {
      j.axis = Eigen::Vector3d::UnitX();
      return j;
    }
    const double n = j.axis_as_written.norm();
    if (n < 1e-9) {
      add(Severity::Error, "axis-zero", where, "axis has zero length; a " + std::string(to_string(j.type)) +
          " joint needs a direction", line);
      j.axis = Eigen::Vector3d::UnitX();
    } else {
      j.axis = j.axis_as_written / n;
      if (std::abs(n - 1.0) > 1e-6)
        add(Severity::Warning, "axis-normalised", where,
            "axis (" + fmt3(j.axis_as_written) + ") has length " + fmt(n) + "; normalised to (" + fmt3(j.axis) + ")",
            line);
    }
    return j;
  }

  // A negative mass is refused on each link as written (lumping would fold it into its parent).
  // A link without <inertial> or with mass 0 is massless: lumped into its parent on a fixed joint, dropped on
  // a moving one (lumping.cpp), never an error by itself.
  void check_masses() {
    for (const auto& l : m_->links) {
      if (!l.inertial || l.inertial->mass == 0.0) continue;
      std::string code;
      const std::string why = inertial_problem(l.inertial->mass, l.inertial->inertia, &code);
      if (!why.empty()) add(Severity::Error, code, "link[" + l.name + "]/inertial/mass", why, line_of("link", l.name));
    }
  }

  // The tensors the physics gets: each kept link's after lumping (a lumped link's own tensor never reaches it).
  // What Gazebo 11 loads but no rigid body has is a warning saying what is simulated.
  void check_inertias() {
    for (const auto& l : m_->links) {
      if (!l.inertial || !(l.inertial->mass > 0.0)) continue;
      std::string code;
      const std::string why = inertial_warning(l.inertial->inertia, &code);
      if (!why.empty())
        add(Severity::Warning, code, "link[" + l.name + "]/inertial/inertia", why, line_of("link", l.name));
    }
  }

  std::map<std::string, int> link_lines() const {
    std::map<std::string, int> out;
    for (const auto& l : m_->links) out[l.name] = line_of("link", l.name);
    return out;
  }

  std::string source_;
  RobotModel* m_;
  std::map<std::string, int> lines_;
};

}  // namespace

void parse_gazebo_extensions(const tinyxml2::XMLElement* robot, RobotModel* model);  // gazebo_ext.cpp

namespace {

// <transmission>s as transmission_interface's parser reads them: <type> (or the old type attribute), each
// <joint name> with its <hardwareInterface>s, each <actuator name> (interfaces there are the old form: they
// apply to the joints that name none) and its <mechanicalReduction>. Checked by the ros_control kind.
void parse_transmissions(const tinyxml2::XMLElement* robot, RobotModel* model) {
  auto text = [](const tinyxml2::XMLElement* e) {
    std::string s = e && e->GetText() ? e->GetText() : "";
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return std::string();
    return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
  };
  auto strip = [](std::string s) {
    const std::string prefix = "hardware_interface/";
    if (s.rfind(prefix, 0) == 0) s = s.substr(prefix.size());
    return s;
  };
  for (auto* t = robot->FirstChildElement("transmission"); t; t = t->NextSiblingElement("transmission")) {
    Transmission tr;
    tr.name = t->Attribute("name") ? t->Attribute("name") : "";
    tr.line = t->GetLineNum();
    tr.type = text(t->FirstChildElement("type"));
    if (tr.type.empty() && t->Attribute("type")) tr.type = t->Attribute("type");
    std::vector<std::string> actuator_interfaces;
    for (auto* a = t->FirstChildElement("actuator"); a; a = a->NextSiblingElement("actuator")) {
      tr.actuators.push_back(a->Attribute("name") ? a->Attribute("name") : "");
      for (auto* h = a->FirstChildElement("hardwareInterface"); h; h = h->NextSiblingElement("hardwareInterface"))
        actuator_interfaces.push_back(strip(text(h)));
      const auto* r = a->FirstChildElement("mechanicalReduction");
      if (!r) r = t->FirstChildElement("mechanicalReduction");
      if (r && tr.actuators.size() == 1) {
        try {
          tr.reduction = std::stod(text(r));
        } catch (const std::exception&) {
          model->diagnostics.push_back({Severity::Error, "bad_number",
                                        "transmission[" + tr.name + "]/mechanicalReduction",
                                        "'" + text(r) + "' is not a number", r->GetLineNum()});
        }
      }
    }
    for (auto* j = t->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
      Transmission::JointEntry e;
      e.joint = j->Attribute("name") ? j->Attribute("name") : "";
      for (auto* h = j->FirstChildElement("hardwareInterface"); h; h = h->NextSiblingElement("hardwareInterface"))
        e.interfaces.push_back(strip(text(h)));
      if (e.interfaces.empty()) e.interfaces = actuator_interfaces;
      tr.joints.push_back(e);
    }
    model->transmissions.push_back(tr);
  }
}

}  // namespace

RobotModel load_urdf_string(const std::string& xml, const std::string& source_name, const LoadOptions& options) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    // "XML_ERROR_MISMATCHED_ELEMENT" -> "mismatched element", plus tinyxml2's detail after "Line number=N: "
    std::string what = doc.ErrorName();
    if (what.rfind("XML_ERROR_", 0) == 0) what = what.substr(10);
    for (auto& c : what) c = c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const std::string full = doc.ErrorStr() ? doc.ErrorStr() : "";
    const auto at = full.find(": ", full.find("Line number="));
    if (at != std::string::npos && full.find("Line number=") != std::string::npos) what += ": " + full.substr(at + 2);
    throw LoadError(source_name, doc.ErrorLineNum(), "", "malformed XML: " + what);
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Name()) != "robot")
    throw LoadError(source_name, robot ? robot->GetLineNum() : 0, robot ? robot->Name() : "",
                    "root element is not <robot>; is this a URDF?");

  std::vector<Diagnostic> checked = detail::validate_urdf(doc, source_name);  // validate.cpp: throws on unusable numbers
  CaptureHandler capture;
  console_bridge::useOutputHandler(&capture);
  const urdf::ModelInterfaceSharedPtr u = urdf::parseURDF(xml);
  console_bridge::restorePreviousOutputHandler();
  if (!u) {
    std::string why;
    for (const auto& e : capture.errors) why += (why.empty() ? "" : "; ") + trim(e);
    throw LoadError(source_name, 0, "robot", why.empty() ? "urdfdom rejected the model" : why);
  }

  RobotModel model;
  model.source = source_name;
  model.diagnostics = std::move(checked);
  Loader loader(source_name, &model);
  loader.index_lines(robot);
  loader.convert(*u, robot);
  // urdfdom takes a <link> without a name for one named "", which no body can stand for (found by fuzz_urdf)
  if (!model.find_link(model.root_link))
    throw LoadError(source_name, robot->GetLineNum(), "robot", "its root link has no name (every <link> needs a name)");
  // a joint whose child is its own parent, or a loop, leaves links that hang from no root (found by fuzz_urdf)
  for (const auto& j : model.joints) {
    const int line = loader.line_of("joint", j.name);
    if (j.parent == j.child)
      throw LoadError(source_name, line, "joint[" + j.name + "]",
                      "its parent and child are the same link '" + j.child + "'");
    // urdfdom and car's XML reader may read a name differently (an unescaped '&': found by fuzz_urdf)
    for (const std::string* l : {&j.parent, &j.child})
      if (!model.find_link(*l))
        throw LoadError(source_name, line, "joint[" + j.name + "]", "names link '" + *l + "', which the model does not hold");
  }
  loader.check_colours(robot, "");
  loader.check_fixed_axes(robot);
  loader.check_masses();
  // collisions with a size <= 0 (validate_urdf warned about each): left out, as docs/COMPAT-validation.md says
  detail::drop_degenerate_collisions(&model);
  parse_gazebo_extensions(robot, &model);
  parse_transmissions(robot, &model);
  // As sdformat's URDF reader: anchor to `world`, lump fixed joints, drop massless links on moving joints.
  detail::find_world_anchor(&model);
  if (options.lump_fixed_joints) {
    const auto lines = loader.link_lines();
    detail::lump_fixed_joints(&model, lines);
    detail::drop_massless_links(&model, lines);
  }
  loader.check_inertias();

  if (options.throw_on_error) {
    for (const auto& d : model.diagnostics)
      if (d.severity == Severity::Error) throw LoadError(source_name, d.line, d.element, d.message);
  }
  return model;
}

RobotModel load_urdf_file(const std::string& path, const LoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LoadError(path, 0, "", "cannot open file");
  std::stringstream ss;
  ss << in.rdbuf();
  return load_urdf_string(ss.str(), path, options);
}

}  // namespace car_sim
