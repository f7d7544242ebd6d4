// Test plug-in: a system plug-in that prints its command line on Load and "init" on Init.
#include <gazebo/common/Plugin.hh>
#include <gazebo/gazebo.hh>

#include <cstdio>

namespace gazebo {
class SystemArgs : public SystemPlugin {
 public:
  void Load(int _argc, char** _argv) override {
    printf("system plug-in: %d args:", _argc);
    for (int i = 0; i < _argc; ++i) printf(" %s", _argv[i]);
    printf("\n");
  }
  void Init() override { printf("system plug-in: init\n"); }
};
GZ_REGISTER_SYSTEM_PLUGIN(SystemArgs)
}  // namespace gazebo
