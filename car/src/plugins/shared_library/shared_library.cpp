// Plug-ins from shared libraries: the search, the loading with Gazebo's messages, and the instance that holds the
// skin's running plug-in (docs/COMPAT-plugins.md "Users' own plug-ins").
#include "shared_library/shared_library.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "car_sim/shared_plugin.hpp"
#include "car_sim/world.hpp"

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

// Opens a plug-in's library and hands its RegisterPlugin to the host: the one loader for model, world and system
// plug-ins. `owner` names what goes on without it in the messages ("model 'M'", "world 'W'", "the server").
std::unique_ptr<SharedPlugin> open_plugin(const SharedPluginContext& base, const std::string& owner,
                                          const std::string& where, std::vector<Diagnostic>* diagnostics) {
  auto fail = [&](const std::string& message) {
    diagnostics->push_back({Severity::Error, "plugin-not-loaded", where, message, 0});
    return nullptr;
  };
  SharedPluginContext ctx = base;
  const std::string path = ctx.path.empty() ? find_shared_plugin(ctx.filename, shared_plugin_search_path()) : ctx.path;
  // Gazebo's RTLD_LAZY | RTLD_GLOBAL: the library's symbols serve the libraries it loads in turn
  void* handle = dlopen(path.empty() ? ctx.filename.c_str() : path.c_str(), RTLD_LAZY | RTLD_GLOBAL);
  if (!handle) {
    const char* e = dlerror();
    return fail("Failed to load plugin " + (path.empty() ? ctx.filename : path) + ": " + (e ? e : "") + "; " + owner +
                " goes on without it");
  }
  dlerror();
  void* fn = dlsym(handle, "RegisterPlugin");
  if (!fn) {
    const char* e = dlerror();
    return fail("Failed to resolve RegisterPlugin: " + std::string(e ? e : "no such symbol") + " (plug-in '" +
                ctx.name + "', " + path + "); " + owner + " goes on without it");
  }
  SharedPluginHost* host = shared_plugin_host();
  if (!host)
    return fail("plug-in '" + ctx.name + "' (" + path +
                ") does not link car's Gazebo API (car_gazebo, find_package(gazebo)); " + owner + " goes on without it");
  ctx.path = path;
  try {
    return host->load(fn, ctx);
  } catch (const std::exception& e) {
    return fail("plug-in '" + ctx.name + "' of " + owner + " failed to load: " + e.what() + "; " +
                (ctx.place == PluginPlace::Model ? std::string("the model") : owner) + " goes on without it");
  }
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
    SharedPluginContext ctx;
    ctx.world = &world;
    ctx.place = PluginPlace::Model;
    ctx.model = robot_;
    ctx.name = config_.name;
    ctx.filename = config_.filename;
    ctx.params = config_.raw;
    running_ = open_plugin(ctx, "model '" + robot_ + "'", "gazebo/plugin[" + config_.name + "]", diagnostics);
  }

  void reset() override {
    if (running_) running_->reset();
  }

  std::string robot_;

 private:
  PluginConfig config_;
  std::unique_ptr<SharedPlugin> running_;
};

// gazebo_ros's system plug-ins: car's node is both (docs/COMPAT-dropins.md), so a world or a command line that
// names them loads nothing.
bool gazebo_ros_system_plugin(const std::string& filename) {
  const auto slash = filename.rfind('/');
  const std::string base = slash == std::string::npos ? filename : filename.substr(slash + 1);
  return base == "libgazebo_ros_api_plugin.so" || base == "libgazebo_ros_paths_plugin.so";
}

std::string joined(const std::vector<std::string>& dirs) {
  std::string out;
  for (const auto& d : dirs) out += (out.empty() ? "" : ":") + d;
  return out;
}

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

std::vector<std::unique_ptr<SharedPlugin>> load_world_plugins(World& world, const std::vector<PluginSpec>& specs,
                                                              std::vector<Diagnostic>* diagnostics) {
  std::vector<std::unique_ptr<SharedPlugin>> out;
  const std::string owner = "world '" + world.description().name + "'";
  for (const auto& spec : specs) {
    const std::string where = "world/plugin[" + spec.name + "]";
    if (gazebo_ros_system_plugin(spec.filename)) {
      diagnostics->push_back({Severity::Info, "plugin-native", where,
                              spec.filename + " is gazebo_ros's own, which car's node is: nothing to load", spec.line});
      continue;
    }
    const auto dirs = shared_plugin_search_path();
    const std::string path = find_shared_plugin(spec.filename, dirs);
    if (path.empty()) {
      diagnostics->push_back({Severity::Warning, "plugin-unknown", where,
                              "Failed to load plugin " + spec.filename +
                                  ": no such file in GAZEBO_PLUGIN_PATH, the ROS library folders or LD_LIBRARY_PATH "
                                  "(searched: " + joined(dirs) + "); " + owner + " goes on without it",
                              spec.line});
      continue;
    }
    SharedPluginContext ctx;
    ctx.world = &world;
    ctx.place = PluginPlace::World;
    ctx.name = spec.name;
    ctx.filename = spec.filename;
    ctx.path = path;
    ctx.params = spec.params;
    ctx.xml = spec.xml;
    const size_t before = diagnostics->size();
    auto p = open_plugin(ctx, owner, where, diagnostics);
    for (size_t k = before; k < diagnostics->size(); ++k) (*diagnostics)[k].line = spec.line;
    if (p) out.push_back(std::move(p));
  }
  return out;
}

std::unique_ptr<SharedPlugin> load_system_plugin(World& world, const std::string& filename,
                                                 const std::vector<std::string>& args,
                                                 std::vector<Diagnostic>* diagnostics) {
  const std::string where = "server/plugin[" + filename + "]";
  if (gazebo_ros_system_plugin(filename)) {
    diagnostics->push_back({Severity::Info, "plugin-native", where,
                            filename + " is gazebo_ros's own, which car's node is: nothing to load", 0});
    return nullptr;
  }
  const auto dirs = shared_plugin_search_path();
  const std::string path = find_shared_plugin(filename, dirs);
  if (path.empty()) {
    diagnostics->push_back({Severity::Warning, "plugin-unknown", where,
                            "Failed to load plugin " + filename +
                                ": no such file in GAZEBO_PLUGIN_PATH, the ROS library folders or LD_LIBRARY_PATH "
                                "(searched: " + joined(dirs) + "); the server goes on without it",
                            0});
    return nullptr;
  }
  SharedPluginContext ctx;
  ctx.world = &world;
  ctx.place = PluginPlace::System;
  ctx.args = args;
  ctx.name = filename;
  ctx.filename = filename;
  ctx.path = path;
  return open_plugin(ctx, "the server", where, diagnostics);
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
