// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::physics::Base, what Model, Link (through Entity) and Joint share
// (Gazebo 11's gazebo/physics/Base.hh): a name, a parent, a type. car's entities are handles made by car_gazebo
// (no constructor is offered); the world's root element is a Base named after the world, the models' parent.
#pragma once

#include <boost/enable_shared_from_this.hpp>
#include <boost/weak_ptr.hpp>
#include <string>

#include "gazebo/physics/PhysicsTypes.hh"

namespace gazebo {
namespace physics {

class Base : public boost::enable_shared_from_this<Base> {
 public:
  // Gazebo 11's type bits; car's entities carry BASE, ENTITY, MODEL, LINK, JOINT, HINGE_JOINT and SLIDER_JOINT.
  enum EntityType {
    BASE = 0x00000000,
    ENTITY = 0x00000001,
    MODEL = 0x00000002,
    LINK = 0x00000004,
    COLLISION = 0x00000008,
    LIGHT = 0x00000010,
    VISUAL = 0x00000020,
    JOINT = 0x00000040,
    BALL_JOINT = 0x00000080,
    HINGE2_JOINT = 0x00000100,
    HINGE_JOINT = 0x00000200,
    SLIDER_JOINT = 0x00000400,
    SCREW_JOINT = 0x00000800,
    UNIVERSAL_JOINT = 0x00001000,
    GEARBOX_JOINT = 0x00002000,
    FIXED_JOINT = 0x00004000,
    ACTOR = 0x00008000,
    SHAPE = 0x00010000,
    BOX_SHAPE = 0x00020000,
    CYLINDER_SHAPE = 0x00040000,
    HEIGHTMAP_SHAPE = 0x00080000,
    MAP_SHAPE = 0x00100000,
    MULTIRAY_SHAPE = 0x00200000,
    RAY_SHAPE = 0x00400000,
    PLANE_SHAPE = 0x00800000,
    SPHERE_SHAPE = 0x01000000,
    MESH_SHAPE = 0x02000000,
    POLYLINE_SHAPE = 0x04000000,
    SENSOR_COLLISION = 0x10000000
  };

  virtual ~Base();

  std::string GetName() const;
  // MODEL::NAME (a model: its name), with WORLD:: in front when _prependWorldName.
  std::string GetScopedName(bool _prependWorldName = false) const;
  // A model's: the world's root element; a link's or joint's: its model.
  BasePtr GetParent() const;
  WorldPtr GetWorld() const;
  // Whether every bit of _t is in this entity's type (BASE: always).
  bool HasType(const EntityType& _t) const;
  // The type bits.
  unsigned int GetType() const;

 protected:
  // car: made by car_gazebo only.
  explicit Base(BasePtr _parent);
  void AddType(EntityType _type);

  std::string name;
  boost::weak_ptr<World> world;

 private:
  boost::weak_ptr<Base> parentBase;
  unsigned int type = BASE;
};

}  // namespace physics
}  // namespace gazebo
