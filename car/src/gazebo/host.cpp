// car_gazebo's host: runs the model plug-ins car's plug-in table loads from libraries (car_sim/shared_plugin.hpp)
// and raises Gazebo's update events from two step hooks on car's world, in Gazebo 11's order: WorldUpdateBegin
// (sim time counting the coming step), the models' joint controllers, BeforePhysicsUpdate (physics enabled), the
// physics step, WorldUpdateEnd. docs/PLUGINS.md.
#include <dirent.h>
#include <sys/types.h>
#include <unistd.h>

#include <boost/make_shared.hpp>

#include <chrono>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "car_sim/shared_plugin.hpp"
#include "car_sim/world.hpp"
#include "gazebo/common/Events.hh"
#include "gazebo/common/Exception.hh"
#include "gazebo/common/Plugin.hh"
#include "gazebo/physics/Model.hh"
#include "gazebo/physics/World.hh"
#include "gazebo/sensors/sensors.hh"
#include "hub.hpp"

namespace car_gazebo {

namespace {

std::map<car_sim::World*, std::weak_ptr<Hub>>& hubs() {
  static std::map<car_sim::World*, std::weak_ptr<Hub>> m;
  return m;
}

thread_local Hub* g_current = nullptr;
thread_local const void* g_owner = nullptr;

}  // namespace

const void*& current_owner() { return g_owner; }

gazebo::common::Time time_of(uint64_t tick, double dt) {
  const int64_t ns = car_sim::tick_time_ns(tick, dt);
  return gazebo::common::Time(static_cast<int32_t>(ns / 1000000000), static_cast<int32_t>(ns % 1000000000));
}

Hub::Hub(car_sim::World* c) : core(c), world(new gazebo::physics::World(c)) {
  info_.worldName = core->description().name;
  before_hook_ = core->add_step_hook(car_sim::World::StepPhase::BeforePhysics, [this](uint64_t t) { before_physics(t); });
  after_hook_ = core->add_step_hook(car_sim::World::StepPhase::AfterPhysics, [this](uint64_t t) { after_physics(t); });
  pause_hook_ = core->add_pause_hook([this](bool p) {
    CurrentHub in(this);
    pause.fire(p);
  });
  // event::Events::timeReset: the core's reset_time and reset (Gazebo's World::ResetTime, which World::Reset calls)
  time_reset_hook_ = core->add_time_reset_hook([this] {
    CurrentHub in(this);
    time_reset.fire();
  });
  stop_hook_ = core->add_stop_hook([this] {
    // the parked plug-ins may hold the last references to this hub
    std::shared_ptr<Hub> self = shared_from_this();
    CurrentHub in(this);
    stop.fire();
    stopping = true;
    parked.clear();
  });
}

Hub::~Hub() {
  for (uint64_t id : {before_hook_, after_hook_, pause_hook_, stop_hook_, time_reset_hook_}) core->remove_step_hook(id);
  hubs().erase(core);
}

Hub* Hub::named(const std::string& name) {
  Hub* cur = current();
  if (name.empty() || (cur && cur->world->Name() == name)) return cur;
  for (auto& [core, weak] : hubs())
    if (auto h = weak.lock())
      if (h->world->Name() == name) return h.get();
  return nullptr;
}

std::shared_ptr<Hub> Hub::of(car_sim::World* core) {
  auto& m = hubs();
  if (auto h = m[core].lock()) return h;
  auto h = std::make_shared<Hub>(core);
  m[core] = h;
  return h;
}

Hub* Hub::current() {
  if (g_current) return g_current;
  auto& m = hubs();
  if (m.size() == 1)
    if (auto h = m.begin()->second.lock()) return h.get();
  return nullptr;
}

CurrentHub::CurrentHub(Hub* hub) : previous_(g_current) { g_current = hub; }
CurrentHub::~CurrentHub() { g_current = previous_; }

void Hub::before_physics(uint64_t tick) {
  CurrentHub in(this);
  // Gazebo counts the step in sim time before it raises WorldUpdateBegin
  info_.simTime = time_of(tick + 1, core->dt());
  info_.realTime = info_.simTime;
  world->SetInStep(true);
  in_step = true;
  try {
    begin.fire(info_);
    world->UpdateControllers();
    if (core->physics_enabled()) before.fire(info_);
  } catch (...) {
    world->SetInStep(false);
    in_step = false;
    throw;
  }
  world->SetInStep(false);
  in_step = false;
}

void Hub::after_physics(uint64_t) {
  CurrentHub in(this);
  in_step = true;
  try {
    if (core->physics_enabled()) islands.fire();
    end.fire();
  } catch (...) {
    in_step = false;
    throw;
  }
  in_step = false;
}

namespace {

// The <plugin> element with its children as written (flattened keys "a/b" back to nested elements), each a string
// value as sdformat keeps a plug-in's elements: Get<double>, Get<ignition::math::Vector3d>, ... parse it.
sdf::ElementPtr plugin_sdf(const car_sim::SharedPluginContext& ctx) {
  // the element as written, when the loader kept it (a world's plug-ins): sdformat copies a <plugin>'s children in
  // order, repeats and attributes included, each value a string, as Gazebo's World::LoadPlugin receives them
  if (!ctx.xml.empty()) {
    sdf::SDFPtr doc(new sdf::SDF());
    sdf::init(doc);
    if (sdf::readString("<sdf version='1.6'><world name='w'>" + ctx.xml + "</world></sdf>", doc)) {
      sdf::ElementPtr w = doc->Root()->GetElement("world");
      if (w->HasElement("plugin")) return w->GetElement("plugin");
    }
  }
  auto e = std::make_shared<sdf::Element>();
  e->SetName("plugin");
  e->AddAttribute("name", "string", "", true);
  e->AddAttribute("filename", "string", "", true);
  e->GetAttribute("name")->SetFromString(ctx.name);
  e->GetAttribute("filename")->SetFromString(ctx.filename);
  for (const auto& [key, value] : ctx.params) {
    sdf::ElementPtr at = e;
    std::stringstream ss(key);
    std::string part;
    std::vector<std::string> parts;
    while (std::getline(ss, part, '/')) parts.push_back(part);
    for (size_t i = 0; i < parts.size(); ++i) {
      const bool leaf = i + 1 == parts.size();
      sdf::ElementPtr next = leaf || !at->HasElement(parts[i]) ? nullptr : at->GetElement(parts[i]);
      if (!next) {
        next = std::make_shared<sdf::Element>();
        next->SetName(parts[i]);
        next->SetParent(at);
        at->InsertElement(next);
      }
      if (leaf) next->AddValue("string", value, false);
      at = next;
    }
  }
  return e;
}

// The <plugin> element's parent, as Gazebo's: the <model name> (a sensor's plug-in: the <sensor name type>), which
// plug-ins read through _sdf->GetParent() (Kobuki's takes its model's name so). Its holder keeps it alive: an
// element holds its parent weakly.
sdf::ElementPtr plugin_parent(const car_sim::SharedPluginContext& ctx, const sdf::ElementPtr& plugin) {
  auto p = std::make_shared<sdf::Element>();
  p->SetName(ctx.in_sensor ? "sensor" : "model");
  p->AddAttribute("name", "string", "", true);
  p->GetAttribute("name")->SetFromString(ctx.in_sensor ? ctx.sensor.name : ctx.model);
  if (ctx.in_sensor) {
    p->AddAttribute("type", "string", "", true);
    p->GetAttribute("type")->SetFromString(ctx.sensor.type);
  }
  plugin->SetParent(p);
  p->InsertElement(plugin);
  return p;
}

// ---- plug-ins' own threads -----------------------------------------------------------------------------------
// Upstream gazebo_plugins' drives start a thread in Load that serves their own ros::CallbackQueue while ros::ok()
// (and a flag only their FiniChild clears, which Gazebo 11 never calls); some destructors join it, some do not.
// Gazebo deletes a model's plug-ins at once (Model::Fini); gzserver's end runs ros::shutdown (gazebo_ros's SigInt
// event) before the world's Fini deletes them. car records the threads each plug-in starts in its Load and Init
// (the process's thread ids before and after, /proc/self/task) and deletes a plug-in only once they have ended, or
// at the world's end (docs/COMPAT-plugins.md "Plug-ins' threads").

std::set<pid_t> thread_ids() {
  std::set<pid_t> ids;
  if (DIR* d = opendir("/proc/self/task")) {
    while (dirent* e = readdir(d))
      if (e->d_name[0] != '.') ids.insert(static_cast<pid_t>(std::stol(e->d_name)));
    closedir(d);
  }
  return ids;
}

bool running(pid_t tid) { return access(("/proc/self/task/" + std::to_string(tid)).c_str(), F_OK) == 0; }

bool any_running(const std::vector<pid_t>& tids) {
  for (pid_t t : tids)
    if (running(t)) return true;
  return false;
}

// Waits for threads to end, at most `limit` of wall time; whether they did.
bool wait_ended(const std::vector<pid_t>& tids, std::chrono::milliseconds limit) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (any_running(tids)) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

// The threads started while `fn` ran.
template <class Fn>
std::vector<pid_t> threads_started(Fn&& fn) {
  const std::set<pid_t> before = thread_ids();
  fn();
  std::vector<pid_t> started;
  for (pid_t t : thread_ids())
    if (!before.count(t)) started.push_back(t);
  return started;
}

// How long the world's end waits for a plug-in's threads: upstream's callback-queue threads look at ros::ok() every
// 10 ms (a CallbackQueue::callAvailable timeout of 0.01 s)
constexpr std::chrono::milliseconds kThreadEndLimit{2000};

// A plug-in deleted once its threads have ended: at once when they have, else after waiting for them (the world's
// end, where the node has shut roscpp down before), else, while the world goes on, kept in the hub ("parked") with
// its callbacks cut, until the world's end.
template <class Plugin>
void delete_plugin(const std::shared_ptr<Hub>& hub, std::unique_ptr<Plugin>& plugin, const void* owner,
                   const std::vector<pid_t>& threads, const std::string& what, std::shared_ptr<void> keep) {
  if (!plugin) return;
  CurrentHub in(hub.get());
  if (any_running(threads)) {
    if (!hub->stopping) {
      hub->disconnect_owner(owner);
      struct Parked {
        std::shared_ptr<Hub> hub;
        std::unique_ptr<Plugin> plugin;
        std::vector<pid_t> threads;
        std::string what;
        std::shared_ptr<void> keep;
        ~Parked() {
          CurrentHub in(hub.get());
          if (!wait_ended(threads, kThreadEndLimit))
            std::cerr << "[Wrn] car: " << what << ": its threads still run " << kThreadEndLimit.count()
                      << " ms after the world's end; it is deleted anyway" << std::endl;
          plugin.reset();
        }
      };
      auto parked = std::make_shared<Parked>();
      parked->hub = hub;
      parked->plugin = std::move(plugin);
      parked->threads = threads;
      parked->what = what;
      parked->keep = std::move(keep);
      hub->parked.push_back(std::move(parked));
      return;
    }
    if (!wait_ended(threads, kThreadEndLimit))
      std::cerr << "[Wrn] car: " << what << ": its threads still run " << kThreadEndLimit.count()
                << " ms after the world's end; it is deleted anyway" << std::endl;
  }
  plugin.reset();  // its connections go with it, while the hub is there
}

// A plug-in (model, world or system) with what keeps its world's events going while it lives.
class Running : public car_sim::SharedPlugin {
 public:
  ~Running() override {
    // the model handle and the SDF stay with a parked plug-in (it may still read them)
    delete_plugin(hub, plugin, this, threads, what,
                  std::make_shared<std::pair<gazebo::physics::ModelPtr, sdf::ElementPtr>>(model, sdf_parent));
  }
  void reset() override {
    CurrentHub in(hub.get());
    CurrentOwner as(this);
    if (do_reset) do_reset();
  }
  // the threads its Load and Init started; what it is, for messages
  std::vector<pid_t> threads;
  std::string what;
  std::shared_ptr<Hub> hub;
  gazebo::physics::ModelPtr model;
  sdf::ElementPtr sdf_parent;
  std::unique_ptr<gazebo::PluginBase> plugin;
  std::function<void()> do_reset;
  // a system plug-in's argv: it may keep the pointers, as gzserver's live as long as the process
  std::vector<std::string> args;
  std::vector<char*> argv;
};

// What a library's RegisterPlugin made, in the words of its registration macro.
std::string kind_of(gazebo::PluginBase* p) {
  if (dynamic_cast<gazebo::ModelPlugin*>(p)) return "a model plug-in (GZ_REGISTER_MODEL_PLUGIN)";
  if (dynamic_cast<gazebo::WorldPlugin*>(p)) return "a world plug-in (GZ_REGISTER_WORLD_PLUGIN)";
  if (dynamic_cast<gazebo::SystemPlugin*>(p)) return "a system plug-in (GZ_REGISTER_SYSTEM_PLUGIN)";
  if (dynamic_cast<gazebo::SensorPlugin*>(p)) return "a sensor plug-in (GZ_REGISTER_SENSOR_PLUGIN)";
  return "a plug-in of a type car does not load here";
}

// Gazebo's message for a plug-in of the wrong type (Model::LoadPlugin, World::LoadPlugin, gazebo::addPlugin), and
// what it is and what the place takes.
std::runtime_error wrong_type(const std::string& who, const car_sim::SharedPluginContext& ctx, gazebo::PluginBase* p,
                              const std::string& takes) {
  return std::runtime_error(who + " is attempting to load a plugin, but detected an incorrect plugin type. Plugin filename[" +
                            ctx.filename + "] name[" + ctx.name + "]: it is " + kind_of(p) + "; " + takes);
}

// Load and Init, an exception out of them a runtime_error saying so.
template <class Fn>
void guarded(Fn&& fn) {
  try {
    fn();
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("Load threw: ") + e.what());
  } catch (const gazebo::common::Exception& e) {
    // gzthrow's text ends in a newline
    std::string what = e.GetErrorStr();
    while (!what.empty() && what.back() == '\n') what.pop_back();
    throw std::runtime_error("Load threw: " + what);
  } catch (...) {
    throw std::runtime_error("Load threw an exception that is not a std::exception");
  }
}

// A sensor offered to Gazebo's sensors API, with its plug-in when it has one; in SensorManager while it lives.
class RunningSensor : public car_sim::SharedPlugin {
 public:
  ~RunningSensor() override {
    CurrentHub in(hub.get());
    plugin.reset();
    if (sensor) gazebo::sensors::SensorManager::Instance()->CarRemove(sensor);
  }
  void reset() override {
    CurrentHub in(hub.get());
    if (plugin) plugin->Reset();
  }
  bool sensor_active() const override { return sensor->IsActive(); }
  void sensor_update(uint64_t tick, const car_sim::Output* sample) override {
    CurrentHub in(hub.get());
    sensor->CarUpdate(time_of(tick, hub->core->dt()), sample);
  }
  std::shared_ptr<Hub> hub;
  gazebo::sensors::SensorPtr sensor;
  sdf::ElementPtr sdf_parent;
  std::unique_ptr<gazebo::SensorPlugin> plugin;
};

// The sensor class for a <sensor type> (the types car_sim::sensor_feed_kind serves).
gazebo::sensors::SensorPtr make_sensor(const car_sim::SharedPluginContext& ctx) {
  namespace gs = gazebo::sensors;
  const std::string world = ctx.world->description().name;
  const std::string& t = ctx.sensor.type;
  if (t == "ray" || t == "gpu_ray") return std::make_shared<gs::RaySensor>(ctx.sensor, world, ctx.model, ctx.sensor_keys);
  if (t == "contact") return std::make_shared<gs::ContactSensor>(ctx.sensor, world, ctx.model, ctx.sensor_keys);
  if (t == "imu") return std::make_shared<gs::ImuSensor>(ctx.sensor, world, ctx.model, ctx.sensor_keys);
  if (t == "camera") return std::make_shared<gs::CameraSensor>(ctx.sensor, world, ctx.model, ctx.sensor_keys);
  if (t == "depth") return std::make_shared<gs::DepthCameraSensor>(ctx.sensor, world, ctx.model, ctx.sensor_keys);
  throw std::runtime_error("sensor type '" + t + "' is not offered by car's Gazebo sensors API");
}

// The plug-in a library's RegisterPlugin makes. Its declared return type depends on the registration macro
// (ModelPlugin*, WorldPlugin*, SystemPlugin*, SensorPlugin*: gazebo/common/Plugin.hh), and each of those derives
// PluginBase alone and first, so the pointer is its PluginBase's. It is called through one type, as Gazebo's
// PluginT::Create casts the symbol to the type it expects; UBSan's function-type check is off here for that only.
#if defined(__clang__)
__attribute__((no_sanitize("function")))
#endif
gazebo::PluginBase* make_plugin(void* register_fn) {
  using Factory = gazebo::PluginBase* (*)();
  return reinterpret_cast<Factory>(register_fn)();
}

class Host : public car_sim::SharedPluginHost {
 public:
  std::unique_ptr<car_sim::SharedPlugin> load(void* register_fn, const car_sim::SharedPluginContext& ctx) override {
    if (ctx.in_sensor) return load_sensor(register_fn, ctx);
    auto run = std::make_unique<Running>();
    run->hub = Hub::of(ctx.world);
    CurrentHub in(run->hub.get());
    CurrentOwner as(run.get());
    run->what = "plug-in '" + ctx.name + "' (" + ctx.filename + ")" +
                (ctx.place == car_sim::PluginPlace::Model ? " of model '" + ctx.model + "'" : std::string());
    run->plugin.reset(make_plugin(register_fn));
    if (!run->plugin) throw std::runtime_error("RegisterPlugin returned no plug-in");
    run->plugin->filename = ctx.filename;
    run->plugin->handleName = ctx.name;
    switch (ctx.place) {
      case car_sim::PluginPlace::Model: {
        auto* p = dynamic_cast<gazebo::ModelPlugin*>(run->plugin.get());
        if (!p)
          throw wrong_type("Model[" + ctx.model + "]", ctx, run->plugin.get(),
                           "a model's <plugin> takes a model plug-in (GZ_REGISTER_MODEL_PLUGIN)");
        run->model = run->hub->world->ModelByName(ctx.model);
        run->threads = threads_started([&] {
          guarded([&] {
            const sdf::ElementPtr sdf = plugin_sdf(ctx);
            run->sdf_parent = plugin_parent(ctx, sdf);
            p->Load(run->model, sdf);
            p->Init();
          });
        });
        run->do_reset = [p] { p->Reset(); };
        break;
      }
      case car_sim::PluginPlace::World: {
        auto* p = dynamic_cast<gazebo::WorldPlugin*>(run->plugin.get());
        if (!p)
          throw wrong_type("World[" + run->hub->world->Name() + "]", ctx, run->plugin.get(),
                           "a <plugin> in <world> takes a world plug-in (GZ_REGISTER_WORLD_PLUGIN)");
        run->threads = threads_started([&] {
          guarded([&] {
            p->Load(run->hub->world, plugin_sdf(ctx));
            p->Init();
          });
        });
        run->do_reset = [p] { p->Reset(); };
        break;
      }
      case car_sim::PluginPlace::System: {
        auto* p = dynamic_cast<gazebo::SystemPlugin*>(run->plugin.get());
        if (!p)
          throw wrong_type("System", ctx, run->plugin.get(),
                           "gzserver's -s takes a system plug-in (GZ_REGISTER_SYSTEM_PLUGIN)");
        run->args = ctx.args;
        for (auto& a : run->args) run->argv.push_back(a.data());
        run->argv.push_back(nullptr);
        run->threads = threads_started([&] {
          guarded([&] {
            p->Load(static_cast<int>(run->args.size()), run->argv.data());
            p->Init();
          });
        });
        break;
      }
    }
    return run;
  }

