// SDF robots: an sdformat DOM model to the core's RobotModel (links with SDF's default inertia, shapes, <surface>,
// joints, <plugin>s and <sensor>s), so an SDF robot is spawned and simulated as a URDF robot is.
// Rules and upstream sources: docs/COMPAT-sdf.md (numbers in comments refer to its rules).
#include "sdf_model.hpp"

#include <sdf/sdf.hh>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "car_sim/description.hpp"
#include "geometry.hpp"
#include "lumping.hpp"
#include "validate.hpp"
#include "xml_util.hpp"

namespace car_sim {

sdf::ParserConfig parser_config(const std::string& world_file);  // sdf_world.cpp: the include rule
void parse_gazebo_extensions(const tinyxml2::XMLElement* robot, RobotModel* model);  // model/gazebo_ext.cpp

namespace detail {

Eigen::Isometry3d to_iso(const ignition::math::Pose3d& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p.Pos().X(), p.Pos().Y(), p.Pos().Z());
  T.linear() = Eigen::Quaterniond(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z()).normalized().toRotationMatrix();
  return T;
}

int line_of(const sdf::ElementPtr& e) { return e && e->LineNumber() ? *e->LineNumber() : 0; }

void refuse_errors(const std::string& source, const sdf::Errors& all, std::vector<Diagnostic>* warnings) {
  sdf::Errors errors;
  bool inertia = false;
  for (const auto& e : all) {
    // LINK_INERTIA_INVALID is libsdformat's DOM; Gazebo 11 reads <inertial> from the element tree and simulates
    // such a link (ODE's rule): car's own check warns instead (inertial_warning, docs/COMPAT-validation.md "Inertia")
    if (e.Code() == sdf::ErrorCode::LINK_INERTIA_INVALID) {
      inertia = true;
      continue;
    }
    // an <include> that resolves nowhere: sdformat (9 as 12) reports it and goes on without that model, and Gazebo
    // 11 loads the rest (docs/COMPAT-validation.md)
    const bool include = e.Code() == sdf::ErrorCode::URI_LOOKUP ||
                         (e.Code() == sdf::ErrorCode::ATTRIBUTE_MISSING &&
                          e.Message() == "<include> element missing 'uri' attribute");
    if (include && warnings) {
      std::string dirs;
      for (const auto& d : model_path()) dirs += (dirs.empty() ? "" : ":") + d;
      warnings->push_back({Severity::Warning, "include-missing", e.XmlPath() ? *e.XmlPath() : "include",
                           e.Message() + " (model path: " + dirs + "): left out, as Gazebo 11 leaves it out",
                           e.LineNumber() ? *e.LineNumber() : 0});
      continue;
    }
    errors.push_back(e);
  }
  // a world whose only trouble was an inertia is kept by libsdformat all the same; its "Failed to load a world."
  // says no more than the inertia errors did
  if (inertia)
    errors.erase(std::remove_if(errors.begin(), errors.end(),
                                [](const sdf::Error& e) { return e.Message() == "Failed to load a world."; }),
                 errors.end());
  if (errors.empty()) return;
  const sdf::Error& e = errors.front();
  std::string reason = e.Message();
  if (errors.size() > 1) reason += " (and " + std::to_string(errors.size() - 1) + " more)";
  // an error inside an included file names that file; one in the text itself names the source (sdformat calls it
  // "data-string")
  const bool in_file = e.FilePath() && *e.FilePath() != "data-string" && std::ifstream(*e.FilePath()).good();
  throw LoadError(in_file ? *e.FilePath() : source, e.LineNumber() ? *e.LineNumber() : 0,
                  e.XmlPath() ? *e.XmlPath() : "", reason);
}

}  // namespace detail

// The geometry to_shape converts (its switch below); keep the two together.
const std::vector<std::string>& simulated_geometry() {
  static const std::vector<std::string> kNames = {"box", "cylinder", "sphere", "plane", "mesh"};
  return kNames;
}

namespace detail {

Inertial read_inertial(const sdf::Link& l) {
  const auto& in = l.Inertial();
  Inertial ci;
  ci.mass = in.MassMatrix().Mass();
  ci.origin = to_iso(in.Pose());
  const auto moi = in.MassMatrix().Moi();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) ci.inertia(r, c) = moi(r, c);
  return ci;
}

