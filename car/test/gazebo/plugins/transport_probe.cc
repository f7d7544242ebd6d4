// Test plug-in for car's transport (docs/PLUGINS.md "Transport"): a msgs::Vector3d topic ~/MODEL/vel_cmd, as the
// velodyne tutorial's plug-in subscribes it; what it received goes to a log the test reads through
// car_test_transport_log(), as X@ITERATIONS (the world's Iterations when the callback ran).
//   deliver:      subscribes in Load; publishes x = 1 and x = 2 in the first two WorldUpdateBegins, logging
//                 "sent" right after each Publish.
//   latch:        publishes x = 5 in Load before anyone subscribes, then subscribes twice: latching (logs L) and not
//                 (logs N).
//   unsubscribe:  subscribes, then resets the SubscriberPtr; publishes x = 3 in the first WorldUpdateBegin.
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>
#include <gazebo/transport/transport.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(transport)

namespace gazebo {
class TransportProbe : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr _sdf) override {
    world = _model->GetWorld();
    const std::string mode = _sdf->Get<std::string>("mode");
    const std::string topic = "~/" + _model->GetName() + "/vel_cmd";
    node = transport::NodePtr(new transport::Node());
    node->Init(world->Name());
    pub = node->Advertise<msgs::Vector3d>(topic);
    if (mode == "latch") {
      msgs::Vector3d five;
      five.set_x(5);
      pub->Publish(five);
      latched = node->Subscribe(topic, &TransportProbe::OnLatched, this, true);
      plain = node->Subscribe(topic, &TransportProbe::OnMsg, this);
      return;
    }
    plain = node->Subscribe(topic, &TransportProbe::OnMsg, this);
    if (mode == "unsubscribe") plain.reset();
    update = event::Events::ConnectWorldUpdateBegin([this, mode](const common::UpdateInfo&) {
      ++steps;
      if (steps > 2 || (mode == "unsubscribe" && steps > 1)) return;
      msgs::Vector3d v;
      v.set_x(mode == "unsubscribe" ? 3 : steps);
      pub->Publish(v);
      g_log << "sent ";
    });
  }

  void OnMsg(ConstVector3dPtr& _msg) { g_log << "N" << _msg->x() << "@" << world->Iterations() << " "; }
  void OnLatched(ConstVector3dPtr& _msg) { g_log << "L" << _msg->x() << "@" << world->Iterations() << " "; }

 private:
  physics::WorldPtr world;
  transport::NodePtr node;
  transport::PublisherPtr pub;
  transport::SubscriberPtr plain, latched;
  event::ConnectionPtr update;
  int steps = 0;
};
GZ_REGISTER_MODEL_PLUGIN(TransportProbe)
}  // namespace gazebo