  // The sensor into SensorManager, then its plug-in (when it has one): Load(sensor, sdf) and Init(), as Gazebo's
  // Sensor::LoadPlugin.
  std::unique_ptr<car_sim::SharedPlugin> load_sensor(void* register_fn, const car_sim::SharedPluginContext& ctx) {
    auto run = std::make_unique<RunningSensor>();
    run->hub = Hub::of(ctx.world);
    CurrentHub in(run->hub.get());
    run->sensor = make_sensor(ctx);
    gazebo::sensors::SensorManager::Instance()->CarAdd(run->sensor);
    if (!register_fn) return run;
    std::unique_ptr<gazebo::PluginBase> made(make_plugin(register_fn));
    if (!made) throw std::runtime_error("RegisterPlugin returned no plug-in");
    auto* p = dynamic_cast<gazebo::SensorPlugin*>(made.get());
    if (!p)
      throw wrong_type("Sensor[" + ctx.sensor.name + "]", ctx, made.get(),
                       "a <plugin> in <sensor> takes a sensor plug-in (GZ_REGISTER_SENSOR_PLUGIN)");
    made.release();
    run->plugin.reset(p);
    run->plugin->filename = ctx.filename;
    run->plugin->handleName = ctx.name;
    guarded([&] {
      const sdf::ElementPtr sdf = plugin_sdf(ctx);
      run->sdf_parent = plugin_parent(ctx, sdf);
      run->plugin->Load(run->sensor, sdf);
      run->plugin->Init();
    });
    return run;
  }
};

Host g_host;

// registered as the library is loaded: as a plug-in's dependency (dlopen) or linked into a program
const bool g_registered = [] {
  car_sim::set_shared_plugin_host(&g_host);
  return true;
}();

}  // namespace

}  // namespace car_gazebo

