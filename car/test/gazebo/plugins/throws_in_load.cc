// Test plug-in whose Load throws, as a plug-in that finds its SDF wrong does (gzthrow).
#include <gazebo/gazebo.hh>

#include <stdexcept>

namespace gazebo {
class ThrowsInLoad : public ModelPlugin {
 public:
  void Load(physics::ModelPtr, sdf::ElementPtr) override { throw std::runtime_error("no <link> given"); }
};
GZ_REGISTER_MODEL_PLUGIN(ThrowsInLoad)
}  // namespace gazebo
