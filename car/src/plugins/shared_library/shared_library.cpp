// Plug-ins from shared libraries: the search, the loading with Gazebo's messages, and the instance that holds the
// skin's running plug-in (docs/COMPAT-plugins.md "Users' own plug-ins").
#include "shared_library/shared_library.hpp"

#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <mutex>
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

class SharedLibraryPlugin;

// Sensors whose world had no skin yet when they loaded (car_gazebo comes with the first plug-in library dlopened):
// they come up as soon as a library of their world brings it, before that library's plug-in loads (a model
// plug-in's Load looks its sensors up, as Kobuki's does).
std::mutex g_pending_mutex;
std::vector<SharedLibraryPlugin*> g_pending;

// Opens a plug-in's library and hands its RegisterPlugin to the host: the one loader for model, world and system
// plug-ins. `owner` names what goes on without it in the messages ("model 'M'", "world 'W'", "the server").
// `before_load` runs once the skin is known to be there, just before the plug-in loads.
std::unique_ptr<SharedPlugin> open_plugin(const SharedPluginContext& base, const std::string& owner,
                                          const std::string& where, std::vector<Diagnostic>* diagnostics,
                                          const std::function<void()>& before_load = {}) {
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
  if (before_load) before_load();
  try {
    return host->load(fn, ctx);
  } catch (const std::exception& e) {
    return fail("plug-in '" + ctx.name + "' of " + owner + " failed to load: " + e.what() + "; " +
                (ctx.place == PluginPlace::Model ? std::string("the model") : owner) + " goes on without it");
  }
}

class SharedLibraryPlugin : public Plugin {
 public:
  SharedLibraryPlugin(const PluginConfig& c, const std::string& robot, uint64_t seed) : config_(c), robot_(robot) {
    if (c.sensor.empty()) return;
    // a sensor's: car's own kind for its type measures, resolved from the same <sensor> (same seed and name, so the
    // same noise; docs/PLUGINS.md "Sensors")
    const PluginKind* feed = sensor_feed_kind(c.sensor_type);
    PluginConfig own = c;
    own.kind = feed->name;
    own.filename = sensor_feed_file(c.sensor_type);
    own.raw.clear();
    feed_ = feed->make(own, robot, seed);
  }
  ~SharedLibraryPlugin() override {
    unpend();
    // unloaded with its model: the plug-in goes; the library stays open (its code may still be referenced by
    // objects the plug-in handed out, as in Gazebo, which never closes a plug-in's library either)
    running_.reset();
  }

  double update_rate() const override { return feed_ ? feed_->update_rate() : 0.0; }
  Schedule schedule(double dt, uint64_t start_tick) const override {
    return feed_ ? feed_->schedule(dt, start_tick) : Plugin::schedule(dt, start_tick);
  }
  void configure(RobotHandle& robot) override {
    if (!feed_) return;
    feed_->configure(robot);
    feed_->set_active(true);
  }
  void start_clock(uint64_t tick) override {
    if (feed_) feed_->start_clock(tick);
  }
  void track(const StepContext& ctx, const RobotHandle& robot) override {
    if (feed_ && measuring()) feed_->track(ctx, robot);
  }
  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    if (!feed_) return;
    if (!measuring()) {
      feed_->idle(ctx, robot);
      return;
    }
    // the kind's outputs go to the sensor, not to the world's queue: nothing is published for them
    OutputQueue own;
    feed_->post_physics(ctx, robot, &own);
    if (own.empty()) running_->sensor_update(ctx.tick, nullptr);
    for (const OutputPtr& o : own) running_->sensor_update(ctx.tick, o.get());
  }

  void loaded(World& world, std::vector<Diagnostic>* diagnostics) override {
    world_ = &world;
    diagnostics_ = diagnostics;
    if (config_.filename.empty()) {
      // a sensor with no plug-in: offered to Gazebo's sensors API once the skin is there
      if (shared_plugin_host()) return bring_up_sensor();
      std::lock_guard<std::mutex> lock(g_pending_mutex);
      g_pending.push_back(this);
      return;
    }
    const std::string where = config_.sensor.empty() ? "gazebo/plugin[" + config_.name + "]"
                                                     : "sensor[" + config_.sensor + "]/plugin[" + config_.name + "]";
    running_ = open_plugin(context(), "model '" + robot_ + "'", where, diagnostics,
                           [&world] { bring_up_pending(&world); });
  }

  void reset() override {
    if (feed_) feed_->reset();
    if (running_) running_->reset();
  }

 private:
  bool measuring() const { return running_ && running_->sensor_active(); }

  // What the skin loads this plug-in (or plug-in-less sensor) with.
  SharedPluginContext context() const {
    SharedPluginContext ctx;
    ctx.world = world_;
    ctx.place = PluginPlace::Model;
    ctx.model = robot_;
    ctx.name = config_.name;
    ctx.filename = config_.filename;
    ctx.params = config_.raw;
    if (!config_.sensor.empty()) {
      ctx.in_sensor = true;
      for (const SensorSpec& s : world_->robot(robot_).model.sensors)
        if (s.name == config_.sensor) ctx.sensor = s;
      // the link after lumping (a contact sensor's: its collision's), as the kind resolved it
      ctx.sensor.link = config_.link;
      for (const ResolvedParam& p : config_.params) ctx.sensor_keys.emplace_back(p.key, p.value);
    }
    return ctx;
  }

  // A sensor with no plug-in into Gazebo's sensors API.
  void bring_up_sensor() {
    try {
      running_ = shared_plugin_host()->load(nullptr, context());
    } catch (const std::exception& e) {
      diagnostics_->push_back({Severity::Error, "plugin-not-loaded", "sensor[" + config_.sensor + "]",
                               "sensor '" + config_.sensor + "' of model '" + robot_ + "' failed to load: " + e.what() +
                                   "; the model goes on without it",
                               0});
    }
  }

  // The sensors of `world` that waited for the skin.
  static void bring_up_pending(World* world) {
    std::vector<SharedLibraryPlugin*> mine;
    {
      std::lock_guard<std::mutex> lock(g_pending_mutex);
      for (auto it = g_pending.begin(); it != g_pending.end();) {
        if ((*it)->world_ == world) {
          mine.push_back(*it);
          it = g_pending.erase(it);
        } else {
          ++it;
        }
      }
    }
    for (SharedLibraryPlugin* p : mine) p->bring_up_sensor();
  }

  void unpend() {
    std::lock_guard<std::mutex> lock(g_pending_mutex);
    g_pending.erase(std::remove(g_pending.begin(), g_pending.end(), this), g_pending.end());
  }

  PluginConfig config_;
  std::string robot_;
  std::unique_ptr<Plugin> feed_;  // a sensor's: car's own kind for its type
  World* world_ = nullptr;
  std::vector<Diagnostic>* diagnostics_ = nullptr;
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

