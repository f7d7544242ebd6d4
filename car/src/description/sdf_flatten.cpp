// One self-contained world document (world_tool flatten, check, map and plot: docs/TOOLS.md): includes expanded,
// nested models hoisted, <state> applied. The include rule (resolve_uri, model.config, the depth limit) is the
// loader's; python/car/world_tools.py reads the text this returns and writes it out.
#include <tinyxml2.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <filesystem>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "validate.hpp"
#include "xml_util.hpp"

namespace car_sim {

namespace {

// An attribute as Python's str(elem.get(name)) writes it ("None" when absent): the element paths of errors.
std::string attr(const tinyxml2::XMLElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v ? v : "None";
}

std::string folder_of(const std::string& file) {
  // os.path.dirname
  const auto slash = file.rfind('/');
  return slash == std::string::npos ? "" : slash == 0 ? "/" : file.substr(0, slash);
}

// os.path.abspath: the path against the working folder, '.', '..' and repeated '/' removed, no trailing '/'.
std::string abspath(const std::string& p) {
  std::error_code ec;
  const std::string full = (!p.empty() && p[0] == '/') ? p : std::filesystem::current_path(ec).string() + "/" + p;
  std::vector<std::string> parts;
  size_t from = 0;
  while (from <= full.size()) {
    const size_t to = std::min(full.find('/', from), full.size());
    const std::string part = full.substr(from, to - from);
    if (part == "..") {
      if (!parts.empty()) parts.pop_back();
    } else if (!part.empty() && part != ".") {
      parts.push_back(part);
    }
    from = to + 1;
  }
  std::string out;
  for (const auto& part : parts) out += "/" + part;
  return out.empty() ? "/" : out;
}

// Reads an SDF file into doc (no DTD entities, as the loader). tinyxml2 refuses documents nested deeper than its
// TINYXML2_MAX_ELEMENT_DEPTH.
void read_sdf(const std::string& file, tinyxml2::XMLDocument* doc) {
  const tinyxml2::XMLError err = doc->LoadFile(file.c_str());
  if (err == tinyxml2::XML_ERROR_FILE_NOT_FOUND) throw LoadError(file, 0, "", "no such file");
  if (err == tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED)
    throw LoadError(file, doc->ErrorLineNum(), "",
                    "elements nest too deep to read (more than " +
                        std::to_string(TINYXML2_MAX_ELEMENT_DEPTH) + " levels)");
  if (err != tinyxml2::XML_SUCCESS)
    throw LoadError(file, doc->ErrorLineNum(), "", std::string("malformed XML: ") + doc->ErrorStr());
  detail::refuse_entities(*doc, file);
}

// A pose 'x y z roll pitch yaw' as a 4x4 transform (blank: identity); throws at element when it is not 6 finite
// numbers (detail::pose_problem, the rule world_tool check holds every <pose> to).
Eigen::Matrix4d parse_pose(const std::string& text, const std::string& file, const std::string& element) {
  std::vector<double> v;
  if (const std::string why = detail::pose_problem(text, &v); !why.empty()) throw LoadError(file, 0, element, why);
  if (v.empty()) return Eigen::Matrix4d::Identity();
  const double cr = std::cos(v[3]), sr = std::sin(v[3]), cp = std::cos(v[4]), sp = std::sin(v[4]),
               cy = std::cos(v[5]), sy = std::sin(v[5]);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 3>(0, 0) << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,                     //
      -sp, cp * sr, cp * cr;
  T.block<3, 1>(0, 3) << v[0], v[1], v[2];
  return T;
}

// A number as Python's repr(float('%.12g' % v)) writes it; 0 as "0".
std::string format_number(double v) {
  if (v == 0.0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.12g", v);
  std::string s = buf;
  if (!std::isfinite(v)) return s;
  const auto e = s.find('e');
  if (e != std::string::npos) {
    const int exp = std::atoi(s.c_str() + e + 1);
    if (exp < 16 && exp >= 12) {  // repr writes these in full; with 12 digits they are whole numbers
      std::snprintf(buf, sizeof(buf), "%.0f", std::strtod(s.c_str(), nullptr));
      return std::string(buf) + ".0";
    }
    return s;
  }
  return s.find('.') == std::string::npos ? s + ".0" : s;
}

// 'x y z roll pitch yaw' of a transform.
std::string format_pose(const Eigen::Matrix4d& T) {
  const double pitch = std::asin(std::max(-1.0, std::min(1.0, -T(2, 0))));
  const double roll = std::atan2(T(2, 1), T(2, 2)), yaw = std::atan2(T(1, 0), T(0, 0));
  const double vals[6] = {T(0, 3), T(1, 3), T(2, 3), roll, pitch, yaw};
  std::string out;
  for (double v : vals) out += (out.empty() ? "" : " ") + format_number(v);
  return out;
}

// A child's text, as Python's findtext: nullopt when there is no such child, "" when it has no text.
std::optional<std::string> find_text(const tinyxml2::XMLElement* e, const char* tag) {
  const tinyxml2::XMLElement* c = e->FirstChildElement(tag);
  if (!c) return std::nullopt;
  return std::string(c->GetText() ? c->GetText() : "");
}

void set_child(tinyxml2::XMLElement* e, const char* tag, const std::string& text) {
  tinyxml2::XMLElement* c = e->FirstChildElement(tag);
  if (!c) c = e->InsertNewChildElement(tag);
  c->SetText(text.c_str());
}

class Flattener {
 public:
  // flatten_includes: a model included inside a model is flattened into it (a document of SDF <= 1.7, which
  // Gazebo 11 reads; libsdformat 12 refuses the `N::name` names in 1.8 and later, so there it stays nested)
  Flattener(tinyxml2::XMLDocument* out, std::vector<Diagnostic>* warnings, bool flatten_includes)
      : out_(out), warnings_(warnings), flatten_includes_(flatten_includes) {}

  // Replaces every <include> below parent by what it includes, with the include's overrides.
  void expand(tinyxml2::XMLElement* parent, const std::string& base_dir, const std::string& file,
              const std::string& where, int depth) {
    if (depth > limits::kIncludeDepthMax)
      throw LoadError(file, parent->GetLineNum(), where,
                      "includes nest deeper than " + std::to_string(limits::kIncludeDepthMax) + " levels (a cycle?)");
    int i = 0;
    for (tinyxml2::XMLElement* child = parent->FirstChildElement(); child; ++i) {
      tinyxml2::XMLElement* next = child->NextSiblingElement();
      const std::string tag = child->Name();
      if (tag == "include") {
        const std::string here = where + "/include[" + std::to_string(i) + "]";
        std::string body_dir, body_file;
        tinyxml2::XMLElement* body = load_included(child, base_dir, file, here, &body_dir, &body_file);
        if (!body) {
          parent->DeleteChild(child);
          child = next;
          continue;
        }
        if (const auto name = find_text(child, "name"); name && !name->empty())
          body->SetAttribute("name", detail::trim(*name).c_str());
        if (const auto pose = find_text(child, "pose")) {
          parse_pose(*pose, file, here + "/pose");
          set_child(body, "pose", detail::trim(*pose));
        }
        if (const auto is_static = find_text(child, "static"); is_static && std::string(body->Name()) == "model")
          set_child(body, "static", detail::trim(*is_static));
        absolute_mesh_uris(body, body_dir);
        expand(body, body_dir, body_file, std::string(body->Name()) + "[" + attr(body, "name") + "]", depth + 1);
        parent->InsertAfterChild(child, body);
        parent->DeleteChild(child);
        // a model included inside a model is flattened into it (docs/COMPAT-sdf.md 16a)
        if (flatten_includes_ && std::string(parent->Name()) == "model" && std::string(body->Name()) == "model")
          flatten_into(parent, body, file, here);
      } else if (tag == "model") {
        expand(child, base_dir, file, where + "/model[" + attr(child, "name") + "]", depth);
      }
      child = next;
    }
  }

 private:
  // Gazebo 11's sdformat 9 addNestedModel (sdf9 src/parser.cc) on the text: the included model's links, joints,
  // frames and models are renamed `N::name`, with every attribute and text that names one exactly (its `"x"`,
  // `'x'` and `>x<`), and move into the parent where the include was, with its plug-ins (and its <static> where the
  // parent writes none); a link or model posed in N's frame (no relative_to) gets N's pose composed with its own,
  // in the parent's frame. libsdformat 12 reads the `N::name` links back as a nested model N (its 1.7 -> 1.8
  // unflattening), which the loader flattens again: the flat world loads as the world does.
  static void flatten_into(tinyxml2::XMLElement* parent, tinyxml2::XMLElement* body, const std::string& file,
                           const std::string& where) {
    const std::string n = attr(body, "name");
    std::map<std::string, std::string> names{{"__model__", n + "::__model__"}};
    for (auto* c = body->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if ((tag == "link" || tag == "joint" || tag == "frame" || tag == "model") && c->Attribute("name"))
        names[c->Attribute("name")] = n + "::" + c->Attribute("name");
    }
    rename_refs(body, names);
    const Eigen::Matrix4d Tn = parse_pose(find_text(body, "pose").value_or(""), file, where + "/pose");
    tinyxml2::XMLElement* after = body;
    for (tinyxml2::XMLElement* c = body->FirstChildElement(); c;) {
      tinyxml2::XMLElement* next = c->NextSiblingElement();
      const std::string tag = c->Name();
      bool move = tag == "link" || tag == "joint" || tag == "frame" || tag == "model" || tag == "plugin" ||
                  tag == "gripper" || (tag == "static" && !parent->FirstChildElement("static"));
      if (move && (tag == "link" || tag == "model")) {
        tinyxml2::XMLElement* pose = c->FirstChildElement("pose");
        if (!pose || !pose->Attribute("relative_to")) {
          const Eigen::Matrix4d Tc = parse_pose(find_text(c, "pose").value_or(""), file, where + "/pose");
          set_child(c, "pose", format_pose(Tn * Tc));
        }
      }
      if (move) {
        parent->InsertAfterChild(after, c);  // moves c out of body
        after = c;
      }
      c = next;
    }
    parent->DeleteChild(body);
  }

  // Every attribute value and element text that is a key of names becomes its value (addNestedModel's replace).
  static void rename_refs(tinyxml2::XMLElement* e, const std::map<std::string, std::string>& names) {
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next())
      if (const auto it = names.find(a->Value()); it != names.end()) e->SetAttribute(a->Name(), it->second.c_str());
    if (e->GetText() && !e->FirstChildElement())
      if (const auto it = names.find(e->GetText()); it != names.end()) e->SetText(it->second.c_str());
    for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) rename_refs(c, names);
  }