// Rule 9: box, cylinder, sphere, mesh, plane; anything else is skipped with a warning (the world loader too).
std::optional<WorldVisual> read_visual(const sdf::Visual& v, const std::string& where,
                                       std::vector<Diagnostic>* diagnostics) {
  auto shape = to_shape(*v.Geom(), where + "/visual[" + v.Name() + "]", line_of(v.Element()), diagnostics);
  if (!shape) return std::nullopt;
  ignition::math::Pose3d vp;
  v.SemanticPose().Resolve(vp);  // relative to the link
  shape->origin = to_iso(vp);
  WorldVisual wv;
  wv.name = v.Name();
  wv.shape = *shape;
  if (const sdf::Material* m = v.Material()) {
    auto rgba = [](const ignition::math::Color& c) { return Eigen::Vector4d(c.R(), c.G(), c.B(), c.A()); };
    wv.script_name = m->ScriptName();
    const sdf::ElementPtr me = m->Element();
    if (me && me->HasElement("diffuse")) {
      wv.material.has_rgba = true;
      wv.material.rgba = rgba(m->Diffuse());
    }
    if (me && me->HasElement("ambient")) {
      wv.has_ambient = true;
      wv.ambient = rgba(m->Ambient());
    }
    wv.material.name = wv.script_name;
  }
  return wv;
}

std::optional<Shape> to_shape(const sdf::Geometry& g, const std::string& where, int line,
                              std::vector<Diagnostic>* diagnostics) {
  Shape s;
  switch (g.Type()) {
    case sdf::GeometryType::BOX:
      s.type = ShapeType::Box;
      s.size = Eigen::Vector3d(g.BoxShape()->Size().X(), g.BoxShape()->Size().Y(), g.BoxShape()->Size().Z());
      return s;
    case sdf::GeometryType::CYLINDER:
      s.type = ShapeType::Cylinder;
      s.radius = g.CylinderShape()->Radius();
      s.length = g.CylinderShape()->Length();
      return s;
    case sdf::GeometryType::SPHERE:
      s.type = ShapeType::Sphere;
      s.radius = g.SphereShape()->Radius();
      return s;
    case sdf::GeometryType::PLANE: {
      s.type = ShapeType::Plane;
      const auto n = g.PlaneShape()->Normal();
      s.normal = Eigen::Vector3d(n.X(), n.Y(), n.Z()).normalized();
      s.size = Eigen::Vector3d(g.PlaneShape()->Size().X(), g.PlaneShape()->Size().Y(), 0.0);
      return s;
    }
    case sdf::GeometryType::MESH:
      s.type = ShapeType::Mesh;
      s.mesh_uri = g.MeshShape()->Uri();
      s.mesh_scale = Eigen::Vector3d(g.MeshShape()->Scale().X(), g.MeshShape()->Scale().Y(), g.MeshShape()->Scale().Z());
      return s;
    default:
      diagnostics->push_back({Severity::Warning, "geometry-unsupported", where,
                              "geometry type not simulated by car; the shape is ignored", line});
      return std::nullopt;
  }
}

}  // namespace detail

using detail::refuse_errors;
using detail::line_of;
using detail::to_iso;

