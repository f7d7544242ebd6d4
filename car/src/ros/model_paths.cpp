// gazebo_ros's model-path exports: a package whose package.xml has
// <export><gazebo_ros gazebo_model_path="..."/></export> adds that folder to the model path (${prefix} = the
// package's folder), as gazebo_ros's paths plug-in does when gzserver starts (docs/COMPAT.md "Model path").
#include <tinyxml2.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "node.hpp"

namespace car_ros {

namespace {

// Packages under one ROS_PACKAGE_PATH entry, as rospack crawls: a folder with a package.xml is a package and is
// not searched further; dot-folders and folders with a CATKIN_IGNORE are skipped.
void crawl(const std::filesystem::path& dir, std::vector<std::filesystem::path>* out, int depth) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (depth > 8 || !fs::is_directory(dir, ec)) return;
  if (fs::exists(dir / "package.xml", ec)) {
    out->push_back(dir);
    return;
  }
  if (fs::exists(dir / "CATKIN_IGNORE", ec)) return;
  for (const auto& e : fs::directory_iterator(dir, fs::directory_options::skip_permission_denied, ec))
    if (e.is_directory(ec) && e.path().filename().string()[0] != '.') crawl(e.path(), out, depth + 1);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> exported_model_paths() {
  std::vector<std::pair<std::string, std::string>> out;  // (package, folder)
  const char* rpp = std::getenv("ROS_PACKAGE_PATH");
  std::stringstream ss(rpp ? rpp : "");
  std::string entry;
  std::vector<std::filesystem::path> packages;
  while (std::getline(ss, entry, ':'))
    if (!entry.empty()) crawl(entry, &packages, 0);
  for (const auto& pkg : packages) {
    tinyxml2::XMLDocument doc;
    if (doc.LoadFile((pkg / "package.xml").c_str()) != tinyxml2::XML_SUCCESS) continue;
    const auto* root = doc.RootElement();
    const auto* exp = root ? root->FirstChildElement("export") : nullptr;
    const auto* name = root ? root->FirstChildElement("name") : nullptr;
    for (const auto* g = exp ? exp->FirstChildElement("gazebo_ros") : nullptr; g;
         g = g->NextSiblingElement("gazebo_ros")) {
      const char* attr = g->Attribute("gazebo_model_path");
      if (!attr) continue;
      std::string path = attr;
      for (size_t at; (at = path.find("${prefix}")) != std::string::npos;) path.replace(at, 9, pkg.string());
      out.emplace_back(name && name->GetText() ? name->GetText() : pkg.filename().string(), path);
    }
  }
  return out;
}

void add_exported_model_paths() {
  const char* env = std::getenv("GAZEBO_MODEL_PATH");
  std::string value = env ? env : "";
  for (const auto& [pkg, path] : exported_model_paths()) {
    if ((":" + value + ":").find(":" + path + ":") != std::string::npos) continue;
    value += (value.empty() ? "" : ":") + path;
    ROS_INFO("car: model path + %s (exported by package %s)", path.c_str(), pkg.c_str());
  }
  setenv("GAZEBO_MODEL_PATH", value.c_str(), 1);
}

}  // namespace car_ros