  // The <model>, <light> or <actor> an <include> names, copied into the output document (not yet linked).
  tinyxml2::XMLElement* load_included(const tinyxml2::XMLElement* include, const std::string& base_dir,
                                      const std::string& file, const std::string& where, std::string* body_dir,
                                      std::string* body_file) {
    // one that names nothing or resolves nowhere: left out with a warning where the caller takes warnings (as the
    // simulator does, and Gazebo 11: sdformat reports it and goes on), an error otherwise
    auto missing = [&](const std::string& element, const std::string& why) -> tinyxml2::XMLElement* {
      if (!warnings_) throw LoadError(file, include->GetLineNum(), element, why);
      warnings_->push_back({Severity::Warning, "include-missing", element,
                            why + ": left out, as Gazebo 11 leaves it out", include->GetLineNum()});
      return nullptr;
    };
    const std::string uri = detail::text_of(include->FirstChildElement("uri"));
    if (uri.empty()) return missing(where, "<include> has no <uri>");
    const std::string target = resolve_uri(uri, base_dir);
    if (target.empty()) {
      std::string path;
      for (const auto& d : model_path()) path += (path.empty() ? "" : ":") + d;
      return missing(where + "/uri", "cannot find '" + uri + "' (model path: " + path + ")");
    }
    std::error_code ec;
    std::string sdf_file = target;
    if (std::filesystem::is_directory(target, ec)) try {
        sdf_file = detail::model_sdf_file(target);
      } catch (const LoadError& e) {
        return missing(where + "/uri", "'" + target + "': " + e.reason());
      }
    tinyxml2::XMLDocument doc;
    read_sdf(sdf_file, &doc);
    const tinyxml2::XMLElement* body = nullptr;
    if (const tinyxml2::XMLElement* root = doc.RootElement())
      for (const tinyxml2::XMLElement* c = root->FirstChildElement(); c && !body; c = c->NextSiblingElement()) {
        const std::string tag = c->Name();
        if (tag == "model" || tag == "light" || tag == "actor") body = c;
      }
    if (!body) throw LoadError(sdf_file, 0, "sdf", "holds no <model> or <light>");
    *body_dir = folder_of(sdf_file);
    *body_file = sdf_file;
    return body->DeepClone(out_)->ToElement();
  }

