// car's Gazebo 11 API (docs/PLUGINS.md): the physics classes' pointer types, boost::shared_ptr as in Gazebo 11.
#pragma once

#include <boost/shared_ptr.hpp>
#include <vector>

namespace gazebo {
namespace physics {

class Base;
class Entity;
class World;
class Model;
class Link;
class Joint;
class JointController;
class Inertial;
class PhysicsEngine;

typedef boost::shared_ptr<Base> BasePtr;
typedef boost::shared_ptr<Entity> EntityPtr;
typedef boost::shared_ptr<World> WorldPtr;
typedef boost::shared_ptr<Model> ModelPtr;
typedef boost::shared_ptr<Link> LinkPtr;
typedef boost::shared_ptr<Joint> JointPtr;
typedef boost::shared_ptr<JointController> JointControllerPtr;
typedef boost::shared_ptr<Inertial> InertialPtr;
typedef boost::shared_ptr<PhysicsEngine> PhysicsEnginePtr;

typedef std::vector<ModelPtr> Model_V;
typedef std::vector<LinkPtr> Link_V;
typedef std::vector<JointPtr> Joint_V;

}  // namespace physics
}  // namespace gazebo
