// Limits and validation before allocation: the numbers of a URDF (before urdfdom) and of an SDF world (before
// and after sdformat). urdfdom reads an unparsable number as 0 or refuses the model with a console line about
// something else; sdformat says only "Error reading element"; so the reasons are found here, with the value as
// written.
#include "validate.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "geometry.hpp"
#include "xml_util.hpp"

namespace car_sim {
namespace detail {

// A DOCTYPE that declares entities: refused, so no entity is ever expanded (billion laughs) or fetched (external).
void refuse_entities(const tinyxml2::XMLDocument& doc, const std::string& source) {
  for (const tinyxml2::XMLNode* n = doc.FirstChild(); n; n = n->NextSibling()) {
    const tinyxml2::XMLUnknown* u = n->ToUnknown();
    if (!u || !u->Value()) continue;
    const std::string v = u->Value();
    if (v.find("ENTITY") != std::string::npos || v.find("SYSTEM") != std::string::npos)
      throw LoadError(source, u->GetLineNum(), "!DOCTYPE",
                      "DTD entity declarations are refused (car expands no entities and reads no external ones)");
  }
}

namespace {

std::string num(double v) { return short_number(v); }

// What car does with a degenerate shape (a warning, as Gazebo 11 loads it), by the element's kind.
std::string left_out(bool visual) {
  return visual ? "the visual is not drawn" : "the collision is left out of the collision world (the model is simulated)";
}

// One finite number: strtod over the whole text (an underflow to a denormal or 0 is fine, an overflow is not).
bool finite_number(const std::string& tok, double* out) {
  if (tok.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(tok.c_str(), &end);
  if (end != tok.c_str() + tok.size() || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

// The text of the element at path below e (nullptr when absent) and its value when it is a positive finite number.
const tinyxml2::XMLElement* child_at(const tinyxml2::XMLElement* e, const std::string& path) {
  std::istringstream parts(path);
  std::string part;
  while (e && std::getline(parts, part, '/')) e = e->FirstChildElement(part.c_str());
  return e;
}

bool positive_at(const tinyxml2::XMLElement* e, const std::string& path, double* out) {
  const tinyxml2::XMLElement* c = child_at(e, path);
  double v = 0;
  if (!c || !finite_number(trim(text_of(c)), &v) || !(v > 0)) return false;
  *out = v;
  return true;
}

// A product of limits as a whole number, below 1e15 (exact in a double and a long long); above, with 10 significant
// digits ("3.072e+26"), since a rate may be any finite number and the product need not fit a long long.
std::string whole(double v) {
  if (v < 1e15) return std::to_string(static_cast<long long>(v));
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

}  // namespace

void check_sensor_limits(const tinyxml2::XMLElement* sensor, const std::string& source) {
  const char* name = sensor->Attribute("name");
  const std::string where = std::string("sensor[") + (name ? name : "") + "]/";
  auto fail = [&](const std::string& key, const std::string& why) {
    throw LoadError(source, sensor->GetLineNum(), where + key, why);
  };
  double rate = 0;
  positive_at(sensor, "update_rate", &rate);
  // every <camera> (a multicamera has several; SDF defaults 320 x 240)
  for (const tinyxml2::XMLElement* cam = sensor->FirstChildElement("camera"); cam;
       cam = cam->NextSiblingElement("camera")) {
    double side[2] = {320, 240};
    const char* sides[2] = {"image/width", "image/height"};
    for (int i = 0; i < 2; ++i) {
      positive_at(cam, sides[i], &side[i]);
      const std::string key = std::string("camera/") + sides[i];
      if (side[i] > limits::kCameraSideMax)
        fail(key, key + " " + trim(text_of(child_at(cam, sides[i]))) + " is above the limit " +
                      limits::text(limits::kCameraSideMax, "px"));
    }
    const double px = side[0] * side[1];
    if (px > limits::kCameraPixelsMax)
      fail("camera/image/width", "width x height = " + whole(px) + " px is above the limit 4194304 px (2048 x 2048)");
    if (px * rate > limits::kCameraPixelsPerSecondMax)
      fail("update_rate", "width x height x update_rate = " + whole(px * rate) + " px/s is above the limit 1e9 px/s");
  }
  // <ray> (SDF 1.6, also in gpu_ray) or <lidar> (SDF 1.7+); SDF defaults 640 samples, resolution 1, one row
  for (const char* ray : {"ray", "lidar"}) {
    const tinyxml2::XMLElement* r = sensor->FirstChildElement(ray);
    if (!r) continue;
    double n[4] = {640, 1, 1, 1};
    const char* axes[4] = {"scan/horizontal/samples", "scan/horizontal/resolution", "scan/vertical/samples",
                           "scan/vertical/resolution"};
    for (int i = 0; i < 4; ++i) {
      positive_at(r, axes[i], &n[i]);
      const std::string key = std::string(ray) + "/" + axes[i];
      if (n[i] > limits::kRaySamplesMax)
        fail(key, key + " " + trim(text_of(child_at(r, axes[i]))) + " is above the limit " +
                      limits::text(limits::kRaySamplesMax, ""));
    }
    const double rays = n[0] * n[1] * std::max(1.0, n[2] * n[3]);
    if (rays > limits::kRaysPerScanMax)
      fail(std::string(ray) + "/scan/horizontal/resolution",
           "samples x resolution = " + whole(rays) + " rays per scan is above the limit 1000000");
    if (rays * rate > limits::kRaysPerSecondMax)
      fail("update_rate", "samples x resolution x update_rate = " + whole(rays * rate) +
                              " rays/s is above the limit 1e8 rays/s");
  }
}

namespace {

// The URDF pass: element paths and line numbers as the loader writes them.
class UrdfCheck {
 public:
  explicit UrdfCheck(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const tinyxml2::XMLElement* e, const std::string& where, const std::string& why) const {
    throw LoadError(source_, e->GetLineNum(), where, why);
  }

  void warn(const tinyxml2::XMLElement* e, const std::string& code, const std::string& where, const std::string& why) {
    warnings.push_back({Severity::Warning, code, where, why, e->GetLineNum()});
  }

  // An attribute of n numbers, all finite; nullopt-like false when absent (urdfdom's defaults apply).
  bool numbers(const tinyxml2::XMLElement* e, const char* attr, size_t n, const std::string& where,
               std::vector<double>* out, bool required = false) {
    const char* text = e->Attribute(attr);
    if (!text) {
      if (required) fail(e, where, std::string("has no '") + attr + "'");
      return false;
    }
    const auto toks = split_ws(text);
    out->clear();
    // a single value is named by its element when the attribute is "value" (<mass value>): "mass 'nan' ..."
    const std::string label = std::string(attr) == "value" ? e->Name() : attr;
    for (const auto& t : toks) {
      double v = 0;
      if (!finite_number(t, &v))
        fail(e, where, label + " '" + trim(text) + "'" + (toks.size() > 1 ? ": '" + t + "'" : "") +
                           " is not a finite number");
      out->push_back(v);
    }
    if (out->size() != n)
      fail(e, where, std::string(attr) + " '" + trim(text) + "' is not " + std::to_string(n) +
                         (n == 1 ? " number" : " numbers"));
    return true;
  }

  bool number(const tinyxml2::XMLElement* e, const char* attr, const std::string& where, double* out,
              bool required = false) {
    std::vector<double> v;
    if (!numbers(e, attr, 1, where, &v, required)) return false;
    *out = v[0];
    return true;
  }

  // <origin xyz rpy>: finite, positions within the length limit.
  void origin(const tinyxml2::XMLElement* parent, const std::string& where) {
    const tinyxml2::XMLElement* o = parent->FirstChildElement("origin");
    if (!o) return;
    const std::string here = where + "/origin";
    std::vector<double> v;
    if (numbers(o, "xyz", 3, here, &v)) {
      double far = 0.0;
      for (double x : v) far = std::max(far, std::abs(x));
      if (far > limits::kLengthRefuse)
        fail(o, here, "xyz '" + trim(o->Attribute("xyz")) + "' is beyond the limit " + num(limits::kLengthRefuse) +
                          " m (its square overflows the ray scene's single precision)");
      if (far > limits::kLengthMax)
        warn(o, "length-range", here, "xyz '" + trim(o->Attribute("xyz")) + "' is beyond " + num(limits::kLengthMax) +
                                          " m (positions that far lose precision in the ray scene's single precision)");
    }
    numbers(o, "rpy", 3, here, &v);
  }

  bool length(const tinyxml2::XMLElement* e, const char* attr, const std::string& where) {
    double v = 0;
    if (!number(e, attr, where, &v, true)) return true;
    return check_length(e, attr, v, where);
  }

  // A shape's length: <= 0 leaves the shape out (a warning, as Gazebo 11's BoxShape::SetSize and kin), beyond
  // kLengthMax a warning, beyond kLengthRefuse an error. Returns false once the shape has been warned about as
  // left out (one warning per shape).
  bool check_length(const tinyxml2::XMLElement* e, const std::string& what, double v, const std::string& where) {
    if (v > limits::kLengthRefuse)
      fail(e, where, what + " " + num(v) + " m is above the limit " + num(limits::kLengthRefuse) +
                         " m (its square overflows the ray scene's single precision)");
    if (!(v > 0.0)) {
      warn(e, "shape-size", where, what + " " + num(v) + " m is not > 0; " + left_out(where));
      return false;
    }
    if (v > limits::kLengthMax)
      warn(e, "length-range", where, what + " " + num(v) + " m is above " + num(limits::kLengthMax) +
                                         " m (the ray scene works in single precision)");
    return true;
  }

  // A URDF shape's kind from where it is: under <visual> or <collision>.
  static std::string left_out(const std::string& where) {
    return car_sim::detail::left_out(where.find("/visual[") != std::string::npos);
  }

  void geometry(const tinyxml2::XMLElement* shape_parent, const std::string& where) {
    const tinyxml2::XMLElement* g = shape_parent->FirstChildElement("geometry");
    if (!g) return;
    for (const tinyxml2::XMLElement* s = g->FirstChildElement(); s; s = s->NextSiblingElement()) {
      const std::string kind = s->Name();
      const std::string here = where + "/geometry/" + kind;
      if (kind == "box") {
        std::vector<double> v;
        numbers(s, "size", 3, here, &v, true);
        for (double x : v)
          if (!check_length(s, "size", x, here)) break;
      } else if (kind == "cylinder") {
        if (length(s, "radius", here)) length(s, "length", here);
      } else if (kind == "sphere") {
        length(s, "radius", here);
      } else if (kind == "mesh") {
        std::vector<double> v;
        if (numbers(s, "scale", 3, here, &v)) {
          double big = 0.0, small = 1.0;
          for (double x : v) big = std::max(big, std::abs(x)), small = std::min(small, std::abs(x));
          const std::string scale = "scale '" + trim(s->Attribute("scale")) + "'";
          if (big > limits::kLengthRefuse)
            fail(s, here, scale + " has a component beyond " + num(limits::kLengthRefuse));
          if (small == 0.0)
            warn(s, "shape-size", here, scale + " has a component 0; " + left_out(here));
          else if (big > limits::kLengthMax)
            warn(s, "length-range", here, scale + " has a component beyond " + num(limits::kLengthMax));
        }
      }
    }
  }

  void link(const tinyxml2::XMLElement* l) {
    const char* name = l->Attribute("name");
    const std::string where = std::string("link[") + (name ? name : "") + "]";
    if (const tinyxml2::XMLElement* in = l->FirstChildElement("inertial")) {
      const std::string here = where + "/inertial";
      origin(in, here);
      if (const tinyxml2::XMLElement* m = in->FirstChildElement("mass")) {
        double mass = 0;
        // mass <= 0 is the loader's error (inertial_problem); here: finite, and a warning outside the range
        if (number(m, "value", here + "/mass", &mass, true) && mass > 0.0 &&
            (mass < limits::kMassMin || mass > limits::kMassMax))
          warn(m, "mass-range", here + "/mass",
               "mass " + num(mass) + " kg is outside " + num(limits::kMassMin) + ".." + num(limits::kMassMax) +
                   " kg (a unit mistake? the solver loses accuracy at such masses)");
      }
      if (const tinyxml2::XMLElement* i = in->FirstChildElement("inertia")) {
        for (const char* a : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
          double v = 0;
          if (!number(i, a, here + "/inertia", &v)) continue;
          const bool diagonal = a[1] == a[2];
          if (diagonal && v > 0.0 && (v < limits::kInertiaMin || v > limits::kInertiaMax))
            warn(i, "inertia-range", here + "/inertia",
                 std::string(a) + " " + num(v) + " kg m^2 is outside " + num(limits::kInertiaMin) + ".." +
                     num(limits::kInertiaMax) + " kg m^2");
        }
      }
    }
    int k[2] = {0, 0};  // index of each collision, visual among its kind (when it has no name)
    for (const tinyxml2::XMLElement* c = l->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (tag != "collision" && tag != "visual") continue;
      const char* n = c->Attribute("name");
      const int i = k[tag == "visual"]++;
      const std::string here = where + "/" + tag + "[" + (n ? std::string(n) : std::to_string(i)) + "]";
      origin(c, here);
      geometry(c, here);
    }
  }

  void joint(const tinyxml2::XMLElement* j) {
    const char* name = j->Attribute("name");
    const std::string where = std::string("joint[") + (name ? name : "") + "]";
    origin(j, where);
    std::vector<double> v;
    double x = 0;
    if (const tinyxml2::XMLElement* a = j->FirstChildElement("axis")) numbers(a, "xyz", 3, where + "/axis", &v);
    if (const tinyxml2::XMLElement* l = j->FirstChildElement("limit")) {
      const std::string here = where + "/limit";
      number(l, "lower", here, &x);
      number(l, "upper", here, &x);
      for (const char* a : {"effort", "velocity"})
        if (number(l, a, here, &x) && x < 0.0)
          warn(l, "limit-negative", here, std::string(a) + " " + num(x) + " is negative; car does not use it");
    }
    if (const tinyxml2::XMLElement* d = j->FirstChildElement("dynamics")) {
      for (const char* a : {"damping", "friction"})
        if (number(d, a, where + "/dynamics", &x) && x < 0.0)
          fail(d, where + "/dynamics", std::string(a) + " " + num(x) + " is negative (it would feed energy in)");
    }
    if (const tinyxml2::XMLElement* c = j->FirstChildElement("calibration")) {
      number(c, "rising", where + "/calibration", &x);
      number(c, "falling", where + "/calibration", &x);
    }
    if (const tinyxml2::XMLElement* m = j->FirstChildElement("mimic")) {
      number(m, "multiplier", where + "/mimic", &x);
      number(m, "offset", where + "/mimic", &x);
    }
    if (const tinyxml2::XMLElement* s = j->FirstChildElement("safety_controller"))
      for (const char* a : {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"})
        number(s, a, where + "/safety_controller", &x);
  }

  std::vector<Diagnostic> warnings;

 private:
  std::string source_;
};

// ---- SDF ------------------------------------------------------------------------------------------------------

// Leaf elements whose text is numbers in every SDF version car reads.
const std::set<std::string>& sdf_numeric_tags() {
  static const std::set<std::string> tags = {
      "pose", "mass", "ixx", "ixy", "ixz", "iyy", "iyz", "izz", "size", "radius", "length", "scale", "normal",
      "gravity", "magnetic_field", "max_step_size", "real_time_factor", "real_time_update_rate", "mu", "mu2",
      "direction", "linear", "angular", "ambient", "background", "diffuse", "specular", "emissive"};
  return tags;
}

std::string sdf_path(const tinyxml2::XMLElement* e) {
  std::string p;
  for (; e; e = e->Parent() ? e->Parent()->ToElement() : nullptr) {
    const char* n = e->Attribute("name");
    p = std::string(e->Name()) + (n ? std::string("[") + n + "]" : "") + (p.empty() ? "" : "/" + p);
  }
  return p;
}

// Every numeric leaf finite. Iterative (a deep document cannot exhaust the stack).
void check_sdf_numbers(const tinyxml2::XMLElement* root, const std::string& source) {
  std::vector<const tinyxml2::XMLElement*> todo = {root};
  while (!todo.empty()) {
    const tinyxml2::XMLElement* e = todo.back();
    todo.pop_back();
    for (const tinyxml2::XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement()) todo.push_back(c);
    if (std::string(e->Name()) == "sensor") check_sensor_limits(e, source);
    if (e->FirstChildElement() || !sdf_numeric_tags().count(e->Name())) continue;
    // <link><gravity> is SDF's per-link gravity switch, a boolean (sdformat reads it); the world's is a vector
    const tinyxml2::XMLElement* parent = e->Parent() ? e->Parent()->ToElement() : nullptr;
    if (std::string(e->Name()) == "gravity" && parent && std::string(parent->Name()) == "link") continue;
    const std::string text = text_of(e);
    const auto toks = split_ws(text);
    for (const auto& t : toks) {
      double v = 0;
      if (!finite_number(t, &v))
        throw LoadError(source, e->GetLineNum(), sdf_path(e),
                        std::string(e->Name()) + " '" + text + "'" + (toks.size() > 1 ? ": '" + t + "'" : "") +
                            " is not a finite number");
    }
  }
}

void parse_sdf(const std::string& xml, const std::string& source, tinyxml2::XMLDocument* doc) {
  if (doc->Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    throw LoadError(source, doc->ErrorLineNum(), "", std::string("malformed XML: ") + doc->ErrorStr());
  refuse_entities(*doc, source);
  if (!doc->RootElement() || std::string(doc->RootElement()->Name()) != "sdf")
    throw LoadError(source, doc->RootElement() ? doc->RootElement()->GetLineNum() : 0,
                    doc->RootElement() ? doc->RootElement()->Name() : "", "root element is not <sdf>");
}

void read_file(const std::string& path, std::string* out) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  *out = ss.str();
}

// Every <include> below e: found, checked, no cycle (chain: the files including this one).
void check_includes(const tinyxml2::XMLElement* root, const std::string& source, const std::string& base_dir,
                    std::vector<std::string>* chain, std::set<std::string>* done) {
  std::vector<const tinyxml2::XMLElement*> todo = {root};
  while (!todo.empty()) {
    const tinyxml2::XMLElement* e = todo.back();
    todo.pop_back();
    for (const tinyxml2::XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement()) todo.push_back(c);
    if (std::string(e->Name()) != "include") continue;
    // one that names nothing, resolves nowhere, or names a folder without a model.config is left to sdformat,
    // which reports it and goes on without it, as Gazebo 11 does (a warning: refuse_errors)
    const std::string uri = text_of(e->FirstChildElement("uri"));
    const std::string found = uri.empty() ? "" : resolve_uri(uri, base_dir);
    if (found.empty()) continue;
    std::error_code ec;
    std::string file = found;
    if (std::filesystem::is_directory(found, ec)) try {
        file = model_sdf_file(found);
      } catch (const LoadError&) {
        file.clear();
      }
    if (file.empty()) continue;
    const std::string canon = std::filesystem::weakly_canonical(file, ec).string();
    for (const auto& f : *chain)
      if (f == canon) {
        std::string loop;
        for (const auto& g : *chain) loop += g + " -> ";
        throw LoadError(source, e->GetLineNum(), sdf_path(e) + "/uri", "include loop: " + loop + canon);
      }
    if (static_cast<int>(chain->size()) > limits::kIncludeDepthMax)
      throw LoadError(source, e->GetLineNum(), sdf_path(e) + "/uri",
                      "includes nest deeper than " + std::to_string(limits::kIncludeDepthMax) + " levels");
    if (done->count(canon)) continue;
    std::string xml;
    read_file(file, &xml);
    tinyxml2::XMLDocument doc;
    parse_sdf(xml, file, &doc);
    check_sdf_numbers(doc.RootElement(), file);
    chain->push_back(canon);
    // sdformat resolves an included model's own includes against the world's folder, so they do here too
    check_includes(doc.RootElement(), file, base_dir, chain, done);
    chain->pop_back();
    done->insert(canon);
  }
}

// ---- converted worlds -----------------------------------------------------------------------------------------

[[noreturn]] void world_fail(const WorldDescription& d, const std::string& where, const std::string& why) {
  throw LoadError(d.source, 0, where, why);
}

void world_warn(WorldDescription* d, const std::string& code, const std::string& where, const std::string& why) {
  d->diagnostics.push_back({Severity::Warning, code, where, why, 0});
}

void check_pose(WorldDescription* d, const Eigen::Isometry3d& T, const std::string& where) {
  if (!T.matrix().allFinite()) world_fail(*d, where, "pose is not finite");
  const double far = T.translation().cwiseAbs().maxCoeff();
  const std::string p = "position (" + num(T.translation().x()) + " " + num(T.translation().y()) + " " +
                        num(T.translation().z()) + ") m";
  if (far > limits::kLengthRefuse)
    world_fail(*d, where, p + " is beyond the limit " + num(limits::kLengthRefuse) +
                              " m (its square overflows the ray scene's single precision)");
  if (far > limits::kLengthMax)
    world_warn(d, "length-range", where, p + " is beyond " + num(limits::kLengthMax) +
                                             " m (the ray scene works in single precision)");
}

// A world shape: false when it is degenerate (warned about; the caller leaves a collision out).
bool check_shape(WorldDescription* d, const Shape& s, const std::string& where, bool visual) {
  check_pose(d, s.origin, where + "/pose");
  bool ok = true;
  auto len = [&](const char* what, double v) {
    if (!ok) return;
    if (!std::isfinite(v) || v > limits::kLengthRefuse)
      world_fail(*d, where, std::string(what) + " " + num(v) + " m is above the limit " + num(limits::kLengthRefuse) +
                                " m (its square overflows the ray scene's single precision)");
    if (!(v > 0.0)) {
      ok = false;
      world_warn(d, "shape-size", where,
                 std::string(what) + " " + num(v) + " m is not > 0; " + left_out(visual));
    } else if (v > limits::kLengthMax) {
      world_warn(d, "length-range", where, std::string(what) + " " + num(v) + " m is above " +
                                               num(limits::kLengthMax) + " m (the ray scene works in single precision)");
    }
  };
  switch (s.type) {
    case ShapeType::Box:
      for (int i = 0; i < 3; ++i) len("size", s.size(i));
      break;
    case ShapeType::Cylinder:
      len("radius", s.radius);
      len("length", s.length);
      break;
    case ShapeType::Sphere:
      len("radius", s.radius);
      break;
    case ShapeType::Plane:
      if (!s.normal.allFinite() || s.normal.norm() < 1e-9) world_fail(*d, where, "plane normal is zero or not finite");
      break;
    case ShapeType::Mesh:
      if (!s.mesh_scale.allFinite()) world_fail(*d, where, "mesh scale is not finite");
      if (s.mesh_scale.cwiseAbs().minCoeff() == 0.0) {
        ok = false;
        world_warn(d, "shape-size", where,
                   std::string("mesh scale has a component 0; ") + left_out(visual));
      }
      break;
  }
  return ok;
}

}  // namespace

std::string rewrite_bare_scripts(const std::string& xml, bool* changed) {
  static const std::string open = "<script>", close = "</script>";
  *changed = false;
  std::string out;
  size_t from = 0;
  for (size_t at = xml.find(open); at != std::string::npos; at = xml.find(open, from)) {
    const size_t text = at + open.size();
    const size_t lt = xml.find('<', text);
    // only text (no child element, no comment) up to </script>, and some of it not blank
    if (lt == std::string::npos || xml.compare(lt, close.size(), close) != 0 ||
        trim(xml.substr(text, lt - text)).empty()) {
      out.append(xml, from, text - from);
      from = text;
      continue;
    }
    out.append(xml, from, text - from);
    out += "<uri>file://media/materials/scripts/gazebo.material</uri><name>" + xml.substr(text, lt - text) + "</name>";
    from = lt;
    *changed = true;
  }
  out.append(xml, from, std::string::npos);
  return out;
}

std::string rewrite_pixel_formats(const std::string& xml, bool* changed) {
  // Gazebo 11's names that libsdformat 12's camera does not list, and the name it lists for the same format
  static const std::pair<const char*, const char*> kRenamed[] = {{"R16G16B16", "RGB_INT16"}};
  static const std::string open = "<format>", close = "</format>";
  *changed = false;
  std::string out;
  size_t from = 0;
  for (size_t at = xml.find(open); at != std::string::npos; at = xml.find(open, from)) {
    const size_t text = at + open.size();
    const size_t end = xml.find(close, text);
    out.append(xml, from, text - from);
    from = text;
    if (end == std::string::npos) continue;
    const std::string name = trim(xml.substr(text, end - text));
    for (const auto& [gz11, sdf12] : kRenamed) {
      if (name != gz11) continue;
      out += sdf12;
      from = end;
      *changed = true;
    }
  }
  out.append(xml, from, std::string::npos);
  return out;
}

std::string read_as_gazebo11(const std::string& xml, bool* changed) {
  bool scripts = false, formats = false;
  std::string out = rewrite_pixel_formats(rewrite_bare_scripts(xml, &scripts), &formats);
  *changed = scripts || formats;
  return out;
}

bool degenerate_shape(const Shape& s) {
  switch (s.type) {
    case ShapeType::Box: return !(s.size.minCoeff() > 0.0);
    case ShapeType::Cylinder: return !(s.radius > 0.0) || !(s.length > 0.0);
    case ShapeType::Sphere: return !(s.radius > 0.0);
    case ShapeType::Mesh: return s.mesh_scale.cwiseAbs().minCoeff() == 0.0;
    case ShapeType::Plane: return false;
  }
  return false;
}

void drop_degenerate_collisions(RobotModel* m) {
  for (auto& l : m->links)
    l.collisions.erase(std::remove_if(l.collisions.begin(), l.collisions.end(), degenerate_shape), l.collisions.end());
}

std::vector<Diagnostic> validate_urdf(const tinyxml2::XMLDocument& doc, const std::string& source) {
  refuse_entities(doc, source);
  UrdfCheck check(source);
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (!robot) return {};
  for (const tinyxml2::XMLElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "link") check.link(e);
    if (tag == "joint") check.joint(e);
    if (tag == "gazebo")
      for (auto* s = e->FirstChildElement("sensor"); s; s = s->NextSiblingElement("sensor"))
        check_sensor_limits(s, source);
  }
  return check.warnings;
}

std::string model_sdf_file(const std::string& folder) {
  const std::string config = folder + "/model.config";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(config, ec))
    throw LoadError(folder, 0, "model.config", "a model folder needs a model.config");
  tinyxml2::XMLDocument cfg;
  if (cfg.LoadFile(config.c_str()) != tinyxml2::XML_SUCCESS || !cfg.RootElement())
    throw LoadError(config, cfg.ErrorLineNum(), "", std::string("malformed XML: ") + cfg.ErrorStr());
  std::string best;
  double best_v = -1;
  for (auto* s = cfg.RootElement()->FirstChildElement("sdf"); s; s = s->NextSiblingElement("sdf")) {
    double v = 0;
    if (!finite_number(s->Attribute("version") ? s->Attribute("version") : "0", &v)) v = 0;
    if (v <= 1.9 && v > best_v && !text_of(s).empty()) best = text_of(s), best_v = v;
  }
  if (best.empty()) throw LoadError(config, 0, "model/sdf", "names no SDF file");
  return folder + "/" + best;
}

void check_sdf_version(const tinyxml2::XMLElement* root, const std::string& source) {
  const char* v = root ? root->Attribute("version") : nullptr;
  if (!v) return;
  const std::string t = v;
  bool ok = !t.empty() && t.front() != '.' && t.back() != '.';
  for (size_t i = 0; ok && i < t.size(); ++i)
    ok = std::isdigit(static_cast<unsigned char>(t[i])) || (t[i] == '.' && t[i + 1] != '.');
  if (!ok) throw LoadError(source, root->GetLineNum(), "sdf", "version '" + t + "' is not an SDF version (such as 1.6)");
}

void prevalidate_sdf(const std::string& xml, const std::string& source, const std::string& base_dir) {
  tinyxml2::XMLDocument doc;
  parse_sdf(xml, source, &doc);
  check_sdf_version(doc.RootElement(), source);
  check_sdf_numbers(doc.RootElement(), source);
  for (auto* w = doc.RootElement()->FirstChildElement("world"); w; w = w->NextSiblingElement("world")) {
    int n = 0;
    for (auto* c = w->FirstChildElement(); c; c = c->NextSiblingElement())
      n += std::string(c->Name()) == "model" || std::string(c->Name()) == "include";
    if (n > limits::kWorldModelsMax)
      throw LoadError(source, w->GetLineNum(), "world[" + std::string(w->Attribute("name") ? w->Attribute("name") : "") + "]",
                      std::to_string(n) + " models is above the limit " + std::to_string(limits::kWorldModelsMax) +
                          " (libsdformat needs about 2.5 MB and 15 ms per model to parse a world)");
  }
  std::error_code ec;
  std::vector<std::string> chain;
  if (source.find('<') == std::string::npos && std::filesystem::exists(source, ec))
    chain.push_back(std::filesystem::weakly_canonical(source, ec).string());
  std::set<std::string> done;
  check_includes(doc.RootElement(), source, base_dir, &chain, &done);
}

std::string pose_problem(const std::string& text, std::vector<double>* values) {
  const std::string t = trim(text);
  const auto toks = split_ws(t);
  std::vector<double> v;
  for (const auto& tok : toks) {
    char* end = nullptr;
    const double x = std::strtod(tok.c_str(), &end);
    // a decimal as Python's float() reads it: strtod's hexadecimal is not one
    if (end != tok.c_str() + tok.size() || tok.find_first_of("xX") != std::string::npos) {
      v.clear();
      break;
    }
    v.push_back(x);
  }
  if (!toks.empty() && v.size() != 6) return "pose '" + t + "' is not 6 numbers (x y z roll pitch yaw)";
  for (double x : v)
    if (!std::isfinite(x)) return "pose '" + t + "' has a non-finite value";
  if (values) *values = v;
  return "";
}

const std::vector<std::string>& sdf_geometry_elements() {
  static const std::vector<std::string> kNames = {"box",     "capsule", "cylinder", "ellipsoid", "empty",  "heightmap",
                                                  "image",   "mesh",    "plane",    "polyline",  "sphere"};
  return kNames;
}

namespace {

// world_tool check's walk (check_world_xml): the children of e, each <pose> and <geometry> where it stands, every
// other element's subtree right after it (document order). Recursive: tinyxml2 reads no document nested deeper
// than TINYXML2_MAX_ELEMENT_DEPTH, so the depth is bounded.
void check_world_children(const tinyxml2::XMLElement* e, const std::string& path, std::vector<Diagnostic>* out) {
  auto listed = [](const std::vector<std::string>& names, const std::string& n) {
    return std::find(names.begin(), names.end(), n) != names.end();
  };
  for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    const char* name = c->Attribute("name");
    const std::string here = path + "/" + (name && *name ? tag + "[" + name + "]" : tag);
    if (tag == "pose") {
      if (const std::string why = pose_problem(text_of(c), nullptr); !why.empty())
        out->push_back({Severity::Error, "pose-malformed", here, why, 0});
    } else if (tag == "geometry") {
      if (!c->FirstChildElement()) out->push_back({Severity::Error, "geometry-empty", here, "<geometry> holds no shape", 0});
      for (const tinyxml2::XMLElement* g = c->FirstChildElement(); g; g = g->NextSiblingElement()) {
        const std::string shape = g->Name();
        if (!listed(sdf_geometry_elements(), shape)) {
          std::string known;
          for (const auto& n : sdf_geometry_elements()) known += (known.empty() ? "" : ", ") + n;
          out->push_back({Severity::Error, "geometry-unknown", here + "/" + shape,
                          "unknown geometry <" + shape + "> (SDF knows " + known + ")", 0});
        } else if (shape == "mesh" && text_of(g->FirstChildElement("uri")).empty()) {
          out->push_back({Severity::Error, "uri-missing", here + "/mesh", "<mesh> has no <uri>", 0});
        } else if (!listed(simulated_geometry(), shape)) {
          out->push_back({Severity::Warning, "geometry-unsimulated", here + "/" + shape,
                          "<" + shape + "> is not simulated by car; ignored", 0});
        }
      }
    } else if (tag != "state" && tag != "gui" && tag != "plugin") {
      check_world_children(c, here, out);
    }
  }
}

}  // namespace

std::vector<Diagnostic> check_world_xml(const tinyxml2::XMLElement* world) {
  std::vector<Diagnostic> out;
  if (!world) return out;
  const char* name = world->Attribute("name");
  check_world_children(world, std::string("world[") + (name ? name : "None") + "]", &out);
  return out;
}

void validate_world(WorldDescription* d) {
  if (!(d->step_size > 0.0) || !std::isfinite(d->step_size))
    world_fail(*d, "world/physics/max_step_size", "step size " + num(d->step_size) + " s is not finite and > 0");
  if (!d->gravity.allFinite()) world_fail(*d, "world/gravity", "gravity is not finite");
  if (!(d->real_time_factor >= 0.0) || !std::isfinite(d->real_time_factor))
    world_fail(*d, "world/physics/real_time_factor",
               "real-time factor " + num(d->real_time_factor) + " is not finite and >= 0");
  for (auto& m : d->models) {
    const std::string mw = "model[" + m.name + "]";
    check_pose(d, m.pose, mw + "/pose");
    for (auto& l : m.links) {
      const std::string lw = mw + "/link[" + l.name + "]";
      check_pose(d, l.pose, lw + "/pose");
      std::vector<WorldCollision> kept;
      for (const auto& c : l.collisions)
        if (check_shape(d, c.shape, lw + "/collision[" + c.name + "]", false)) kept.push_back(c);
      l.collisions = std::move(kept);
      for (const auto& v : l.visuals) check_shape(d, v.shape, lw + "/visual[" + v.name + "]", true);
      if (!l.inertial) continue;
      const Inertial& in = *l.inertial;
      check_pose(d, in.origin, lw + "/inertial/pose");
      if (!std::isfinite(in.mass)) world_fail(*d, lw + "/inertial/mass", "mass " + num(in.mass) + " kg is not finite");
      if (!in.inertia.allFinite()) world_fail(*d, lw + "/inertial/inertia", "inertia is not finite");
      if (m.is_static) continue;
      std::string code;
      if (const std::string why = in.mass > 0.0 ? inertial_warning(in.inertia, &code) : ""; !why.empty())
        world_warn(d, code, lw + "/inertial/inertia", why);
      if (in.mass > 0.0 && (in.mass < limits::kMassMin || in.mass > limits::kMassMax))
        d->diagnostics.push_back({Severity::Warning, "mass-range", lw + "/inertial/mass",
                                  "mass " + num(in.mass) + " kg is outside " + num(limits::kMassMin) + ".." +
                                      num(limits::kMassMax) + " kg",
                                  0});
    }
  }
}

}  // namespace detail

std::string limits::text(double v, const char* unit) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str() + (*unit ? std::string(" ") + unit : "");
}

}  // namespace car_sim
