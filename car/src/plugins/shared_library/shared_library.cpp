// Plug-ins from shared libraries: the search, the loading with Gazebo's messages, and the instance that holds the
// skin's running plug-in (docs/COMPAT-plugins.md "Users' own plug-ins").
#include "shared_library/shared_library.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "car_sim/shared_plugin.hpp"

namespace car_sim {

namespace {

SharedPluginHost* g_host = nullptr;

void split_into(const char* var, const std::string& suffix, std::vector<std::string>* out) {
  const char* v = std::getenv(var);
  if (!v) return;
  std::stringstream ss(v);
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty()) out->push_back(dir + suffix);
}

bool is_file(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

class SharedLibraryPlugin : public Plugin {
 public:
  explicit SharedLibraryPlugin(const PluginConfig& c) : config_(c) {}
  ~SharedLibraryPlugin() override {
    // unloaded with its model: the plug-in goes; the library stays open (its code may still be referenced by
    // objects the plug-in handed out, as in Gazebo, which never closes a plug-in's library either)
    running_.reset();
  }

  double update_rate() const override { return 0.0; }

  void loaded(World& world, std::vector<Diagnostic>* diagnostics) override {
    const std::string where = "gazebo/plugin[" + config_.name + "]";
    auto fail = [&](const std::string& message) {
      diagnostics->push_back({Severity::Error, "plugin-not-loaded", where, message, 0});
    };
    const std::string path = find_shared_plugin(config_.filename, shared_plugin_search_path());
    // Gazebo's RTLD_LAZY | RTLD_GLOBAL: the library's symbols serve the libraries it loads in turn
    void* handle = dlopen(path.empty() ? config_.filename.c_str() : path.c_str(), RTLD_LAZY | RTLD_GLOBAL);
    if (!handle) {
      const char* e = dlerror();
      return fail("Failed to load plugin " + (path.empty() ? config_.filename : path) + ": " + (e ? e : "") +
                  "; model '" + robot_ + "' goes on without it");
    }
    dlerror();
    void* fn = dlsym(handle, "RegisterPlugin");
    if (!fn) {
      const char* e = dlerror();
      return fail("Failed to resolve RegisterPlugin: " + std::string(e ? e : "no such symbol") + " (plug-in '" +
                  config_.name + "', " + path + "); model '" + robot_ + "' goes on without it");
    }
    SharedPluginHost* host = shared_plugin_host();
    if (!host)
      return fail("plug-in '" + config_.name + "' (" + path +
                  ") does not link car's Gazebo API (car_gazebo, find_package(gazebo)); model '" + robot_ +
                  "' goes on without it");
    SharedPluginContext ctx;
    ctx.world = &world;
    ctx.model = robot_;
    ctx.name = config_.name;
    ctx.filename = config_.filename;
    ctx.path = path;
    ctx.params = config_.raw;
    try {
      running_ = host->load(fn, ctx);
    } catch (const std::exception& e) {
      fail("plug-in '" + config_.name + "' of model '" + robot_ + "' failed to load: " + e.what() +
           "; the model goes on without it");
    }
  }

  void reset() override {
    if (running_) running_->reset();
  }

  std::string robot_;

 private:
  PluginConfig config_;
  std::unique_ptr<SharedPlugin> running_;
};

}  // namespace

void set_shared_plugin_host(SharedPluginHost* host) { g_host = host; }
SharedPluginHost* shared_plugin_host() { return g_host; }

std::vector<std::string> shared_plugin_search_path() {
  std::vector<std::string> dirs;
  split_into("GAZEBO_PLUGIN_PATH", "", &dirs);
  split_into("CMAKE_PREFIX_PATH", "/lib", &dirs);
  split_into("LD_LIBRARY_PATH", "", &dirs);
  // a folder named twice is searched once, where it first comes
  std::vector<std::string> once;
  for (const auto& d : dirs)
    if (std::find(once.begin(), once.end(), d) == once.end()) once.push_back(d);
  return once;
}

bool upstream_plugin_wanted(const std::string& filename) {
  const char* v = std::getenv("CAR_UPSTREAM_PLUGINS");
  if (!v || filename.empty()) return false;
  std::string list(v);
  for (char& c : list)
    if (c == ',') c = ':';
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ':'))
    if (name == filename) return true;
  return false;
}

std::string find_shared_plugin(const std::string& filename, const std::vector<std::string>& dirs) {
  if (filename.empty()) return "";
  if (filename[0] == '/') return is_file(filename) ? filename : "";
  for (const auto& d : dirs) {
    const std::string p = d + "/" + filename;
    if (is_file(p)) return p;
  }
  return "";
}

const PluginKind& shared_library_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "shared_library";
    k.any_keys = true;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t) {
      auto p = std::make_unique<SharedLibraryPlugin>(c);
      p->robot_ = robot;
      return std::unique_ptr<Plugin>(std::move(p));
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