  // Mesh URIs inside an included model, made absolute so the output stands alone (package:// ones stay).
  static void absolute_mesh_uris(tinyxml2::XMLElement* e, const std::string& base_dir) {
    if (std::string(e->Name()) == "mesh")
      if (tinyxml2::XMLElement* u = e->FirstChildElement("uri"); u && u->GetText()) {
        const std::string text = u->GetText();
        if (detail::trim(text).rfind("package://", 0) != 0) {
          const std::string p = resolve_uri(text, base_dir);
          if (!p.empty()) u->SetText(("file://" + abspath(p)).c_str());
        }
      }
    for (tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
      absolute_mesh_uris(c, base_dir);
  }

  tinyxml2::XMLDocument* out_;
  std::vector<Diagnostic>* warnings_;  // nullptr: an include that resolves nowhere is an error
  bool flatten_includes_;
};

// True for an <sdf version> below 1.8 (or none): the versions Gazebo 11's sdformat 9 reads.
bool before_1_8(const tinyxml2::XMLElement* sdf) {
  const char* v = sdf->Attribute("version");
  if (!v) return true;
  int major = 0, minor = 0;
  if (std::sscanf(v, "%d.%d", &major, &minor) < 1) return true;
  return major < 1 || (major == 1 && minor < 8);
}

// Nested models become top-level models 'parent::child' with composed poses, static when the parent is (the
// loader's add_model does the same on the DOM). Each pass hoists one level; a parent's nested models land right
// after it, the last one first. A parent left with no <link> is dropped: libsdformat 12 refuses a model without a
// link, and its nested models hold everything it simulated (the loader keeps it as a model that follows its
// canonical link, docs/COMPAT-sdf.md 16a; the flat world has no way to say that).
void hoist_nested(tinyxml2::XMLElement* world, const std::string& file) {
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<tinyxml2::XMLElement*> models;
    for (auto* m = world->FirstChildElement("model"); m; m = m->NextSiblingElement("model")) models.push_back(m);
    for (tinyxml2::XMLElement* m : models) {
      std::vector<tinyxml2::XMLElement*> nested;
      for (auto* n = m->FirstChildElement("model"); n; n = n->NextSiblingElement("model")) nested.push_back(n);
      for (tinyxml2::XMLElement* n : nested) {
        const Eigen::Matrix4d Tm = parse_pose(find_text(m, "pose").value_or(""), file, "");
        const Eigen::Matrix4d Tn = parse_pose(find_text(n, "pose").value_or(""), file, "");
        n->SetAttribute("name", (attr(m, "name") + "::" + attr(n, "name")).c_str());
        set_child(n, "pose", format_pose(Tm * Tn));
        const std::string parent_static = detail::trim(find_text(m, "static").value_or(""));
        if (parent_static == "1" || parent_static == "true") set_child(n, "static", "true");
        world->InsertAfterChild(m, n);  // moves n out of m
        changed = true;
      }
      if (!nested.empty() && !m->FirstChildElement("link")) world->DeleteChild(m);
    }
  }
}

// Gazebo applies a world's <state> when it loads: model poses there win; the block is then dropped.
void apply_state(tinyxml2::XMLElement* world) {
  std::vector<tinyxml2::XMLElement*> states;
  for (auto* st = world->FirstChildElement("state"); st; st = st->NextSiblingElement("state")) states.push_back(st);
  for (tinyxml2::XMLElement* st : states) {
    for (auto* sm = st->FirstChildElement("model"); sm; sm = sm->NextSiblingElement("model")) {
      const auto pose = find_text(sm, "pose");
      for (auto* m = world->FirstChildElement("model"); m; m = m->NextSiblingElement("model"))
        if (pose && attr(m, "name") == attr(sm, "name")) set_child(m, "pose", detail::trim(*pose));
    }
    world->DeleteChild(st);
  }
}

// The encoding the document's declaration names (' encoding="ISO-8859-1"'), or "" when it names none or one that is
// not a plain name (a letter, then letters, digits, '.', '_', '-').
std::string declared_encoding(const tinyxml2::XMLDocument& doc) {
  const tinyxml2::XMLNode* first = doc.FirstChild();
  const tinyxml2::XMLDeclaration* decl = first ? first->ToDeclaration() : nullptr;
  if (!decl || !decl->Value()) return "";
  const std::string v = decl->Value();
  size_t i = v.find("encoding");
  if (i == std::string::npos) return "";
  i = v.find_first_not_of(" \t\r\n", i + 8);
  if (i == std::string::npos || v[i] != '=') return "";
  i = v.find_first_not_of(" \t\r\n", i + 1);
  if (i == std::string::npos || (v[i] != '"' && v[i] != '\'')) return "";
  const size_t end = v.find(v[i], i + 1);
  if (end == std::string::npos) return "";
  const std::string name = v.substr(i + 1, end - i - 1);
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return "";
  for (const char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') return "";
  return " encoding=\"" + name + "\"";
}

// The flattened document in doc (see flatten_world_file); returns its <world>.
tinyxml2::XMLElement* flatten_document(const std::string& path, tinyxml2::XMLDocument* doc,
                                       std::vector<Diagnostic>* warnings) {
  read_sdf(path, doc);
  tinyxml2::XMLElement* root = doc->RootElement();
  if (!root || std::string(root->Name()) != "sdf")
    throw LoadError(path, root ? root->GetLineNum() : 0, root ? root->Name() : "", "root element is not <sdf>");
  tinyxml2::XMLElement* world = root->FirstChildElement("world");
  if (!world) throw LoadError(path, root->GetLineNum(), "sdf", "no <world>");
  Flattener(doc, warnings, before_1_8(root)).expand(world, folder_of(abspath(path)), path, "world[" + attr(world, "name") + "]", 0);
  hoist_nested(world, path);
  apply_state(world);
  return world;
}

// The <sdf> element as text under a declaration of our own (with encoding, when not empty): the input's
// declarations, comments and unknown nodes are left out, since tinyxml2 writes some of them back in forms it cannot
// read again (a '<??xml' declaration, found by fuzz_flatten).
std::string print_document(const tinyxml2::XMLDocument& doc, const std::string& encoding) {
  class Printer : public tinyxml2::XMLPrinter {
   public:
    Printer() : tinyxml2::XMLPrinter(nullptr, /*compact=*/true) {}
    bool Visit(const tinyxml2::XMLComment&) override { return true; }
    bool Visit(const tinyxml2::XMLUnknown&) override { return true; }
    bool Visit(const tinyxml2::XMLDeclaration&) override { return true; }
  } printer;
  printer.PushDeclaration(("xml version=\"1.0\"" + encoding).c_str());
  doc.RootElement()->Accept(&printer);
  return printer.CStr();
}

// The text in UTF-8 for the loader: an ISO-8859-1 document's bytes above 0x7f become two bytes each (tinyxml2
// passes bytes through untranslated, and the loader's names reach Python as UTF-8).
std::string utf8_of(const std::string& text, const std::string& encoding) {
  std::string name;
  for (const char c : encoding.substr(encoding.find('"') + 1))
    if (std::isalnum(static_cast<unsigned char>(c))) name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (name != "iso88591" && name != "latin1" && name != "l1") return text;
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out += ch;
    } else {
      out += static_cast<char>(0xc0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3f));
    }
  }
  return out;
}

