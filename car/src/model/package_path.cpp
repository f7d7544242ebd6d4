// rospack's package crawl for package:// URIs (see package_path.hpp).
#include "package_path.hpp"

#include <dlfcn.h>
#include <tinyxml2.h>

#include <filesystem>
#include <map>
#include <mutex>

namespace car_sim {
namespace detail {

namespace {

namespace fs = std::filesystem;

// <name> of DIR/package.xml, or "" when DIR holds none or it cannot be read.
std::string package_xml_name(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / "package.xml", ec)) return "";
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile((dir / "package.xml").c_str()) != tinyxml2::XML_SUCCESS) return "";
  const auto* root = doc.RootElement();
  const auto* n = root ? root->FirstChildElement("name") : nullptr;
  if (!n || !n->GetText()) return "";
  std::string s = n->GetText();
  s.erase(0, s.find_first_not_of(" \t\r\n"));
  s.erase(s.find_last_not_of(" \t\r\n") + 1);
  return s;
}

// rospack's crawl of one entry: name -> folder (the first found in directory order kept).
void crawl(const fs::path& dir, int depth, std::map<std::string, std::string>* out) {
  std::error_code ec;
  // rospack stops at the same depth bound for pathological trees
  if (depth > 16 || !fs::is_directory(dir, ec)) return;
  const std::string name = package_xml_name(dir);
  if (!name.empty()) {
    out->emplace(name, dir.string());
    return;
  }
  if (fs::exists(dir / "CATKIN_IGNORE", ec) || fs::exists(dir / "rospack_nosubdirs", ec)) return;
  for (const auto& e : fs::directory_iterator(dir, fs::directory_options::skip_permission_denied, ec)) {
    const std::string f = e.path().filename().string();
    if (!f.empty() && f[0] != '.' && e.is_directory(ec)) crawl(e.path(), depth + 1, out);
  }
}

std::mutex cache_mutex;

// Crawl results per entry, kept for the process (rospack keeps a cache too); entries are crawled on first need.
const std::map<std::string, std::string>& crawled(const std::string& entry) {
  static std::map<std::string, std::map<std::string, std::string>> cache;
  std::lock_guard<std::mutex> lock(cache_mutex);
  auto it = cache.find(entry);
  if (it == cache.end()) {
    std::map<std::string, std::string> found;
    crawl(entry, 0, &found);
    it = cache.emplace(entry, std::move(found)).first;
  }
  return it->second;
}

}  // namespace

std::string find_ros_package(const std::string& name, const std::vector<std::string>& entries) {
  if (name.empty()) return "";
  for (const auto& entry : entries) {
    // the common layouts first, without a crawl: the entry is the package, or holds it as ENTRY/NAME
    for (const fs::path cand : {fs::path(entry), fs::path(entry) / name})
      if (package_xml_name(cand) == name) return cand.string();
    const auto& found = crawled(entry);
    const auto it = found.find(name);
    if (it != found.end()) return it->second;
  }
  return "";
}

const std::string& car_package_dir() {
  static const std::string dir = [] {
    // the file this function was loaded from: <prefix>/lib/libcar_sim.so once installed
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&car_package_dir), &info) && info.dli_fname) {
      std::error_code ec;
      const fs::path lib = fs::canonical(info.dli_fname, ec);
      const fs::path share = lib.parent_path().parent_path() / "share" / "car";
      if (!ec && fs::exists(share / "config" / "gazebo_materials.txt", ec)) return share.string();
      // a wheel (pip, pyproject.toml): the core is linked into <site-packages>/car/_core*.so, beside car/data/
      const fs::path data = lib.parent_path() / "data";
      if (!ec && fs::exists(data / "config" / "gazebo_materials.txt", ec)) return data.string();
    }
    return std::string(CAR_PACKAGE_DIR);
  }();
  return dir;
}

}  // namespace detail
}  // namespace car_sim
