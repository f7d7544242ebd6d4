// Plug-ins from shared libraries: a robot's <plugin filename> that is none of car's kinds and names a file on the
// search path is dlopened by the plug-in table's one entry for them (src/plugins/shared_library/), which hands the
// library's factory to the skin that runs its API (src/gazebo/: Gazebo 11's C++ plug-in API, library car_gazebo).
// No Gazebo header here: the core knows the skin only through SharedPluginHost.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "car_sim/model.hpp"

namespace car_sim {

class World;
struct Output;
struct PluginKind;

// Where a plug-in from a library sits, which says the class its RegisterPlugin must make (Gazebo's PluginType).
enum class PluginPlace {
  Model,   // a robot's <plugin>: a ModelPlugin, Load(model, sdf)
  World,   // a <plugin> directly in <world>: a WorldPlugin, Load(world, sdf)
  System,  // gzserver's -s FILE: a SystemPlugin, Load(argc, argv)
};

// What a plug-in from a library is loaded with.
struct SharedPluginContext {
  World* world = nullptr;
  PluginPlace place = PluginPlace::Model;
  std::vector<std::string> args;  // a system plug-in's argv (the server's command line)
  std::string model;     // the robot it belongs to (a model plug-in)
  std::string name;      // <plugin name>
  std::string filename;  // <plugin filename>, as written
  std::string path;      // the file loaded
  ParamList params;      // the <plugin>'s elements, flattened ("a/b" for <a><b>)
  std::string xml;       // the <plugin> element as written, when known (a world's): its sdf keeps order and repeats
  // A sensor's plug-in, or a sensor with no plug-in that Gazebo's sensors API offers (filename ""): the <sensor>
  // it belongs to (in_sensor true). Its samples come from car's own kind for the sensor's type (sensor_feed_kind).
  bool in_sensor = false;
  SensorSpec sensor;
  ParamList sensor_keys;  // the sensor's keys as that kind resolved them, its defaults filled in ("ray/range/max")
};

// A running plug-in, held by the skin; destroyed with its model (unload).
class SharedPlugin {
 public:
  virtual ~SharedPlugin() = default;
  // reset_world and reset_simulation: the plug-in's Reset.
  virtual void reset() = 0;
  // A sensor's: whether it measures now (Gazebo's Sensor::IsActive); while not, car's kind is not run for it.
  virtual bool sensor_active() const { return false; }
  // A sensor's: a measurement at `tick` (the tick reached), when its update_rate is due and it is active; `sample`
  // is the output car's kind made for it (nullptr when it made none).
  virtual void sensor_update(uint64_t tick, const Output* sample) {}
};

// The skin that runs a library's plug-ins. load() calls the factory `register_fn` (the library's RegisterPlugin)
// and the plug-in's Load and Init; it throws std::runtime_error with the reason when they fail.
class SharedPluginHost {
 public:
  virtual ~SharedPluginHost() = default;
  // For a sensor (ctx.in_sensor) it makes the sensor and, when register_fn is not null, loads the sensor's plug-in.
  virtual std::unique_ptr<SharedPlugin> load(void* register_fn, const SharedPluginContext& ctx) = 0;
};

// The world's own <plugin>s that none of car's kinds serves, in order: each found on the search path, dlopened, its
// RegisterPlugin handed to the host with PluginPlace::World. What fails is a diagnostic, and the world goes on.
std::vector<std::unique_ptr<SharedPlugin>> load_world_plugins(World& world, const std::vector<PluginSpec>& specs,
                                                              std::vector<Diagnostic>* diagnostics);
// A system plug-in (PluginPlace::System) by file name, the same way.
std::unique_ptr<SharedPlugin> load_system_plugin(World& world, const std::string& filename,
                                                 const std::vector<std::string>& args,
                                                 std::vector<Diagnostic>* diagnostics);

// The host: car_gazebo registers itself when it is loaded (as the dependency of a plug-in's library, or linked).
void set_shared_plugin_host(SharedPluginHost* host);
SharedPluginHost* shared_plugin_host();

// Where a plug-in file is looked for, in order, as Gazebo with ROS does: the folders of GAZEBO_PLUGIN_PATH, then
// the ROS library folders (each CMAKE_PREFIX_PATH entry's lib/), then LD_LIBRARY_PATH's (empty entries dropped,
// a folder named twice searched once, where it first comes).
std::vector<std::string> shared_plugin_search_path();
// The switch for a file name car simulates natively: listed in CAR_UPSTREAM_PLUGINS (names separated by ':' or ','),
// it loads from its library when one is found on the search path, instead of car's kind.
bool upstream_plugin_wanted(const std::string& filename);
// The file for a <plugin filename>: an absolute path as it is when it exists, else the first folder of `dirs` that
// has it; "" when none has.
std::string find_shared_plugin(const std::string& filename, const std::vector<std::string>& dirs);

// The kind of car's own that measures for Gazebo's sensors API on a <sensor type> (ray and gpu_ray: laser; contact:
// bumper; imu: imu_sensor; camera: camera; depth: depth_camera), and the file name it is resolved as; nullptr and ""
// for a type the API does not offer.
const PluginKind* sensor_feed_kind(const std::string& sensor_type);
std::string sensor_feed_file(const std::string& sensor_type);

}  // namespace car_sim