// The offset of the first byte that does not belong to a well-formed UTF-8 sequence, -1 when there is none.
int first_non_utf8(const std::string& s) {
  for (size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
    if (n == 0 || i + n > s.size()) return static_cast<int>(i);
    for (size_t k = 1; k < n; ++k)
      if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return static_cast<int>(i);
    i += n;
  }
  return -1;
}

// The flattened document as UTF-8 text (an ISO-8859-1 declaration transcoded); false, with why in *not_text, where
// a byte is not text.
bool flat_utf8(const tinyxml2::XMLDocument& doc, std::string* text, std::string* not_text) {
  *text = utf8_of(print_document(doc, ""), declared_encoding(doc));
  const int bad = first_non_utf8(*text);
  if (bad < 0) return true;
  char byte[8];
  std::snprintf(byte, sizeof(byte), "0x%02x", static_cast<unsigned char>((*text)[bad]));
  *not_text = std::string("not UTF-8 text (byte ") + byte +
              "; car reads worlds in UTF-8, and in ISO-8859-1 where their declaration says so)";
  return false;
}

}  // namespace

std::string flatten_world_file(const std::string& path, std::vector<Diagnostic>* warnings) {
  tinyxml2::XMLDocument doc;
  flatten_document(path, &doc, warnings);
  // the input's declared encoding is kept (tinyxml2 passes the bytes through untranslated), so the text reads back
  // as the input did: an ISO-8859-1 world stays ISO-8859-1
  return print_document(doc, declared_encoding(doc));
}

