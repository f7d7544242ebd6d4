// car's Gazebo 11 API (docs/PLUGINS.md): the plug-in base classes and their registration macros. A library that
// registers a model plug-in is loaded by car's plug-in table (src/plugins/shared_library/) and run by car_gazebo:
// Load(model, sdf), Init(), the update events each step, Reset() on reset_world and reset_simulation, deleted with
// its model. A sensor plug-in (in a <sensor>) gets Load(sensor, sdf) and Init() with its sensor. World, system,
// visual and GUI plug-ins are not offered yet: their classes and macros are not declared, so such a plug-in does
// not build against car.
#pragma once

#include <sdf/sdf.hh>
#include <string>

#include "gazebo/common/Console.hh"
#include "gazebo/physics/PhysicsTypes.hh"
#include "gazebo/sensors/SensorTypes.hh"

#define GZ_PLUGIN_VISIBLE __attribute__((visibility("default")))

namespace gazebo {

enum PluginType { WORLD_PLUGIN, MODEL_PLUGIN, SENSOR_PLUGIN, SYSTEM_PLUGIN, VISUAL_PLUGIN, GUI_PLUGIN };

template <class T>
class PluginT {
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

 public:
  // car: set by the loader before Load.
  std::string filename;
  std::string handleName;

 protected:
  PluginType type = MODEL_PLUGIN;
};

class ModelPlugin : public PluginT<ModelPlugin> {
 public:
  ModelPlugin() { this->type = MODEL_PLUGIN; }
  virtual ~ModelPlugin() {}
  virtual void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) = 0;
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

#define GZ_REGISTER_MODEL_PLUGIN(classname)                                 \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::ModelPlugin* RegisterPlugin();       \
  gazebo::ModelPlugin* RegisterPlugin() { return new classname(); }

#define GZ_REGISTER_SENSOR_PLUGIN(classname)                                \
  extern "C" GZ_PLUGIN_VISIBLE gazebo::SensorPlugin* RegisterPlugin();      \
  gazebo::SensorPlugin* RegisterPlugin() { return new classname(); }
