// The URDF's <gazebo> extensions: link surface settings, robot-level plug-ins and link-level sensors,
// read the way Gazebo's URDF import reads them.
#include <tinyxml2.h>

#include "car_sim/model.hpp"
#include "xml_util.hpp"

namespace car_sim {

using detail::flatten;
using detail::parse_number;
using detail::text_of;

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

// A number in a <gazebo> block; a bad one is an error naming the element.
std::optional<double> number_in(RobotModel* m, const tinyxml2::XMLElement* e, const std::string& where) {
  const auto v = parse_number(text_of(e));
  if (!v)
    note(m, Severity::Error, "gazebo-value", where, "'" + text_of(e) + "' is not a number", e->GetLineNum());
  return v;
}

std::optional<bool> flag_in(RobotModel* m, const tinyxml2::XMLElement* e, const std::string& where) {
  std::string t = text_of(e);
  for (auto& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "true" || t == "1") return true;
  if (t == "false" || t == "0") return false;
  note(m, Severity::Error, "gazebo-value", where, "'" + text_of(e) + "' is not a boolean (true/false/1/0)",
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
      ext.material = text_of(c);
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
    } else if (c->FirstChildElement()) {
      flatten(c, tag, &ext.other);
    } else {
      ext.other.emplace_back(tag, text_of(c));
    }
  }
  for (const char* key : {"mu1", "mu2"}) {
    const auto& v = std::string(key) == "mu1" ? ext.mu1 : ext.mu2;
    if (v && *v < 0.0)
      note(m, Severity::Error, "gazebo-value", where + "/" + key, "friction coefficient must be >= 0", g->GetLineNum());
  }
}

}  // namespace

void parse_gazebo_extensions(const tinyxml2::XMLElement* robot, RobotModel* m) {
  for (auto* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo")) {
    const char* ref = g->Attribute("reference");
    if (!ref || !*ref) {
      for (auto* p = g->FirstChildElement("plugin"); p; p = p->NextSiblingElement("plugin"))
        m->plugins.push_back(read_plugin(p));
      continue;
    }
    const std::string name = ref;
    Link* link = nullptr;
    for (auto& l : m->links)
      if (l.name == name) link = &l;
    if (link) {
      read_link_block(m, g, link);
    } else if (m->find_joint(name)) {
      note(m, Severity::Info, "gazebo-joint", "gazebo[" + name + "]",
           "settings on joint '" + name + "' are accepted and not simulated", g->GetLineNum());
    } else {
      note(m, Severity::Warning, "gazebo-reference", "gazebo[" + name + "]",
           "reference '" + name + "' names no link or joint; the block is ignored", g->GetLineNum());
    }
  }
}

}  // namespace car_sim