WorldCheck check_world_file(const std::string& path) {
  WorldCheck out;
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* world = nullptr;
  try {
    world = flatten_document(path, &doc, &out.findings);
  } catch (const LoadError& e) {
    out.findings.push_back({Severity::Error, "world-unreadable", e.element(), e.reason(), 0});
    return out;
  }
  const std::vector<Diagnostic> rules = detail::check_world_xml(world);
  out.findings.insert(out.findings.end(), rules.begin(), rules.end());
  for (const auto& f : out.findings)
    if (f.severity == Severity::Error) return out;
  std::string text, not_text;
  if (!flat_utf8(doc, &text, &not_text)) {
    out.findings.push_back({Severity::Error, "world-unreadable", "", not_text, 0});
    return out;
  }
  try {
    auto d = std::make_shared<WorldDescription>(load_world_string(text, path));
    out.findings.insert(out.findings.end(), d->diagnostics.begin(), d->diagnostics.end());
    out.world = std::move(d);
  } catch (const LoadError& e) {
    // the words of LoadError::what() after "FILE[:LINE]: "
    out.findings.push_back(
        {Severity::Error, "world-load", "", (e.element().empty() ? "" : e.element() + ": ") + e.reason(), 0});
  }
  return out;
}

WorldDescription load_flattened_world(const std::string& path, std::vector<Diagnostic>* warnings) {
  tinyxml2::XMLDocument doc;
  flatten_document(path, &doc, warnings);
  std::string text, not_text;
  if (!flat_utf8(doc, &text, &not_text)) throw LoadError(path, 0, "", not_text);
  return load_world_string(text, path);
}

}  // namespace car_sim
