// SDF worlds through sdformat: models, links, collision and visual shapes with surface friction and
// materials, gravity, step size, the sun, and the <state> block's poses.
#include <sdf/sdf.hh>
#include <sdf/Scene.hh>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <tinyxml2.h>

#include "car_sim/description.hpp"
#include "car_sim/mesh.hpp"
#include "package_path.hpp"
#include "sdf_model.hpp"
#include "validate.hpp"
#include "xml_util.hpp"

namespace car_sim {

void parse_gazebo_extensions(const tinyxml2::XMLElement* robot, RobotModel* model);  // model/gazebo_ext.cpp

namespace {

using detail::refuse_errors;
using detail::line_of;
using detail::to_iso;

bool exists(const std::string& p) {
  struct stat st;
  return ::stat(p.c_str(), &st) == 0;
}

std::vector<std::string> split_path(const char* env) {
  std::vector<std::string> out;
  if (!env) return out;
  std::stringstream ss(env);
  std::string item;
  while (std::getline(ss, item, ':'))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string package_named(const std::string& name) {
  std::vector<std::string> roots = split_path(std::getenv("ROS_PACKAGE_PATH"));
  roots.push_back(detail::car_package_dir());  // car itself, also where no ROS environment is set up
  // rospack's crawl: nested packages (catkin_ws/src/REPO/PKG) are found too
  return detail::find_ros_package(name, roots);
}

SurfaceFriction read_friction(const sdf::Collision& c) {
  SurfaceFriction f;
  sdf::ElementPtr e = c.Element();
  for (const char* tag : {"surface", "friction", "ode"}) {
    if (!e || !e->HasElement(tag)) return f;
    e = e->GetElement(tag);
  }
  if (e->HasElement("mu")) f.mu = e->Get<double>("mu");
  if (e->HasElement("mu2")) f.mu2 = e->Get<double>("mu2");
  return f;
}


WorldLink read_link(const sdf::Link& l, const std::string& model, WorldDescription* desc) {
  WorldLink wl;
  wl.name = l.Name();
  ignition::math::Pose3d p;
  l.SemanticPose().Resolve(p);  // relative to the model frame
  wl.pose = to_iso(p);
  // <gravity>false</gravity>: SDF's per-link switch; the link feels no gravity (docs/COMPAT-sdf.md)
  if (l.Element() && l.Element()->HasElement("gravity")) wl.gravity = l.Element()->Get<bool>("gravity");
  // SDF's default when <inertial> is absent: 1 kg, unit inertia (docs/COMPAT-sdf.md 3); the DOM fills it in
  wl.inertial = detail::read_inertial(l);
  const std::string where = "model[" + model + "]/link[" + l.Name() + "]";
  for (uint64_t i = 0; i < l.CollisionCount(); ++i) {
    const sdf::Collision* c = l.CollisionByIndex(i);
    auto shape = detail::to_shape(*c->Geom(), where + "/collision[" + c->Name() + "]", line_of(c->Element()),
                                   &desc->diagnostics);
    if (!shape) continue;
    ignition::math::Pose3d cp;
    c->SemanticPose().Resolve(cp);  // relative to the link
    shape->origin = to_iso(cp);
    std::optional<double> retro;
    if (c->Element() && c->Element()->HasElement("laser_retro")) retro = c->Element()->Get<double>("laser_retro");
    wl.collisions.push_back({c->Name(), *shape, read_friction(*c), retro});
  }
  for (uint64_t i = 0; i < l.VisualCount(); ++i)
    if (auto wv = detail::read_visual(*l.VisualByIndex(i), where, &desc->diagnostics)) wl.visuals.push_back(std::move(*wv));
  return wl;
}

// Gazebo sets the world to its <state> when it loads: model poses there win over the models' own.
void apply_state(const sdf::World& w, WorldDescription* desc) {
  sdf::ElementPtr we = w.Element();
  if (!we || !we->HasElement("state")) return;
  for (sdf::ElementPtr st = we->GetElement("state"); st; st = st->GetNextElement("state")) {
    if (!st->HasElement("model")) continue;
    for (sdf::ElementPtr me = st->GetElement("model"); me; me = me->GetNextElement("model")) {
      const std::string name = me->Get<std::string>("name");
      if (!me->HasElement("pose")) continue;
      for (auto& m : desc->models)
        if (m.name == name) m.pose = to_iso(me->Get<ignition::math::Pose3d>("pose"));
      for (auto& r : desc->robots)
        if (r.name == name) {
          // the state's model pose replaces the model's own: undo the raw pose the robot's root_pose holds
          const sdf::Model* sm = w.ModelByName(name);
          r.pose = to_iso(me->Get<ignition::math::Pose3d>("pose")) * (sm ? to_iso(sm->RawPose()).inverse()
                                                                         : Eigen::Isometry3d::Identity());
        }
    }
  }
}

// A world model as Gazebo 11 loads it (docs/COMPAT-sdf.md 16 and 16a): the models it includes flattened into it;
// a robot when it then has a joint, a plug-in or a sensor and no <model> written inside it; else a world model,
// followed by its written nested models as models of their own, "parent::child", pose composed, static when the
// parent is (the world tools flatten nested models the same way). name: the model's name in the world; pose: its
// frame in the world; top: a model of the world itself (not a nested one).
void add_model(const sdf::Model& m, const std::string& name, const Eigen::Isometry3d& pose, bool parent_static,
               bool top, WorldDescription* d) {
  const detail::FlatModel flat = detail::flatten_model(m);
  if (top && flat.nested.empty() && flat.is_robot()) {
    WorldRobotDesc rd;
    rd.name = m.Name();
    rd.robot = detail::convert_sdf_model(m, d->source, LoadOptions());
    // convert_sdf_model composed the raw <pose> into root_pose; the resolved one replaces it
    rd.pose = pose * to_iso(m.RawPose()).inverse();
    d->robots.push_back(std::move(rd));
    return;
  }
  WorldModelDesc md;
  md.name = name;
  md.is_static = flat.is_static.value_or(false) || parent_static;
  md.pose = pose;
  for (const auto& fl : flat.links) {
    md.links.push_back(read_link(*fl.link, md.name, d));
    md.links.back().name = fl.name;
    md.links.back().pose = fl.pose;
  }
  // what only a robot simulates is left out with a warning, never silently
  const std::string why = top ? "car simulates a model with nested models as world bodies, not as a robot"
                              : "car simulates a nested model as world bodies, not as a robot";
  if (!flat.joints.empty())
    d->diagnostics.push_back({Severity::Warning, "nested-model-joints", "model[" + md.name + "]",
                              top ? "joints of a model with nested models are not simulated"
                                  : "joints of a nested model are not simulated",
                              0});
  detail::warn_plugins_dropped(flat, md.name, why, &d->diagnostics);
  const bool is_static = md.is_static;
  d->models.push_back(std::move(md));
  for (const auto& n : flat.nested) add_model(*n.model, name + "::" + n.name, pose * n.pose, is_static, false, d);
}

// The <plugin>s directly in <world> (Gazebo's World::LoadPlugins reads the same): through the URDF path's <gazebo>
// reader, as a model's plug-ins (sdf_model.cpp rule 10), so each keeps its elements flattened as every kind's do.
void read_world_plugins(const sdf::ElementPtr& we, const std::string& source, WorldDescription* d) {
  if (!we || !we->HasElement("plugin")) return;
  std::string xml = "<robot>";
  std::vector<int> lines;
  std::vector<std::string> texts;
  for (sdf::ElementPtr p = we->GetElement("plugin"); p; p = p->GetNextElement("plugin")) {
    texts.push_back(p->ToString(""));
    xml += "<gazebo>" + texts.back() + "</gazebo>";
    lines.push_back(line_of(p));
  }
  xml += "</robot>";
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw LoadError(source, 0, "world/plugin", std::string("cannot read the world's plug-ins: ") + doc.ErrorStr());
  RobotModel m;
  parse_gazebo_extensions(doc.RootElement(), &m);
  for (size_t i = 0; i < m.plugins.size(); ++i) {
    if (i < lines.size()) m.plugins[i].line = lines[i];
    if (i < texts.size()) m.plugins[i].xml = texts[i];
    d->plugins.push_back(m.plugins[i]);
  }
}

WorldDescription convert(const sdf::Root& root, const std::string& source) {
  const sdf::World* w = root.WorldCount() > 0 ? root.WorldByIndex(0) : nullptr;
  if (!w) throw LoadError(source, 0, "sdf", "no <world> in the file");
  WorldDescription d;
  d.source = source;
  d.name = w->Name();
  const auto g = w->Gravity();
  d.gravity = Eigen::Vector3d(g.X(), g.Y(), g.Z());
  if (w->PhysicsCount() > 0) {
    const sdf::Physics* ph = w->PhysicsDefault();
    d.step_size = ph->MaxStepSize();
    d.real_time_factor = ph->RealTimeFactor();
  }
  if (const sdf::Scene* sc = w->Scene()) {
    d.ambient = (sc->Ambient().R() + sc->Ambient().G() + sc->Ambient().B()) / 3.0;
    d.background = Eigen::Vector3d(sc->Background().R(), sc->Background().G(), sc->Background().B());
  }
  for (uint64_t i = 0; i < w->LightCount(); ++i) {
    const sdf::Light* l = w->LightByIndex(i);
    if (l->Type() != sdf::LightType::DIRECTIONAL) continue;
    ignition::math::Pose3d lp;
    l->SemanticPose().Resolve(lp);
    const auto dir = lp.Rot().RotateVector(l->Direction());
    if (dir.Length() > 0) d.sun_direction = Eigen::Vector3d(dir.X(), dir.Y(), dir.Z()).normalized();
    break;
  }
  for (uint64_t i = 0; i < w->ModelCount(); ++i) {
    const sdf::Model* m = w->ModelByIndex(i);
    ignition::math::Pose3d wp;
    m->SemanticPose().Resolve(wp);
    add_model(*m, m->Name(), to_iso(wp), false, true, &d);
  }
  read_world_plugins(w->Element(), source, &d);
  apply_state(*w, &d);
  detail::validate_world(&d);  // validate.cpp: step size, gravity, poses, masses, shape sizes
  for (const auto& m : d.models) {
    if (m.is_static) continue;
    for (const auto& l : m.links) {
      const std::string where = "model[" + m.name + "]/link[" + l.name + "]/inertial";
      if (!l.inertial || !(l.inertial->mass > 0.0))
        throw LoadError(source, 0, where, "a dynamic link needs a mass > 0");
    }
  }
  return d;
}

}  // namespace

std::vector<std::string> model_path() {
  std::vector<std::string> dirs = split_path(std::getenv("GAZEBO_MODEL_PATH"));
  dirs.push_back(detail::car_package_dir() + "/models");
  return dirs;
}

std::string resolve_uri(const std::string& uri) { return resolve_uri(uri, ""); }

std::string resolve_uri(const std::string& uri_text, const std::string& base_dir) {
  const std::string uri = detail::trim(uri_text);
  if (uri.rfind("model://", 0) == 0) {
    const std::string rest = uri.substr(8);
    const std::string name = rest.substr(0, rest.find('/'));
    const std::string tail = rest.size() > name.size() ? rest.substr(name.size()) : "";
    for (const auto& d : model_path())
      if (exists(d + "/" + name)) return d + "/" + name + tail;
    return "";
  }
  if (uri.rfind("package://", 0) == 0) {
    const std::string rest = uri.substr(10);
    const std::string pkg = rest.substr(0, rest.find('/'));
    const std::string root = package_named(pkg);
    return root.empty() ? "" : root + rest.substr(pkg.size());
  }
  std::string path = uri.rfind("file://", 0) == 0 ? uri.substr(7) : uri;
  if (!path.empty() && path[0] != '/' && !base_dir.empty())
    path = std::filesystem::path(base_dir + "/" + path).lexically_normal().string();
  return exists(path) ? path : "";
}

const WorldModelDesc* WorldDescription::find_model(const std::string& n) const {
  for (const auto& m : models)
    if (m.name == n) return &m;
  return nullptr;
}

// The include rule of car's world tools (python/car/world_tools.py), for sdformat. Relative paths resolve against
// the world file's folder. sdformat reads includes inside included models with its global configuration, so the
// rule is set there too.
sdf::ParserConfig parser_config(const std::string& world_file) {
  const std::string base = world_file.find('/') == std::string::npos ? "." : world_file.substr(0, world_file.rfind('/'));
  auto find = [base](const std::string& uri) { return resolve_uri(uri, base); };
  sdf::ParserConfig::GlobalConfig().SetFindCallback(find);
  sdf::setFindCallback(find);
  sdf::ParserConfig config;
  config.SetFindCallback(find);
  return config;
}

WorldDescription load_world_file(const std::string& path) {
  std::ifstream probe(path);
  if (!probe) throw LoadError(path, 0, "", "cannot open file");
  const std::string text(std::istreambuf_iterator<char>(probe), {});
  detail::prevalidate_sdf(text, path, path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/')));
  // SDF 1.4's bare-text material scripts and Gazebo 11's pixel format names, read as Gazebo 11 did (validate.hpp): then sdformat reads the rewritten
  // text (includes resolve as from the file; errors name the file)
  bool rewritten = false;
  const std::string gz11 = detail::read_as_gazebo11(text, &rewritten);
  sdf::Root root;
  sdf::Errors errors;
  // libsdformat throws on some inputs (an included file's bad version: std::invalid_argument); refused, never escaped
  try {
    errors = rewritten ? root.LoadSdfString(gz11, parser_config(path)) : root.Load(path, parser_config(path));
  } catch (const std::exception& e) {
    throw LoadError(path, 0, "sdf", std::string("libsdformat failed: ") + e.what());
  }
  std::vector<Diagnostic> warnings;
  refuse_errors(path, errors, &warnings);
  WorldDescription d = convert(root, path);
  d.diagnostics.insert(d.diagnostics.begin(), warnings.begin(), warnings.end());
  load_meshes(&d, path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/')));
  return d;
}

WorldDescription load_world_string(const std::string& xml, const std::string& source_name) {
  detail::prevalidate_sdf(xml, source_name, "");  // validate.cpp
  bool rewritten = false;
  sdf::Root root;
  sdf::Errors errors;
  try {
    errors = root.LoadSdfString(detail::read_as_gazebo11(xml, &rewritten), parser_config(""));
  } catch (const std::exception& e) {
    throw LoadError(source_name, 0, "sdf", std::string("libsdformat failed: ") + e.what());
  }
  std::vector<Diagnostic> warnings;
  refuse_errors(source_name, errors, &warnings);
  WorldDescription d = convert(root, source_name);
  d.diagnostics.insert(d.diagnostics.begin(), warnings.begin(), warnings.end());
  load_meshes(&d, "");
  return d;
}

WorldDescription empty_world() {
  return load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.7">
  <world name="default">
    <light name="sun" type="directional">
      <pose>0 0 10 0 0 0</pose>
      <direction>-0.5 0.1 -0.9</direction>
    </light>
    <model name="ground_plane">
      <static>true</static>
      <link name="link">
        <collision name="collision">
          <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
          <surface><friction><ode><mu>100</mu><mu2>50</mu2></ode></friction></surface>
        </collision>
        <visual name="visual">
          <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
          <material><script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Grey</name></script></material>
        </visual>
      </link>
    </model>
    <physics type="ode"><max_step_size>0.001</max_step_size><real_time_factor>1</real_time_factor></physics>
  </world>
</sdf>)",
                           "empty.world");
}

}  // namespace car_sim
