// Test plug-in in the style of Gazebo's hello_world tutorial: a world plug-in that prints "Hello World!" on Load.
#include <gazebo/common/Plugin.hh>
#include <gazebo/gazebo.hh>

#include <cstdio>

namespace gazebo {
class WorldHello : public WorldPlugin {
 public:
  void Load(physics::WorldPtr /*_world*/, sdf::ElementPtr /*_sdf*/) override { printf("Hello World!\n"); }
};
GZ_REGISTER_WORLD_PLUGIN(WorldHello)
}  // namespace gazebo