namespace {

// A child element by path ("friction/ode/mu"), nullptr when any step is absent (never creates one).
sdf::ElementPtr find_path(sdf::ElementPtr e, const std::string& path) {
  std::stringstream ss(path);
  std::string step;
  while (e && std::getline(ss, step, '/')) e = e->HasElement(step) ? e->GetElement(step) : nullptr;
  return e;
}

// Rule 8: a collision's <surface> on the URDF path's GazeboLinkExt fields; only values written are set.
GazeboLinkExt read_surface(const sdf::Collision& c) {
  GazeboLinkExt ext;
  const sdf::ElementPtr s = find_path(c.Element(), "surface");
  if (!s) return ext;
  auto num = [&](const char* path) -> std::optional<double> {
    if (auto e = find_path(s, path)) return e->Get<double>();
    return std::nullopt;
  };
  ext.mu1 = num("friction/ode/mu");
  ext.mu2 = num("friction/ode/mu2");
  if (auto e = find_path(s, "friction/ode/fdir1")) {
    const auto v = e->Get<ignition::math::Vector3d>();
    ext.fdir1 = Eigen::Vector3d(v.X(), v.Y(), v.Z());
  }
  ext.kp = num("contact/ode/kp");
  ext.kd = num("contact/ode/kd");
  ext.min_depth = num("contact/ode/min_depth");
  ext.max_vel = num("contact/ode/max_vel");
  return ext;
}

bool same_surface(const GazeboLinkExt& a, const GazeboLinkExt& b) {
  return a.mu1 == b.mu1 && a.mu2 == b.mu2 && a.kp == b.kp && a.kd == b.kd && a.min_depth == b.min_depth &&
         a.max_vel == b.max_vel && a.fdir1.has_value() == b.fdir1.has_value() &&
         (!a.fdir1 || a.fdir1->isApprox(*b.fdir1));
}

bool surface_empty(const GazeboLinkExt& a) { return same_surface(a, GazeboLinkExt()); }

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

Link convert_link(const sdf::Link& l, const std::string& where, RobotModel* m) {
  Link out;
  out.name = l.Name();
  // Rule 3: the DOM fills SDF's defaults (mass 1 kg, inertia diag(1, 1, 1) kg m^2) when <inertial> is absent.
  const Inertial ci = detail::read_inertial(l);
  // a mass <= 0 is refused (Gazebo 11's ODELink::UpdateMass throws); a tensor no rigid body has is a warning
  // saying what is simulated (docs/COMPAT-validation.md "Inertia")
  std::string code;
  if (const std::string why = inertial_problem(ci.mass, ci.inertia); !why.empty())
    m->diagnostics.push_back({Severity::Error, "inertial", where + "/inertial", why, line_of(l.Element())});
  else if (const std::string warn = inertial_warning(ci.inertia, &code); !warn.empty())
    m->diagnostics.push_back({Severity::Warning, code, where + "/inertial/inertia", warn, line_of(l.Element())});
  out.inertial = ci;
  std::string surface_from;
  std::optional<double> laser_retro;
  for (uint64_t i = 0; i < l.CollisionCount(); ++i) {
    const sdf::Collision* c = l.CollisionByIndex(i);
    const std::string here = where + "/collision[" + c->Name() + "]";
    auto shape = detail::to_shape(*c->Geom(), here, line_of(c->Element()), &m->diagnostics);
    if (!shape) continue;
    // a size <= 0: Gazebo 11 warns and simulates the model; car leaves the shape out (docs/COMPAT-validation.md)
    if (detail::degenerate_shape(*shape)) {
      m->diagnostics.push_back({Severity::Warning, "shape-size", here,
                                "a size is not > 0; the collision is left out of the collision world (the model is "
                                "simulated)",
                                line_of(c->Element())});
      continue;
    }
    ignition::math::Pose3d cp;
    c->SemanticPose().Resolve(cp);  // rule 4: relative to the link
    shape->origin = to_iso(cp);
    out.collisions.push_back(*shape);
    // <laser_retro> (collision level, 0 when absent): what ray sensors read as intensity; car keeps one per link,
    // the first collision's that sets one
    if (!laser_retro && c->Element() && c->Element()->HasElement("laser_retro"))
      laser_retro = c->Element()->Get<double>("laser_retro");
    const GazeboLinkExt ext = read_surface(*c);
    if (surface_empty(ext)) continue;
    if (surface_from.empty()) {
      surface_from = c->Name();
      const std::string material = out.gazebo.material;
      out.gazebo = ext;
      out.gazebo.material = material;
    } else if (!same_surface(ext, out.gazebo)) {
      m->diagnostics.push_back({Severity::Warning, "surface-per-link", here + "/surface",
                                "car keeps one surface per link: collision '" + surface_from +
                                    "''s surface is used for every collision of link '" + l.Name() + "'",
                                line_of(c->Element())});
    }
  }
  // after the surfaces (a collision's surface replaces out.gazebo): <gravity>, SDF's per-link switch (default
  // true), the URDF path's <gazebo reference><gravity>; and the laser retro
  if (l.Element() && l.Element()->HasElement("gravity")) out.gazebo.gravity = l.Element()->Get<bool>("gravity");
  if (laser_retro) out.gazebo.laser_retro = laser_retro;
  for (uint64_t i = 0; i < l.VisualCount(); ++i) {
    const auto wv = detail::read_visual(*l.VisualByIndex(i), where, &m->diagnostics);
    if (!wv) continue;
    out.visuals.push_back({wv->name, wv->shape, wv->material});
    // the link's material: its first visual's script ("" without a <material>)
    if (out.gazebo.material.empty()) out.gazebo.material = wv->script_name;
  }
  return out;
}

// Rule 5: SDF joint types onto car's; the others are refused.
JointType to_joint_type(const sdf::Joint& j, const sdf::JointAxis* axis, const std::string& where, int line,
                        const std::string& source) {
  switch (j.Type()) {
    case sdf::JointType::FIXED: return JointType::Fixed;
    case sdf::JointType::CONTINUOUS: return JointType::Continuous;
    case sdf::JointType::PRISMATIC: return JointType::Prismatic;
    case sdf::JointType::REVOLUTE:
      // SDF's "no limit" defaults are -1e16 / 1e16: such a revolute joint turns freely
      if (axis && axis->Lower() <= -1e16 && axis->Upper() >= 1e16) return JointType::Continuous;
      return JointType::Revolute;
    default: break;
  }
  const std::string type = j.Element() && j.Element()->HasAttribute("type")
                               ? j.Element()->GetAttribute("type")->GetAsString()
                               : "?";
  throw LoadError(source, line, where,
                  "joint type '" + type + "' is not simulated by car (revolute, continuous, prismatic and fixed are)");
}

// Rule 10: a model's plug-ins and its links' sensors through the URDF path's <gazebo> reader, so every kind resolves
// the same; their lines are the SDF file's. mwhere: "model[M]". The flattened model's (rule 16a): an included
// model's plug-ins and sensors with their text renamed, on the links' flattened names.
void read_plugins_and_sensors(const detail::FlatModel& f, const std::string& source, const std::string& mwhere,
                              RobotModel* m) {
  std::string xml = "<robot>";
  std::vector<int> plugin_lines;
  for (const auto& p : f.plugins) {
    xml += "<gazebo>" + p.xml + "</gazebo>";
    plugin_lines.push_back(p.line);
  }
  for (const auto& sn : f.sensors) xml += "<gazebo reference=\"" + xml_escape(sn.link) + "\">" + sn.xml + "</gazebo>";
  xml += "</robot>";
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw LoadError(source, 0, mwhere, std::string("cannot read plug-ins and sensors: ") + doc.ErrorStr());
  const size_t before = m->diagnostics.size();
  parse_gazebo_extensions(doc.RootElement(), m);
  // findings of that reader name our elements, but its lines are of the rebuilt text: drop them
  for (size_t i = before; i < m->diagnostics.size(); ++i) m->diagnostics[i].line = 0;
  for (size_t i = 0; i < m->plugins.size() && i < plugin_lines.size(); ++i) m->plugins[i].line = plugin_lines[i];
  for (auto& spec : m->sensors) {
    for (const auto& sn : f.sensors) {
      if (sn.name != spec.name || sn.link != spec.link) continue;
      const sdf::Sensor* s = sn.sensor;
      spec.line = line_of(s->Element());
      ignition::math::Pose3d sp;
      if (s->SemanticPose().Resolve(sp, sn.local_link).empty()) spec.pose = to_iso(sp);  // rule 4
      int k = 0;
      if (s->Element()->HasElement("plugin"))
        for (sdf::ElementPtr p = s->Element()->GetElement("plugin"); p && k < static_cast<int>(spec.plugins.size());
             p = p->GetNextElement("plugin"))
          spec.plugins[k++].line = line_of(p);
    }
  }
}

}  // namespace