// The library a world's or the server's <plugin> names, or "" when there is none to open: gazebo_ros's own (car's
// node is it: an info) or a file on no search path (Gazebo's "Failed to load plugin" warning, the folders searched).
static std::string locate_plugin(const std::string& filename, const std::string& owner, const std::string& where,
                                 int line, std::vector<Diagnostic>* diagnostics) {
  if (gazebo_ros_system_plugin(filename)) {
    diagnostics->push_back({Severity::Info, "plugin-native", where,
                            filename + " is gazebo_ros's own, which car's node is: nothing to load", line});
    return "";
  }
  const auto dirs = shared_plugin_search_path();
  const std::string path = find_shared_plugin(filename, dirs);
  if (path.empty())
    diagnostics->push_back({Severity::Warning, "plugin-unknown", where,
                            "Failed to load plugin " + filename +
                                ": no such file in GAZEBO_PLUGIN_PATH, the ROS library folders or LD_LIBRARY_PATH "
                                "(searched: " + joined(dirs) + "); " + owner + " goes on without it",
                            line});
  return path;
}

std::vector<std::unique_ptr<SharedPlugin>> load_world_plugins(World& world, const std::vector<PluginSpec>& specs,
                                                              std::vector<Diagnostic>* diagnostics) {
  std::vector<std::unique_ptr<SharedPlugin>> out;
  const std::string owner = "world '" + world.description().name + "'";
  for (const auto& spec : specs) {
    const std::string where = "world/plugin[" + spec.name + "]";
    const std::string path = locate_plugin(spec.filename, owner, where, spec.line, diagnostics);
    if (path.empty()) continue;
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
  const std::string path = locate_plugin(filename, "the server", where, 0, diagnostics);
  if (path.empty()) return nullptr;
  SharedPluginContext ctx;
  ctx.world = &world;
  ctx.place = PluginPlace::System;
  ctx.args = args;
  ctx.name = filename;
  ctx.filename = filename;
  ctx.path = path;
  return open_plugin(ctx, "the server", where, diagnostics);
}

namespace {

struct Feed {
  const char* type;
  const char* file;  // the file of car's kind that measures it
};
// Gazebo's sensor types the API offers, each measured by car's kind for the gazebo_ros plug-in of that type
const Feed kFeeds[] = {
    {"ray", "libgazebo_ros_laser.so"},          {"gpu_ray", "libgazebo_ros_gpu_laser.so"},
    {"contact", "libgazebo_ros_bumper.so"},     {"imu", "libgazebo_ros_imu_sensor.so"},
    {"camera", "libgazebo_ros_camera.so"},      {"depth", "libgazebo_ros_depth_camera.so"},
};

}  // namespace

std::string sensor_feed_file(const std::string& sensor_type) {
  for (const Feed& f : kFeeds)
    if (sensor_type == f.type) return f.file;
  return "";
}

ParamList sensor_feed_params(const SensorSpec& sensor) {
  if (sensor.type == "imu")
    return {{"frameName", sensor.link}, {"updateRateHZ", "0"}, {"initialOrientationAsReference", "true"}};
  return {};
}

const PluginKind* sensor_feed_kind(const std::string& sensor_type) {
  const std::string file = sensor_feed_file(sensor_type);
  if (file.empty()) return nullptr;
  for (const PluginKind* k : plugin_kinds())
    for (const auto& f : k->filenames)
      if (f == file) return k;
  return nullptr;
}

const PluginKind& shared_library_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "shared_library";
    k.any_keys = true;
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) {
      return std::unique_ptr<Plugin>(std::make_unique<SharedLibraryPlugin>(c, robot, seed));
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
