// Bench plug-in (bench_gazebo.cpp): a model plug-in whose WorldUpdateBegin callback does nothing but count its calls
// (one increment, so the bench can check every callback ran), so a step's extra cost with it connected is the
// Gazebo skin's dispatch (issue 49: at most 1 µs per callback).
#include <functional>
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>

// calls of every instance's callback, read by bench_gazebo through dlsym
extern "C" {
unsigned long car_bench_empty_update_calls = 0;
}

namespace gazebo {
class EmptyUpdate : public ModelPlugin {
 public:
  void Load(physics::ModelPtr /*_parent*/, sdf::ElementPtr /*_sdf*/) override {
    this->connection = event::Events::ConnectWorldUpdateBegin(std::bind(&EmptyUpdate::OnUpdate, this));
  }
  void OnUpdate() { ++car_bench_empty_update_calls; }

 private:
  event::ConnectionPtr connection;
};
GZ_REGISTER_MODEL_PLUGIN(EmptyUpdate)
}  // namespace gazebo