namespace {

// sdformat 9's replace_all (src/parser.cc): every `from`, the search going on after each replacement.
void replace_all(std::string* text, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (size_t at = text->find(from); at != std::string::npos; at = text->find(from, at + to.size()))
    text->replace(at, from.size(), to);
}

// addNestedModel's renaming of an included model's text (sdf9 src/parser.cc): each name in `"x"`, `'x'` and `>x<`
// becomes its new name, the names taken in the map's (sorted) order as upstream's std::map.
std::string renamed(std::string text, const std::map<std::string, std::string>& names) {
  for (const auto& [from, to] : names) {
    replace_all(&text, "\"" + from + "\"", "\"" + to + "\"");
    replace_all(&text, "'" + from + "'", "'" + to + "'");
    replace_all(&text, ">" + from + "<", ">" + to + "<");
  }
  return text;
}

std::string renamed_name(const std::string& name, const std::map<std::string, std::string>& names) {
  const auto it = names.find(name);
  return it == names.end() ? name : it->second;
}

}  // namespace

namespace detail {

bool flattened_in_gazebo11(const sdf::Model& nested) {
  const sdf::ElementPtr e = nested.Element();
  if (!e) return false;
  // an <include>: libsdformat 12 keeps the include element on the included model's element
  if (e->GetIncludeElement()) return true;
  // a name `a::b` of an SDF <= 1.7 file: libsdformat 12's 1.7 -> 1.8 converter made model `a` (a new XML element,
  // with no line of its own); every <model> written in a file has its line
  return !e->LineNumber() || *e->LineNumber() <= 0;
}

const FlatLink* FlatModel::link(const std::string& name) const {
  for (const auto& l : links)
    if (l.name == name) return &l;
  return nullptr;
}

FlatModel flatten_model(const sdf::Model& m) {
  FlatModel f;
  std::set<const void*> seen;
  auto add_link = [&](const sdf::Link* l) {
    if (!l || !seen.insert(l).second) return;
    ignition::math::Pose3d p;
    l->SemanticPose().Resolve(p);  // rule 4: in the model frame
    f.links.push_back({l->Name(), l, to_iso(p)});
    for (uint64_t k = 0; k < l->SensorCount(); ++k) {
      const sdf::Sensor* sn = l->SensorByIndex(k);
      f.sensors.push_back({sn, sn->Name(), l->Name(), l->Name(), sn->Element() ? sn->Element()->ToString("") : ""});
    }
  };
  auto add_joint = [&](const sdf::Joint* j) {
    if (j && seen.insert(j).second) f.joints.push_back({j->Name(), j, ""});
  };
  auto add_model = [&](const sdf::Model* n) {
    if (!n || !seen.insert(n).second) return;
    ignition::math::Pose3d np;
    n->SemanticPose().Resolve(np);  // N's frame in this model's frame
    const Eigen::Isometry3d T = to_iso(np);
    if (!flattened_in_gazebo11(*n)) {
      f.nested.push_back({n->Name(), n, T});
      return;
    }
    // sdformat 9's addNestedModel: N's links, joints, frames and models become ours as `N::name`, its text renamed
    const FlatModel sub = flatten_model(*n);
    const std::string pre = n->Name() + "::";
    std::map<std::string, std::string> names{{"__model__", pre + "__model__"}};
    for (const auto& l : sub.links) names[l.name] = pre + l.name;
    for (const auto& j : sub.joints) names[j.name] = pre + j.name;
    for (const auto& w : sub.nested) names[w.name] = pre + w.name;
    for (const auto& fr : sub.frames) names[fr] = pre + fr;
    for (const auto& l : sub.links) f.links.push_back({pre + l.name, l.link, T * l.pose});
    for (const auto& j : sub.joints) f.joints.push_back({pre + j.name, j.joint, pre + j.prefix});
    for (const auto& p : sub.plugins)
      f.plugins.push_back({renamed(p.xml, names), renamed_name(p.name, names), p.filename, p.line});
    for (const auto& sn : sub.sensors)
      f.sensors.push_back({sn.sensor, renamed_name(sn.name, names), pre + sn.link, sn.local_link,
                           renamed(sn.xml, names)});
    for (const auto& w : sub.nested) f.nested.push_back({pre + w.name, w.model, T * w.pose});
    for (const auto& fr : sub.frames) f.frames.push_back(pre + fr);
    f.frames.push_back(pre + "__model__");  // the frame addNestedModel injects
    if (!f.is_static) f.is_static = sub.is_static;
  };
  // the model's elements in document order (an included model sits where its <include> was)
  if (const sdf::ElementPtr me = m.Element())
    for (sdf::ElementPtr e = me->GetFirstElement(); e; e = e->GetNextElement()) {
      const std::string tag = e->GetName();
      const std::string name = e->HasAttribute("name") ? e->GetAttribute("name")->GetAsString() : "";
      if (tag == "link") {
        add_link(m.LinkByName(name));
      } else if (tag == "joint") {
        add_joint(m.JointByName(name));
      } else if (tag == "model") {
        add_model(m.ModelByName(name));
      } else if (tag == "frame") {
        f.frames.push_back(name);
      } else if (tag == "plugin") {
        const std::string file = e->HasAttribute("filename") ? e->GetAttribute("filename")->GetAsString() : "";
        f.plugins.push_back({e->ToString(""), name, file, line_of(e)});
      } else if (tag == "static") {
        if (!f.is_static) f.is_static = e->Get<bool>();
      }
    }
  // whatever the walk did not meet (a model without elements, built in code): in the DOM's order
  for (uint64_t i = 0; i < m.LinkCount(); ++i) add_link(m.LinkByIndex(i));
  for (uint64_t i = 0; i < m.JointCount(); ++i) add_joint(m.JointByIndex(i));
  for (uint64_t i = 0; i < m.ModelCount(); ++i) add_model(m.ModelByIndex(i));
  return f;
}

void warn_plugins_dropped(const FlatModel& f, const std::string& model, const std::string& why,
                          std::vector<Diagnostic>* diagnostics) {
  for (const auto& p : f.plugins)
    diagnostics->push_back({Severity::Warning, "plugin-not-loaded", "model[" + model + "]/plugin[" + p.name + "]",
                            "plug-in '" + p.name + "' (" + p.filename + ") of model '" + model +
                                "' is not loaded: " + why,
                            p.line});
  for (const auto& sn : f.sensors) {
    const sdf::ElementPtr se = sn.sensor->Element();
    if (!se || !se->HasElement("plugin")) continue;
    for (sdf::ElementPtr p = se->GetElement("plugin"); p; p = p->GetNextElement("plugin")) {
      const std::string name = p->HasAttribute("name") ? p->GetAttribute("name")->GetAsString() : "";
      const std::string file = p->HasAttribute("filename") ? p->GetAttribute("filename")->GetAsString() : "";
      diagnostics->push_back({Severity::Warning, "plugin-not-loaded",
                              "model[" + model + "]/link[" + sn.link + "]/sensor[" + sn.name + "]/plugin[" + name + "]",
                              "plug-in '" + name + "' (" + file + ") of sensor '" + sn.name + "' of model '" + model +
                                  "' is not loaded: " + why,
                              line_of(p)});
    }
  }
}

SdfRobot convert_sdf_model(const sdf::Model& sm, const std::string& source, const LoadOptions& options) {
  SdfRobot out;
  RobotModel& m = out.model;
  m.name = sm.Name();
  m.source = source;
  const std::string mwhere = "model[" + sm.Name() + "]";
  // rule 16a: the models it includes flattened into it, as Gazebo 11 loads them; a <model> written inside it is not
  const FlatModel f = flatten_model(sm);
  out.is_static = f.is_static.value_or(false);
  m.is_static = out.is_static;
  if (!f.nested.empty())
    throw LoadError(source, line_of(f.nested.front().model->Element()), mwhere + "/model[" + f.nested.front().name + "]",
                    "nested models are not simulated by car as one robot");
  if (f.links.empty()) throw LoadError(source, line_of(sm.Element()), mwhere, "the model has no <link>");

  for (const auto& fl : f.links) {
    m.links.push_back(convert_link(*fl.link, mwhere + "/link[" + fl.name + "]", &m));
    m.links.back().name = fl.name;
  }
  // a link's frame in the flattened model's frame
  auto pose_of = [&](const std::string& link) { return f.link(link)->pose; };

  // Joints: parent and child resolved through frames; the child's pose in the parent gives the joint origin.
  std::map<std::string, std::string> parent_of;
  bool world_parent = false;
  for (const auto& fj : f.joints) {
    const sdf::Joint* sj = fj.joint;
    const std::string where = mwhere + "/joint[" + fj.name + "]";
    const int line = line_of(sj->Element());
    const sdf::JointAxis* axis = sj->Axis(0);
    Joint j;
    j.name = fj.name;
    j.type = to_joint_type(*sj, axis, where, line, source);
    // the names in the joint's own model's scope, then in the flattened model's (`N::` before an included one's)
    std::string local_parent, local_child;
    if (!sj->ResolveParentLink(local_parent).empty() || local_parent.empty()) local_parent = sj->ParentLinkName();
    if (!sj->ResolveChildLink(local_child).empty() || local_child.empty()) local_child = sj->ChildLinkName();
    const std::string parent = local_parent == "world" ? local_parent : fj.prefix + local_parent;
    const std::string child = fj.prefix + local_child;
    if (local_child == "world" || !f.link(child))
      throw LoadError(source, line, where + "/child", "child '" + child + "' is not a link of the model");
    if (parent != "world" && !f.link(parent))
      throw LoadError(source, line, where + "/parent", "parent '" + parent + "' is not a link of the model");
    if (parent_of.count(child))
      throw LoadError(source, line, where, "link '" + child + "' already has the parent joint of link '" +
                                               parent_of[child] + "'; car simulates a tree of links");
    parent_of[child] = parent;
    j.parent = parent;
    j.child = child;
    world_parent = world_parent || parent == "world";
    // rule 4: child link frame in the parent link frame (the model frame for `world`); the DOM resolves it within
    // one model's scope, the flattened poses across scopes
    if (parent == "world") {
      j.origin = pose_of(child);
    } else if (local_parent.find("::") == std::string::npos && local_child.find("::") == std::string::npos) {
      // both links of the joint's own model: the child link's scope is the joint's
      ignition::math::Pose3d cp;
      refuse_errors(source, f.link(child)->link->SemanticPose().Resolve(cp, local_parent), nullptr);
      j.origin = to_iso(cp);
    } else {
      j.origin = pose_of(parent).inverse() * pose_of(child);
    }
    // rule 6: the joint frame in the child link; car's joint frame is the child's
    ignition::math::Pose3d jp;
    if (sj->SemanticPose().Resolve(jp, local_child).empty() && !to_iso(jp).isApprox(Eigen::Isometry3d::Identity(), 1e-9))
      m.diagnostics.push_back({Severity::Warning, "joint-pose", where + "/pose",
                               "the joint frame is offset from child link '" + child +
                                   "'; car turns the joint about the child link's origin",
                               line});
    if (j.type != JointType::Fixed && axis) {
      ignition::math::Vector3d xyz;
      if (!axis->ResolveXyz(xyz, local_child).empty()) xyz = axis->Xyz();
      j.axis_as_written = Eigen::Vector3d(axis->Xyz().X(), axis->Xyz().Y(), axis->Xyz().Z());
      const Eigen::Vector3d a(xyz.X(), xyz.Y(), xyz.Z());
      if (a.norm() < 1e-9)
        throw LoadError(source, line, where + "/axis/xyz", "axis has zero length; the joint needs a direction");
      j.axis = a.normalized();
      j.damping = axis->Damping();
      j.friction = axis->Friction();
      // rule 3: effort/velocity -1 = no limit (0 here, as urdfdom leaves an unwritten one)
      if (j.type != JointType::Continuous)
        j.limits = JointLimits{axis->Lower(), axis->Upper(), std::max(axis->Effort(), 0.0),
                               std::max(axis->MaxVelocity(), 0.0)};
      else if (axis->Effort() >= 0.0 || axis->MaxVelocity() >= 0.0)
        j.limits = JointLimits{0.0, 0.0, std::max(axis->Effort(), 0.0), std::max(axis->MaxVelocity(), 0.0)};
    }
    m.joints.push_back(j);
  }

  // Rule 7 and 12: one tree; a static model's parentless links hang from `world` on fixed joints.
  std::vector<std::string> roots;
  for (const auto& l : m.links)
    if (!parent_of.count(l.name)) roots.push_back(l.name);
  ignition::math::Pose3d mp = sm.RawPose();
  const Eigen::Isometry3d model_pose = to_iso(mp);
  if (out.is_static || world_parent) {
    for (const auto& r : roots) {
      if (!out.is_static) {
        throw LoadError(source, line_of(f.link(r)->link->Element()), mwhere + "/link[" + r + "]",
                        "link '" + r + "' is joined to neither `world` nor another link; car simulates one tree");
      }
      Joint j;
      j.name = "world_static_" + r;
      j.type = JointType::Fixed;
      j.parent = "world";
      j.child = r;
      j.origin = pose_of(r);
      j.anchor = true;
      m.joints.push_back(j);
    }
    Link world;
    world.name = "world";
    m.links.insert(m.links.begin(), world);
    m.root_link = "world";
    out.root_pose = model_pose;
  } else {
    if (roots.size() != 1) {
      const std::string extra = roots.size() > 1 ? roots[1] : m.links.front().name;
      // a forest of a flattened model (rule 16a) says where its links came from
      const bool included = roots.size() > 1 && (roots[0].find("::") != std::string::npos ||
                                                 roots[1].find("::") != std::string::npos);
      throw LoadError(source, line_of(sm.Element()), mwhere + "/link[" + extra + "]",
                      roots.size() > 1 ? "link '" + extra + "' is joined to no other link (a second free body); car "
                                                                "simulates one tree of links per model" +
                                             std::string(included ? " (an included model's links are the model's "
                                                                    "own, as Gazebo 11 flattens an <include>)"
                                                                  : "")
                                       : "the joints form a loop; car simulates a tree of links");
    }
    m.root_link = roots.front();
    m.root_in_model = pose_of(m.root_link);
    out.root_pose = model_pose * m.root_in_model;
  }

  read_plugins_and_sensors(f, source, mwhere, &m);

  detail::find_world_anchor(&m);
  if (options.throw_on_error)
    for (const auto& d : m.diagnostics)
      if (d.severity == Severity::Error) throw LoadError(source, d.line, d.element, d.message);
  return out;
}

}  // namespace detail

