// Test plug-in for msgs::ImageStamped over car's transport, common::Image's pixel formats and msgs::Time
// (docs/PLUGINS.md "Transport"). It includes only what PAL's RealSensePlugin.h includes, which in Gazebo 11 brings
// transport::Node, its Publisher, boost::bind with the global placeholders (_1) and the messages, so a missing
// include fails the build. Load logs ConvertPixelFormat of seven names and a msgs::Time round trip; the first
// WorldUpdateBegin (connected through boost::bind(..., _1)) publishes a 2 x 1 R8G8B8 image stamped with the sim time
// on ~/MODEL/image, which the plug-in itself subscribes; the log is read through car_test_camera_transport_log().
#include <gazebo/common/Plugin.hh>
#include <gazebo/common/common.hh>
#include <gazebo/physics/PhysicsTypes.hh>
#include <gazebo/physics/physics.hh>
#include <gazebo/rendering/DepthCamera.hh>
#include <gazebo/sensors/sensors.hh>

#include <sstream>
#include <string>

#include "event_log.hh"

CAR_TEST_PLUGIN_LOG(camera_transport)

namespace gazebo {
class CameraTransport : public ModelPlugin {
 public:
  void Load(physics::ModelPtr _model, sdf::ElementPtr) override {
    world = _model->GetWorld();
    for (const char* name : {"L8", "L_UINT16", "R8G8B8", "BGR_INT8", "FLOAT32", "BAYER_GRBG8", "RGB"})
      g_log << name << "=" << common::Image::ConvertPixelFormat(name) << " ";
    const common::Time t = msgs::Convert(msgs::Convert(common::Time(3, 250)));
    g_log << "time=" << t.sec << "." << t.nsec << " ";
    node = transport::NodePtr(new transport::Node());
    node->Init(world->Name());
    const std::string topic = "~/" + _model->GetName() + "/image";
    pub = node->Advertise<msgs::ImageStamped>(topic, 1, 30.0);
    sub = node->Subscribe(topic, &CameraTransport::OnImage, this);
    update = event::Events::ConnectWorldUpdateBegin(boost::bind(&CameraTransport::OnUpdate, this, _1));
  }

  void OnUpdate(const common::UpdateInfo&) {
    if (sent) return;
    sent = true;
    msgs::ImageStamped msg;
    msgs::Set(msg.mutable_time(), world->SimTime());
    msg.mutable_image()->set_width(2);
    msg.mutable_image()->set_height(1);
    msg.mutable_image()->set_pixel_format(common::Image::ConvertPixelFormat("R8G8B8"));
    msg.mutable_image()->set_step(6);
    msg.mutable_image()->set_data("abcdef", 6);
    pub->Publish(msg);
  }

  void OnImage(ConstImageStampedPtr& _msg) {
    const msgs::Image& i = _msg->image();
    g_log << "image=" << i.width() << "x" << i.height() << " format=" << i.pixel_format() << " step=" << i.step()
          << " stamp=" << _msg->time().sec() << "." << _msg->time().nsec() << " data=" << i.data()
          << " at=" << world->Iterations();
  }

 private:
  physics::WorldPtr world;
  transport::NodePtr node;
  transport::PublisherPtr pub;
  transport::SubscriberPtr sub;
  event::ConnectionPtr update;
  bool sent = false;
};
GZ_REGISTER_MODEL_PLUGIN(CameraTransport)
}  // namespace gazebo
