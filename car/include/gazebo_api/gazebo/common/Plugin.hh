// car's Gazebo 11 API (docs/PLUGINS.md): the plug-in base classes and their registration macros, as
// gazebo/common/Plugin.hh declares them. car's plug-in table (src/plugins/shared_library/) loads a library and
// car_gazebo runs what its RegisterPlugin makes: a ModelPlugin for a model's <plugin> (Load(model, sdf)), a
// WorldPlugin for a <plugin> in <world> (Load(world, sdf)), a SystemPlugin for gzserver's -s (Load(argc, argv)), a
// SensorPlugin for a <plugin> in a <sensor> (Load(sensor, sdf)); then Init(), the update events each step, Reset() on
// reset_world (models) and reset_simulation (all), deleted with what owns it. Visual and GUI plug-ins are not
// offered: their classes and macros are not declared, so such a plug-in does not build against car.
#pragma once

#include <sdf/sdf.hh>
#include <string>

#include "gazebo/common/CommonTypes.hh"
#include "gazebo/common/Console.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/sensors/SensorTypes.hh"

#define GZ_PLUGIN_VISIBLE __attribute__((visibility("default")))

namespace gazebo {

enum PluginType { WORLD_PLUGIN, MODEL_PLUGIN, SENSOR_PLUGIN, SYSTEM_PLUGIN, VISUAL_PLUGIN, GUI_PLUGIN };

// car: what every plug-in class shares, so that the loader can tell which class a library's RegisterPlugin made. Its
// destructor is car_gazebo's (not inline): every plug-in library then needs libcar_gazebo.so, even one that calls
// nothing of it (the hello world tutorial) and is linked --as-needed, so the API is there when the plug-in loads.
class PluginBase {
 public:
  virtual ~PluginBase();
  // car: set by the loader before Load.
  std::string filename;
  std::string handleName;

 protected:
  PluginType type = MODEL_PLUGIN;
};

template <class T>
class PluginT : public PluginBase {
 public:
  using TPtr = boost::shared_ptr<T>;
  PluginT() = default;
  virtual ~PluginT() = default;
  std::string GetFilename() const { return this->filename; }
  std::string GetHandle() const { return this->handleName; }
  PluginType GetType() const { return this->type; }

 protected:
  // _target = <_name> of _sdf when it has one, else _defaultValue (with a message, as upstream).
  template <typename V>
  void LoadParam(const sdf::ElementPtr& _sdf, const std::string& _name, V& _target, V _defaultValue = V()) const {
    auto result = _sdf->Get<V>(_name, _defaultValue);
    if (!result.second)
      gzmsg << this->handleName.c_str() << " Plugin missing <" << _name.c_str() << ">, defaults to " << result.first
            << std::endl;
    _target = result.first;
  }
  void LoadParam(sdf::ElementPtr& _sdf, const std::string& _name, std::string& _target,
                 const char* _defaultValue) const {
    this->LoadParam<std::string>(_sdf, _name, _target, _defaultValue);
  }
};

class ModelPlugin : public PluginT<ModelPlugin> {
 public:
  ModelPlugin() { this->type = MODEL_PLUGIN; }
  virtual ~ModelPlugin() {}
  virtual void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

class WorldPlugin : public PluginT<WorldPlugin> {
 public:
  WorldPlugin() { this->type = WORLD_PLUGIN; }
  virtual ~WorldPlugin() {}
  virtual void Load(physics::WorldPtr _world, sdf::ElementPtr _sdf) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

class SystemPlugin : public PluginT<SystemPlugin> {
 public:
  SystemPlugin() { this->type = SYSTEM_PLUGIN; }
  virtual ~SystemPlugin() {}
  virtual void Load(int _argc = 0, char** _argv = NULL) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

// A plug-in in a <sensor>: loaded with its sensor as parent, as Gazebo's Sensor::LoadPlugin.
class SensorPlugin : public PluginT<SensorPlugin> {
 public:
  SensorPlugin() { this->type = SENSOR_PLUGIN; }
  virtual ~SensorPlugin() {}
  virtual void Load(sensors::SensorPtr _sensor, sdf::ElementPtr _sdf) = 0;
  virtual void Init() {}
  virtual void Reset() {}
};

}  // namespace gazebo

#define GZ_REGISTER_WORLD_PLUGIN(classname)                                 \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::WorldPlugin* RegisterPlugin();       \
  gazebo::WorldPlugin* RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_SYSTEM_PLUGIN(classname)                                \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::SystemPlugin* RegisterPlugin();      \
  gazebo::SystemPlugin* RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_MODEL_PLUGIN(classname)                                 \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::ModelPlugin* RegisterPlugin();       \
  gazebo::ModelPlugin* RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_SENSOR_PLUGIN(classname)                                \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::SensorPlugin* RegisterPlugin();      \
  gazebo::SensorPlugin* RegisterPlugin() { return new classname(); }