bool is_sdf_document(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) return false;
  return doc.RootElement() && std::string(doc.RootElement()->Name()) == "sdf";
}

namespace {

}  // namespace

SdfRobot load_sdf_model_string(const std::string& xml, const std::string& source_name, const LoadOptions& options,
                               const std::string& base_dir) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw LoadError(source_name, doc.ErrorLineNum(), "", std::string("malformed XML: ") + doc.ErrorName());
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "sdf")
    throw LoadError(source_name, root ? root->GetLineNum() : 0, root ? root->Name() : "",
                    "root element is not <sdf>; is this an SDF model?");
  detail::check_sdf_version(root, source_name);
  // every number finite and every sensor within its limits, in the text and each file it includes (validate.hpp)
  detail::prevalidate_sdf(xml, source_name, base_dir);
  sdf::Root sroot;
  bool rewritten = false;  // SDF 1.4's bare-text material scripts and Gazebo 11's pixel format names, read as Gazebo 11 did (validate.hpp)
  sdf::Errors errors;
  // libsdformat throws on some inputs (an included file's bad version: std::invalid_argument); refused, never escaped
  try {
    errors = sroot.LoadSdfString(detail::read_as_gazebo11(xml, &rewritten),
                                 parser_config(base_dir.empty() ? std::string() : base_dir + "/x.sdf"));
  } catch (const std::exception& e) {
    throw LoadError(source_name, 0, "sdf", std::string("libsdformat failed: ") + e.what());
  }
  std::vector<Diagnostic> warnings;
  refuse_errors(source_name, errors, &warnings);
  const sdf::Model* model = sroot.Model();
  Eigen::Isometry3d world_pose = Eigen::Isometry3d::Identity();
  if (!model && sroot.WorldCount() > 0) {
    const sdf::World* w = sroot.WorldByIndex(0);
    // nothing to spawn: an include that resolved nowhere says why (spawn_model -database)
    if (w->ModelCount() == 0)
      throw warnings.empty() ? LoadError(source_name, 0, "sdf/world", "the world holds no model to spawn")
                             : LoadError(source_name, warnings[0].line, warnings[0].element,
                                         warnings[0].message.substr(0, warnings[0].message.find(": left out")) +
                                             "; the world holds no model to spawn");
    model = w->ModelByIndex(0);
    ignition::math::Pose3d p;
    model->SemanticPose().Resolve(p);
    // convert_sdf_model composes the model's raw pose; an include's pose is in the world already
    world_pose = to_iso(p) * to_iso(model->RawPose()).inverse();
  }
  if (!model) throw LoadError(source_name, root->GetLineNum(), "sdf", "no <model> in the document");
  SdfRobot r = detail::convert_sdf_model(*model, source_name, options);
  r.model.diagnostics.insert(r.model.diagnostics.begin(), warnings.begin(), warnings.end());
  r.root_pose = world_pose * r.root_pose;
  return r;
}

}  // namespace car_sim