namespace gazebo {
namespace event {

namespace {

car_gazebo::Hub& hub_for(const char* event) {
  car_gazebo::Hub* h = car_gazebo::Hub::current();
  if (!h)
    throw std::logic_error(std::string("event::Events::") + event +
                           " outside a plug-in's Load, Init, Reset or event, with several worlds: car cannot tell "
                           "which world it is for");
  return *h;
}

template <class List, class Fn>
ConnectionPtr connect(car_gazebo::Hub& h, List car_gazebo::Hub::*list, Fn fn) {
  const int id = (h.*list).connect(std::move(fn));
  std::weak_ptr<car_gazebo::Hub> weak = h.shared_from_this();
  return boost::make_shared<Connection>([weak, list, id] {
    if (auto hub = weak.lock()) ((*hub).*list).disconnect(id);
  });
}

}  // namespace

ConnectionPtr Events::ConnectWorldUpdateBegin(std::function<void(const common::UpdateInfo&)> _subscriber) {
  return connect(hub_for("ConnectWorldUpdateBegin"), &car_gazebo::Hub::begin, std::move(_subscriber));
}

ConnectionPtr Events::ConnectBeforePhysicsUpdate(std::function<void(const common::UpdateInfo&)> _subscriber) {
  return connect(hub_for("ConnectBeforePhysicsUpdate"), &car_gazebo::Hub::before, std::move(_subscriber));
}

ConnectionPtr Events::ConnectWorldUpdateEnd(std::function<void()> _subscriber) {
  return connect(hub_for("ConnectWorldUpdateEnd"), &car_gazebo::Hub::end, std::move(_subscriber));
}

ConnectionPtr Events::ConnectPause(std::function<void(bool)> _subscriber) {
  return connect(hub_for("ConnectPause"), &car_gazebo::Hub::pause, std::move(_subscriber));
}

ConnectionPtr Events::ConnectStop(std::function<void()> _subscriber) {
  return connect(hub_for("ConnectStop"), &car_gazebo::Hub::stop, std::move(_subscriber));
}

ConnectionPtr Events::ConnectTimeReset(std::function<void()> _subscriber) {
  return connect(hub_for("ConnectTimeReset"), &car_gazebo::Hub::time_reset, std::move(_subscriber));
}

}  // namespace event
}  // namespace gazebo
