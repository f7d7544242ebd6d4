// The URDF's <gazebo> extensions: link surface settings, robot-level plug-ins and link-level sensors,
// read the way Gazebo's URDF import reads them.
#include <tinyxml2.h>

#include <sstream>

#include "car_sim/model.hpp"
#include "xml_util.hpp"

namespace car_sim {

using detail::flatten;
using detail::parse_number;
using detail::text_of;
using detail::value_of;

namespace {

void note(RobotModel* m, Severity sev, const std::string& code, const std::string& element, const std::string& msg,
          int line) {
  m->diagnostics.push_back({sev, code, element, msg, line});
}

PluginSpec read_plugin(const tinyxml2::XMLElement* p) {
  PluginSpec spec;
  spec.name = p->Attribute("name") ? p->Attribute("name") : "";
  spec.filename = p->Attribute("filename") ? p->Attribute("filename") : "";
  spec.line = p->GetLineNum();
  flatten(p, "", &spec.params);
  return spec;
}

// A number in a <gazebo> block, from the `value` attribute or the text (value_of); a bad one is an error
// naming the element.
std::optional<double> number_in(RobotModel* m, const tinyxml2::XMLElement* e, const std::string& where) {
  const std::string t = value_of(e);
  const auto v = parse_number(t);
  if (!v) note(m, Severity::Error, "gazebo-value", where, "'" + t + "' is not a number", e->GetLineNum());
  return v;
}

// Three numbers in a <gazebo> block (e.g. fdir1 "1 0 0"); anything else is an error naming the element.
std::optional<Eigen::Vector3d> vector_in(RobotModel* m, const tinyxml2::XMLElement* e, const std::string& where) {
  std::istringstream in(value_of(e));
  Eigen::Vector3d v;
  std::string rest;
  if (in >> v.x() >> v.y() >> v.z() && !(in >> rest) && v.allFinite()) return v;
  note(m, Severity::Error, "gazebo-value", where, "'" + value_of(e) + "' is not three numbers", e->GetLineNum());
  return std::nullopt;
}

// A boolean as sdformat's URDF reader takes one: true/yes/1 (any case), and false/no/0.
std::optional<bool> flag_in(RobotModel* m, const tinyxml2::XMLElement* e, const std::string& where) {
  std::string t = value_of(e);
  for (auto& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "true" || t == "yes" || t == "1") return true;
  if (t == "false" || t == "no" || t == "0") return false;
  note(m, Severity::Error, "gazebo-value", where, "'" + value_of(e) + "' is not a boolean (true/false/yes/no/1/0)",
       e->GetLineNum());
  return std::nullopt;
}

void read_sensor(RobotModel* m, const tinyxml2::XMLElement* s, const std::string& link) {
  SensorSpec spec;
  spec.name = s->Attribute("name") ? s->Attribute("name") : "";
  spec.type = s->Attribute("type") ? s->Attribute("type") : "";
  spec.link = link;
  spec.line = s->GetLineNum();
  const std::string where = "gazebo[" + link + "]/sensor[" + spec.name + "]";
  for (auto* c = s->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "plugin") {
      spec.plugins.push_back(read_plugin(c));
    } else if (tag == "update_rate") {
      if (auto v = number_in(m, c, where + "/update_rate")) {
        if (*v < 0.0)
          note(m, Severity::Error, "sensor-value", where + "/update_rate", "update rate must be >= 0",
               c->GetLineNum());
        spec.update_rate = *v;
      }
    } else if (tag == "always_on") {
      if (auto v = flag_in(m, c, where + "/always_on")) spec.always_on = *v;
    } else if (tag == "visualize") {
      if (auto v = flag_in(m, c, where + "/visualize")) spec.visualize = *v;
    } else if (tag == "pose") {
      if (auto T = detail::parse_pose6(text_of(c)))
        spec.pose = *T;
      else
        note(m, Severity::Error, "sensor-value", where + "/pose", "pose '" + text_of(c) + "' is not 6 numbers",
             c->GetLineNum());
    } else if (c->FirstChildElement()) {
      // a named block (a multicamera's <camera name="left">) keeps its name, as "TAG/@name", before its keys
      if (c->Attribute("name")) spec.params.emplace_back(tag + "/@name", c->Attribute("name"));
      flatten(c, tag, &spec.params);
    } else {
      spec.params.emplace_back(tag, text_of(c));
    }
  }
  if (spec.name.empty())
    note(m, Severity::Error, "sensor-name", "gazebo[" + link + "]/sensor", "sensor has no name", spec.line);
  // Gazebo keeps one sensor per name on a link: the later definition replaces the earlier one.
  for (auto it = m->sensors.begin(); it != m->sensors.end(); ++it) {
    if (it->name == spec.name && it->link == link) {
      note(m, Severity::Warning, "sensor-duplicate", where,
           "sensor '" + spec.name + "' on link '" + link + "' is defined twice (lines " +
               std::to_string(it->line) + " and " + std::to_string(spec.line) + "); the later one is kept",
           spec.line);
      m->sensors.erase(it);
      break;
    }
  }
  m->sensors.push_back(std::move(spec));
}

void read_link_block(RobotModel* m, const tinyxml2::XMLElement* g, Link* link) {
  const std::string where = "gazebo[" + link->name + "]";
  auto& ext = link->gazebo;
  for (auto* c = g->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    const std::string here = where + "/" + tag;
    if (tag == "sensor") {
      read_sensor(m, c, link->name);
    } else if (tag == "plugin") {
      m->plugins.push_back(read_plugin(c));
    } else if (tag == "material") {
      ext.material = value_of(c);
    } else if (tag == "mu1") {
      ext.mu1 = number_in(m, c, here);
    } else if (tag == "mu2") {
      ext.mu2 = number_in(m, c, here);
    } else if (tag == "kp") {
      ext.kp = number_in(m, c, here);
    } else if (tag == "kd") {
      ext.kd = number_in(m, c, here);
    } else if (tag == "laserRetro") {
      ext.laser_retro = number_in(m, c, here);
    } else if (tag == "selfCollide") {
      ext.self_collide = flag_in(m, c, here);
    } else if (tag == "fdir1") {
      ext.fdir1 = vector_in(m, c, here);
    } else if (tag == "minDepth") {
      ext.min_depth = number_in(m, c, here);
    } else if (tag == "maxVel") {
      ext.max_vel = number_in(m, c, here);
    } else if (tag == "maxContacts") {
      if (auto v = number_in(m, c, here)) {
        if (*v < 0.0 || *v != static_cast<double>(static_cast<int>(*v)))
          note(m, Severity::Error, "gazebo-value", here, "maxContacts must be a non-negative integer", c->GetLineNum());
        else
          ext.max_contacts = static_cast<int>(*v);
      }
    } else if (tag == "gravity") {
      ext.gravity = flag_in(m, c, here);
    } else if (tag == "turnGravityOff") {
      ext.turn_gravity_off = flag_in(m, c, here);
    } else if (tag == "dampingFactor") {
      ext.damping_factor = number_in(m, c, here);
    } else if (c->FirstChildElement()) {
      flatten(c, tag, &ext.other);
    } else {
      ext.other.emplace_back(tag, value_of(c));
    }
  }
  for (const char* key : {"mu1", "mu2"}) {
    const auto& v = std::string(key) == "mu1" ? ext.mu1 : ext.mu2;
    if (v && *v < 0.0)
      note(m, Severity::Error, "gazebo-value", where + "/" + key, "friction coefficient must be >= 0", g->GetLineNum());
  }
  // [surface physics] values that must not be negative, and a stiffness that must be positive
  const std::pair<const char*, const std::optional<double>*> non_negative[] = {
      {"kd", &ext.kd}, {"minDepth", &ext.min_depth}, {"maxVel", &ext.max_vel}, {"dampingFactor", &ext.damping_factor}};
  for (const auto& [key, v] : non_negative)
    if (*v && **v < 0.0)
      note(m, Severity::Error, "gazebo-value", where + "/" + key, "must be >= 0", g->GetLineNum());
  if (ext.kp && !(*ext.kp > 0.0))
    note(m, Severity::Error, "gazebo-value", where + "/kp", "contact stiffness must be > 0", g->GetLineNum());
}

// <preserveFixedJoint> and the older <disableFixedJointLumping> in a joint's block keep a fixed joint from
// lumping (sdformat parser_urdf.cc; it turns the latter into a zero-range revolute joint, which moves the same).
void read_joint_lumping(RobotModel* m, const tinyxml2::XMLElement* g, const std::string& joint) {
  for (const char* key : {"preserveFixedJoint", "disableFixedJointLumping"})
    for (auto* c = g->FirstChildElement(key); c; c = c->NextSiblingElement(key))
      if (auto v = flag_in(m, c, "gazebo[" + joint + "]/" + key); v && *v) m->preserved_fixed_joints.insert(joint);
}

// A <gazebo> block without reference: sdformat copies its elements into the <model> as written (SDF names).
// Plug-ins; <self_collide> (the model's: links that set none take it, Gazebo's Link::Load); anything else is
// named in a note (<static> in a warning: car keeps the model dynamic).
void read_robot_block(RobotModel* m, const tinyxml2::XMLElement* g, std::optional<bool>* self_collide) {
  for (auto* c = g->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    const std::string here = "gazebo/" + tag;
    if (tag == "plugin") {
      m->plugins.push_back(read_plugin(c));
    } else if (tag == "self_collide") {
      if (auto v = flag_in(m, c, here); v && !*self_collide) *self_collide = v;
    } else if (tag == "static") {
      if (auto v = flag_in(m, c, here); v && *v)
        note(m, Severity::Warning, "gazebo-robot", here,
             "<static>true</static> is not simulated by car: the model stays dynamic (fix it to the link "
             "'world' with a fixed joint to anchor it)",
             c->GetLineNum());
    } else {
      note(m, Severity::Info, "gazebo-robot", here,
           "model-level <" + tag + "> is accepted and not simulated by car", c->GetLineNum());
    }
  }
}

}  // namespace

void parse_gazebo_extensions(const tinyxml2::XMLElement* robot, RobotModel* m) {
  std::optional<bool> self_collide;  // the model's <self_collide>, the first one written
  for (auto* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo")) {
    const char* ref = g->Attribute("reference");
    if (!ref || !*ref) {
      read_robot_block(m, g, &self_collide);
      continue;
    }
    const std::string name = ref;
    Link* link = nullptr;
    for (auto& l : m->links)
      if (l.name == name) link = &l;
    if (link) {
      read_link_block(m, g, link);
    } else if (m->find_joint(name)) {
      read_joint_lumping(m, g, name);
      note(m, Severity::Info, "gazebo-joint", "gazebo[" + name + "]",
           "settings on joint '" + name + "' are accepted and not simulated", g->GetLineNum());
    } else {
      note(m, Severity::Warning, "gazebo-reference", "gazebo[" + name + "]",
           "reference '" + name + "' names no link or joint; the block is ignored", g->GetLineNum());
    }
  }
  // the model's <self_collide> for each link that sets no <selfCollide> of its own
  if (self_collide)
    for (auto& l : m->links)
      if (!l.gazebo.self_collide) l.gazebo.self_collide = self_collide;
}

}  // namespace car_sim
