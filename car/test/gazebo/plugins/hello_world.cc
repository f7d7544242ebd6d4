// Test plug-in in the style of Gazebo's hello_world tutorial, as a model plug-in: prints on Load.
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

#include <cstdio>

namespace gazebo {
class HelloWorld : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr /*_sdf*/) override {
    printf("Hello World! I am model '%s'\n", _model->GetName().c_str());
  }
};
GZ_REGISTER_MODEL_PLUGIN(HelloWorld)
}  // namespace gazebo
