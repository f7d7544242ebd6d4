// Test plug-in of the rostest gazebo_ros_threads (docs/COMPAT-plugins.md "ROS time in car's node" and "Plug-ins'
// threads"). It is shaped as upstream gazebo_plugins' drives are (written for car, not their code): Load makes a
// ros::NodeHandle in the model's name, subscribes <model>/probe_command (std_msgs/Empty) on a ros::CallbackQueue of
// its own, and starts a boost::thread that serves that queue while the flag alive_ is set and the handle is ok; only
// Fini() would stop it, and nothing calls Fini (nor does Gazebo 11 call upstream's FiniChild); the destructor stops
// nothing. It only tells: deleted while the thread still serves, it prints "ros_thread_probe: deleted while its queue
// thread still serves" on stderr (the thread then runs on freed memory, as upstream's planar_move's would). Every WorldUpdateBegin publishes a sensor_msgs/TimeReference on <model>/probe_time: header.stamp is
// ros::Time::now() as the callback reads it, time_ref is World::SimTime().
#include <boost/bind/bind.hpp>
#include <boost/thread.hpp>
#include <gazebo/common/common.hh>
#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/TimeReference.h>
#include <std_msgs/Empty.h>

#include <atomic>
#include <cstdio>
#include <memory>

namespace {
// threads serving a probe's queue now (in the library: it outlives the plug-in objects)
std::atomic<int> g_serving{0};
}  // namespace

namespace gazebo {
class RosThreadProbe : public ModelPlugin {
 public:
  ~RosThreadProbe() override {
    if (g_serving.load() > 0) std::fprintf(stderr, "ros_thread_probe: deleted while its queue thread still serves\n");
  }

  void Load(physics::ModelPtr _model, sdf::ElementPtr) override {
    world_ = _model->GetWorld();
    node_ = std::make_unique<ros::NodeHandle>(_model->GetName());
    ros::SubscribeOptions so = ros::SubscribeOptions::create<std_msgs::Empty>(
        "probe_command", 1, boost::bind(&RosThreadProbe::OnCommand, this, boost::placeholders::_1), ros::VoidPtr(),
        &queue_);
    sub_ = node_->subscribe(so);
    // a queue as deep as a run's steps: the test reads every step's message
    pub_ = node_->advertise<sensor_msgs::TimeReference>("probe_time", 100000);
    alive_ = true;
    thread_ = boost::thread(boost::bind(&RosThreadProbe::Serve, this));
    update_ = event::Events::ConnectWorldUpdateBegin(boost::bind(&RosThreadProbe::OnUpdate, this));
  }

  // never called (Gazebo 11 has no such call: upstream's FiniChild is the same)
  void Fini() {
    alive_ = false;
    queue_.clear();
    queue_.disable();
    node_->shutdown();
    thread_.join();
  }

 private:
  void OnUpdate() {
    sensor_msgs::TimeReference m;
    m.header.stamp = ros::Time::now();
    const common::Time t = world_->SimTime();
    m.time_ref = ros::Time(t.sec, t.nsec);
    m.source = "WorldUpdateBegin";
    pub_.publish(m);
  }
  void OnCommand(const std_msgs::Empty::ConstPtr&) {}
  void Serve() {
    ++g_serving;
    while (alive_ && node_->ok()) queue_.callAvailable(ros::WallDuration(0.01));
    --g_serving;
  }

  physics::WorldPtr world_;
  std::unique_ptr<ros::NodeHandle> node_;
  ros::Subscriber sub_;
  ros::Publisher pub_;
  ros::CallbackQueue queue_;
  boost::thread thread_;
  std::atomic<bool> alive_{false};
  event::ConnectionPtr update_;
};
GZ_REGISTER_MODEL_PLUGIN(RosThreadProbe)
}  // namespace gazebo
