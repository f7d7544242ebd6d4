#include "xml_util.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace car_sim {
namespace detail {

std::string trim(const std::string& s) {
  const char* ws = " \t\r\n";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

std::string short_number(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

std::vector<std::string> split_ws(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  std::string tok;
  while (in >> tok) out.push_back(tok);
  return out;
}

std::optional<double> parse_number(const std::string& text) {
  const std::string t = trim(text);
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  // strtod follows the C locale, which the core never changes.
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::vector<double>> parse_numbers(const std::string& text, size_t n) {
  const auto toks = split_ws(text);
  if (toks.size() != n) return std::nullopt;
  std::vector<double> out;
  for (const auto& t : toks) {
    const auto v = parse_number(t);
    if (!v) return std::nullopt;
    out.push_back(*v);
  }
  return out;
}

Eigen::Matrix3d rpy_to_matrix(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::optional<Eigen::Isometry3d> parse_pose6(const std::string& text) {
  const auto v = parse_numbers(text, 6);
  if (!v) return std::nullopt;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]);
  T.linear() = rpy_to_matrix((*v)[3], (*v)[4], (*v)[5]);
  return T;
}

std::string text_of(const tinyxml2::XMLElement* e) {
  if (!e || !e->GetText()) return "";
  return trim(e->GetText());
}

std::string value_of(const tinyxml2::XMLElement* e) {
  if (!e) return "";
  if (const char* v = e->Attribute("value")) return trim(v);
  return text_of(e);
}

void flatten(const tinyxml2::XMLElement* e, const std::string& prefix, ParamList* out) {
  for (auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string key = prefix.empty() ? c->Name() : prefix + "/" + c->Name();
    if (c->FirstChildElement()) {
      flatten(c, key, out);
    } else {
      out->emplace_back(key, text_of(c));
    }
  }
}

}  // namespace detail
}  // namespace car_sim
