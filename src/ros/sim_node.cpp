// car's simulator node: the ROS skin over car_sim::World. It paces the world against the wall clock (rtf),
// publishes /clock, runs Gazebo-style services under /gazebo, and maps plug-in outputs to messages.
// All maths lives in the core; this file maps parameters to structs and state to messages.
#include <car/DeleteModel.h>
#include <car/GetModelState.h>
#include <car/GetWorldProperties.h>
#include <car/ModelStates.h>
#include <car/SetModelState.h>
#include <car/SpawnModel.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/transform_broadcaster.h>

#include <malloc.h>

#include <chrono>
#include <cstring>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include "car_sim/world.hpp"
#include "conversions.hpp"

namespace car_ros {

using car_sim::World;

// Publishers of one sensor plug-in.
struct SensorIO {
  car_sim::SensorInfo info;
  std::string frame;
  ros::Publisher scan, image, info_pub, depth, depth_info, points, imu;
  double info_period = 0.0;  // [s] camera_info throttle (the plug-in's updateRate), 0 = with every image
  ros::Time last_info;
  bool active = false;

  bool listened() const {
    for (const ros::Publisher* p : {&scan, &image, &info_pub, &depth, &depth_info, &points, &imu})
      if (*p && p->getNumSubscribers() > 0) return true;
    return false;
  }
};

// Publishers and subscribers of one spawned robot.
struct RobotIO {
  struct Drive {
    ros::Subscriber cmd_vel;
    ros::Publisher odom;
    ros::Publisher wheel_joint_states;
    bool warned_publish_tf = false;
  };
  std::vector<Drive> drives;
  ros::Publisher joint_states;  // every non-fixed joint
  ros::Publisher ground_truth;
  std::vector<SensorIO> sensors;
};

class SimNode {
 public:
  SimNode() : nh_(), pnh_("~"), gz_("gazebo") {}

  bool init() {
    std::string world_file;
    pnh_.param<std::string>("world_name", world_file, "");
    pnh_.param("rtf", rtf_, 1.0);
    pnh_.param("paused", paused_, false);
    pnh_.param("clock_rate", clock_rate_, 100.0);
    pnh_.param("joint_state_rate", joint_state_rate_, 50.0);
    pnh_.param("model_states_rate", model_states_rate_, 100.0);
    pnh_.param("solver_iterations", solver_iterations_, 10);
    int seed = 0;
    pnh_.param("seed", seed, 0);
    if (!(rtf_ >= 0.0) || !std::isfinite(rtf_)) {
      ROS_FATAL("car: parameter ~rtf must be >= 0 (0 = as fast as possible), got %g", rtf_);
      return false;
    }
    car_sim::WorldOptions options;
    options.solver_iterations = solver_iterations_;
    options.seed = static_cast<uint64_t>(seed);
    try {
      world_ = std::make_unique<World>(world_file.empty() ? car_sim::empty_world() : car_sim::load_world_file(world_file),
                                       options);
    } catch (const car_sim::LoadError& e) {
      ROS_FATAL("car: cannot load the world: %s", e.what());
      return false;
    }
    nh_.setParam("/use_sim_time", true);
    log_world(world_file);

    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    model_states_pub_ = gz_.advertise<car::ModelStates>("model_states", 100);
    services_.push_back(gz_.advertiseService("spawn_urdf_model", &SimNode::spawn, this));
    services_.push_back(gz_.advertiseService("delete_model", &SimNode::remove, this));
    services_.push_back(gz_.advertiseService("get_model_state", &SimNode::get_state, this));
    services_.push_back(gz_.advertiseService("set_model_state", &SimNode::set_state, this));
    services_.push_back(gz_.advertiseService("get_world_properties", &SimNode::properties, this));
    services_.push_back(gz_.advertiseService("reset_simulation", &SimNode::reset_simulation, this));
    services_.push_back(gz_.advertiseService("reset_world", &SimNode::reset_world, this));
    services_.push_back(gz_.advertiseService("pause_physics", &SimNode::pause, this));
    services_.push_back(gz_.advertiseService("unpause_physics", &SimNode::unpause, this));
    publish_clock();
    return true;
  }

  void run() {
    using clock = std::chrono::steady_clock;
    auto wall0 = clock::now();
    uint64_t tick0 = world_->tick();
    bool was_paused = true;
    auto last_paused_clock = clock::now();
    while (ros::ok()) {
      ros::spinOnce();
      if (paused_) {
        was_paused = true;
        // keep /clock alive while paused, at 10 Hz of wall time
        if (clock::now() - last_paused_clock > std::chrono::milliseconds(100)) {
          publish_clock();
          last_paused_clock = clock::now();
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      if (was_paused || tick0 > world_->tick()) {
        // (re)start pacing after a pause or a reset
        wall0 = clock::now();
        tick0 = world_->tick();
        was_paused = false;
      }
      world_->step(1);
      publish_outputs();
      if (rtf_ > 0.0) {
        const double sim_elapsed = static_cast<double>(world_->tick() - tick0) * world_->dt();
        const auto due = wall0 + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(sim_elapsed / rtf_));
        if (due > clock::now()) std::this_thread::sleep_until(due);
      }
    }
  }

 private:
  uint64_t period_of(double rate) const {
    if (!(rate > 0.0)) return 1;
    return std::max<uint64_t>(1, std::llround(1.0 / (rate * world_->dt())));
  }

  void log_world(const std::string& file) {
    const auto& d = world_->description();
    int statics = 0;
    for (const auto& m : d.models) statics += m.is_static ? 1 : 0;
    ROS_INFO("car: world '%s' from %s: %zu models (%d static), step %g s, gravity (%g %g %g) m/s^2", d.name.c_str(),
             file.empty() ? "the built-in empty world" : file.c_str(), d.models.size(), statics, d.step_size,
             d.gravity.x(), d.gravity.y(), d.gravity.z());
    for (const auto& m : d.models)
      ROS_INFO("car:   model %-16s %s at (%.3f %.3f %.3f)", m.name.c_str(), m.is_static ? "static " : "dynamic",
               m.pose.translation().x(), m.pose.translation().y(), m.pose.translation().z());
    for (const auto& diag : d.diagnostics) ROS_WARN("car: %s: %s", diag.element.c_str(), diag.message.c_str());
    ROS_INFO("car: %s, real-time factor %s, solver %d iterations", paused_ ? "paused" : "running",
             rtf_ > 0 ? std::to_string(rtf_).c_str() : "0 (as fast as possible)", solver_iterations_);
  }

  void publish_clock() {
    rosgraph_msgs::Clock c;
    c.clock = sim_time(world_->tick(), world_->dt());
    clock_pub_.publish(c);
  }

  void publish_outputs() {
    const uint64_t tick = world_->tick();
    const ros::Time now = sim_time(tick, world_->dt());
    if (tick % period_of(clock_rate_) == 0) publish_clock();
    for (const auto& o : world_->take_odometry()) publish_odometry(o);
    // sensors compute only while someone listens; look every 50 steps
    if (tick % 50 == 0) update_sensor_activity();
    publish_sensors(world_->take_sensor_outputs());
    if (tick % period_of(joint_state_rate_) == 0) {
      for (const auto& name : world_->robot_names()) {
        if (io_[name].joint_states.getNumSubscribers() == 0) continue;
        sensor_msgs::JointState js;
        js.header.stamp = now;
        for (const auto& j : world_->joint_states(name)) {
          js.name.push_back(j.name);
          js.position.push_back(j.position);
          js.velocity.push_back(j.velocity);
        }
        io_[name].joint_states.publish(js);
      }
    }
    if (tick % period_of(model_states_rate_) == 0 && (model_states_pub_.getNumSubscribers() > 0 || ground_truth_listened())) {
      car::ModelStates ms;
      for (const auto& name : world_->model_names()) {
        const car_sim::ModelState s = world_->model_state(name);
        ms.name.push_back(name);
        ms.pose.push_back(to_pose(s.pose));
        ms.twist.push_back(to_twist(s.linear, s.angular));
        auto it = io_.find(name);
        if (it != io_.end() && it->second.ground_truth.getNumSubscribers() > 0) {
          nav_msgs::Odometry gt;
          gt.header.stamp = now;
          gt.header.frame_id = "world";
          gt.child_frame_id = world_->robot(name).model.root_link;
          gt.pose.pose = ms.pose.back();
          gt.twist.twist = ms.twist.back();
          it->second.ground_truth.publish(gt);
        }
      }
      model_states_pub_.publish(ms);
    }
  }

  void update_sensor_activity() {
    for (auto& [name, io] : io_)
      for (auto& s : io.sensors) {
        const bool want = s.listened();
        if (want != s.active) {
          world_->set_sensor_active(name, s.info.config.name, want);
          s.active = want;
        }
      }
  }

  SensorIO* sensor_io(const std::string& robot, const std::string& plugin) {
    auto it = io_.find(robot);
    if (it == io_.end()) return nullptr;
    for (auto& s : it->second.sensors)
      if (s.info.config.name == plugin) return &s;
    return nullptr;
  }

  void publish_sensors(const car_sim::SensorOutputs& out) {
    const double dt = world_->dt();
    for (const auto& o : out.scans) {
      SensorIO* io = sensor_io(o.robot, o.plugin);
      if (!io) continue;
      sensor_msgs::LaserScan m;
      m.header.stamp = sim_time(o.tick, dt);
      m.header.frame_id = io->frame;
      m.angle_min = o.angle_min;
      m.angle_max = o.angle_max;
      m.angle_increment = o.angle_increment;
      m.time_increment = 0.f;
      m.scan_time = 0.f;
      m.range_min = o.range_min;
      m.range_max = o.range_max;
      m.ranges = o.ranges;
      m.intensities = o.intensities;
      io->scan.publish(m);
    }
    for (const auto& o : out.images) {
      SensorIO* io = sensor_io(o.robot, o.plugin);
      if (!io) continue;
      const ros::Time stamp = sim_time(o.tick, dt);
      const auto& cfg = io->info.config;
      if (io->image.getNumSubscribers() > 0) {
        sensor_msgs::Image im;
        im.header.stamp = stamp;
        im.header.frame_id = io->frame;
        im.height = o.height;
        im.width = o.width;
        im.encoding = o.encoding;
        im.is_bigendian = 0;
        im.step = o.width * (o.encoding == "mono8" ? 1 : 3);
        im.data = o.image;
        io->image.publish(im);
      }
      const bool info_due = io->info_period <= 0.0 || (stamp - io->last_info).toSec() >= io->info_period - 1e-9 ||
                            stamp < io->last_info;
      if (info_due) {
        const sensor_msgs::CameraInfo ci = camera_info(o, cfg, io->frame, stamp);
        io->info_pub.publish(ci);
        if (io->depth_info) io->depth_info.publish(ci);
        io->last_info = stamp;
      }
      if (!o.has_depth) continue;
      const bool mm = cfg.flag("useDepth16UC1Format");
      if (io->depth.getNumSubscribers() > 0) {
        sensor_msgs::Image d;
        d.header.stamp = stamp;
        d.header.frame_id = io->frame;
        d.height = o.height;
        d.width = o.width;
        d.is_bigendian = 0;
        if (mm) {
          d.encoding = "16UC1";
          d.step = o.width * 2;
          d.data.resize(static_cast<size_t>(d.step) * o.height);
          auto* px = reinterpret_cast<uint16_t*>(d.data.data());
          for (size_t i = 0; i < o.depth.size(); ++i)
            px[i] = std::isfinite(o.depth[i]) ? static_cast<uint16_t>(std::lround(o.depth[i] * 1000.0f)) : 0;
        } else {
          d.encoding = "32FC1";
          d.step = o.width * 4;
          d.data.resize(static_cast<size_t>(d.step) * o.height);
          std::memcpy(d.data.data(), o.depth.data(), d.data.size());
        }
        io->depth.publish(d);
      }
      if (io->points.getNumSubscribers() > 0) io->points.publish(point_cloud(o, io->frame, stamp));
    }
    for (const auto& o : out.imus) {
      SensorIO* io = sensor_io(o.robot, o.plugin);
      if (!io) continue;
      sensor_msgs::Imu m;
      m.header.stamp = sim_time(o.tick, dt);
      m.header.frame_id = io->frame;
      m.orientation.x = o.orientation.x();
      m.orientation.y = o.orientation.y();
      m.orientation.z = o.orientation.z();
      m.orientation.w = o.orientation.w();
      m.angular_velocity.x = o.angular_velocity.x();
      m.angular_velocity.y = o.angular_velocity.y();
      m.angular_velocity.z = o.angular_velocity.z();
      m.linear_acceleration.x = o.linear_acceleration.x();
      m.linear_acceleration.y = o.linear_acceleration.y();
      m.linear_acceleration.z = o.linear_acceleration.z();
      const double var = std::pow(io->info.config.number("gaussianNoise"), 2);
      for (int i = 0; i < 3; ++i) {
        m.orientation_covariance[i * 4] = var;
        m.angular_velocity_covariance[i * 4] = var;
        m.linear_acceleration_covariance[i * 4] = var;
      }
      io->imu.publish(m);
    }
  }

  static sensor_msgs::CameraInfo camera_info(const car_sim::CameraOut& o, const car_sim::PluginConfig& cfg,
                                             const std::string& frame, const ros::Time& stamp) {
    sensor_msgs::CameraInfo ci;
    ci.header.stamp = stamp;
    ci.header.frame_id = frame;
    ci.width = o.width;
    ci.height = o.height;
    ci.distortion_model = "plumb_bob";
    ci.D = {cfg.number("distortionK1"), cfg.number("distortionK2"), cfg.number("distortionT1"),
            cfg.number("distortionT2"), cfg.number("distortionK3")};
    ci.K = {o.f, 0, o.cx, 0, o.f, o.cy, 0, 0, 1};
    ci.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    ci.P = {o.f, 0, o.cx, -o.f * cfg.number("hackBaseline"), 0, o.f, o.cy, 0, 0, 0, 1, 0};
    return ci;
  }

  static sensor_msgs::PointCloud2 point_cloud(const car_sim::CameraOut& o, const std::string& frame,
                                              const ros::Time& stamp) {
    sensor_msgs::PointCloud2 pc;
    pc.header.stamp = stamp;
    pc.header.frame_id = frame;
    pc.height = o.height;
    pc.width = o.width;
    const char* names[4] = {"x", "y", "z", "rgb"};
    const uint32_t offsets[4] = {0, 4, 8, 16};
    for (int k = 0; k < 4; ++k) {
      sensor_msgs::PointField f;
      f.name = names[k];
      f.offset = offsets[k];
      f.datatype = sensor_msgs::PointField::FLOAT32;
      f.count = 1;
      pc.fields.push_back(f);
    }
    pc.is_bigendian = false;
    pc.point_step = 32;
    pc.row_step = 32 * o.width;
    const size_t n = static_cast<size_t>(o.width) * o.height;
    pc.data.assign(32 * n, 0);
    bool dense = true;
    for (size_t i = 0; i < n; ++i) {
      uint8_t* p = pc.data.data() + 32 * i;
      std::memcpy(p, &o.points[3 * i], 12);
      // rgb packed as 0x00RRGGBB in a float's bits, as PCL and rviz read it
      const uint32_t rgb = (uint32_t(o.point_rgb[3 * i]) << 16) | (uint32_t(o.point_rgb[3 * i + 1]) << 8) |
                           uint32_t(o.point_rgb[3 * i + 2]);
      std::memcpy(p + 16, &rgb, 4);
      if (!std::isfinite(o.points[3 * i + 2])) dense = false;
    }
    pc.is_dense = dense;
    return pc;
  }

  bool ground_truth_listened() const {
    for (const auto& [name, io] : io_)
      if (io.ground_truth.getNumSubscribers() > 0) return true;
    return false;
  }

  void publish_odometry(const car_sim::OdometrySample& o) {
    const auto& info = world_->robot(o.model);
    const car_sim::DiffDriveConfig& cfg = info.drives.at(o.drive);
    RobotIO::Drive& io = io_[o.model].drives.at(o.drive);
    const ros::Time stamp = sim_time(o.tick, world_->dt());
    nav_msgs::Odometry msg;
    msg.header.stamp = stamp;
    msg.header.frame_id = frame(cfg.odometry_frame);
    msg.child_frame_id = frame(cfg.robot_base_frame);
    msg.pose.pose = to_pose(o.pose);
    const double cov[6] = {1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3};
    for (int i = 0; i < 6; ++i) msg.pose.covariance[i * 7] = cov[i];
    msg.twist.twist = to_twist(o.linear, o.angular);
    io.odom.publish(msg);
    if (cfg.publish_odom_tf) {
      geometry_msgs::TransformStamped t;
      t.header = msg.header;
      t.child_frame_id = msg.child_frame_id;
      t.transform = to_transform(o.pose);
      tf_.sendTransform(t);
    }
    if (cfg.publish_wheel_joint_state) {
      sensor_msgs::JointState js;
      js.header.stamp = stamp;
      for (const auto* j : {&o.left, &o.right}) {
        js.name.push_back(j->name);
        js.position.push_back(j->position);
        js.velocity.push_back(j->velocity);
      }
      io.wheel_joint_states.publish(js);
    }
    if (cfg.publish_wheel_tf) {
      // fix: each wheel relative to its parent link (upstream publishes it relative to the odometry frame)
      for (const auto* j : {&o.left, &o.right}) {
        const car_sim::Joint* joint = info.model.find_joint(j->name);
        geometry_msgs::TransformStamped t;
        t.header.stamp = stamp;
        t.header.frame_id = joint->parent;
        t.child_frame_id = joint->child;
        Eigen::Isometry3d T = joint->origin;
        T.rotate(Eigen::AngleAxisd(j->position, joint->axis));
        t.transform = to_transform(T);
        tf_.sendTransform(t);
      }
    }
  }

  void make_io(const std::string& name) {
    const auto& info = world_->robot(name);
    RobotIO io;
    const std::string spawn_ns = frame(info.robot_namespace);
    io.joint_states = nh_.advertise<sensor_msgs::JointState>(topic_in(spawn_ns, "joint_states"), 10);
    io.ground_truth = gz_.advertise<nav_msgs::Odometry>("ground_truth/" + name, 100);
    for (const auto& cfg : info.drives) {
      RobotIO::Drive d;
      d.cmd_vel = nh_.subscribe<geometry_msgs::Twist>(
          topic_in(cfg.robot_namespace, cfg.command_topic), 10,
          [this, name](const geometry_msgs::Twist::ConstPtr& m) { on_cmd_vel(name, *m); });
      if (cfg.publish_tf) {
        d.odom = nh_.advertise<nav_msgs::Odometry>(topic_in(cfg.robot_namespace, cfg.odometry_topic), 100);
      } else {
        ROS_WARN("car: %s: publishTf is false, so (like gazebo_ros) no %s is published at all", cfg.plugin_name.c_str(),
                 topic_in(cfg.robot_namespace, cfg.odometry_topic).c_str());
      }
      if (cfg.publish_wheel_joint_state)
        d.wheel_joint_states = nh_.advertise<sensor_msgs::JointState>(topic_in(cfg.robot_namespace, "joint_states"), 10);
      ROS_INFO("car: %s: diff drive '%s': command %s, odometry %s (%s) %s -> %s at %g Hz, wheels %s/%s, separation %g m, "
               "diameter %g m, torque %g N m, acceleration %g m/s^2%s%s%s",
               name.c_str(), cfg.plugin_name.c_str(), topic_in(cfg.robot_namespace, cfg.command_topic).c_str(),
               topic_in(cfg.robot_namespace, cfg.odometry_topic).c_str(), cfg.encoder_odometry ? "encoder" : "world",
               frame(cfg.odometry_frame).c_str(), frame(cfg.robot_base_frame).c_str(), cfg.update_rate,
               cfg.left_joint.c_str(), cfg.right_joint.c_str(), cfg.wheel_separation, cfg.wheel_diameter,
               cfg.wheel_torque, cfg.wheel_acceleration, cfg.publish_odom_tf ? ", odom TF" : "",
               cfg.publish_wheel_tf ? ", wheel TF" : "", cfg.publish_wheel_joint_state ? ", wheel joint states" : "");
      set_debug_level(cfg);
      io.drives.push_back(std::move(d));
    }
    for (const auto& si : world_->sensors()) {
      if (si.robot != name) continue;
      SensorIO sio;
      sio.info = si;
      const car_sim::PluginConfig& c = si.config;
      std::string ns = c.text("robotNamespace");
      while (!ns.empty() && ns.front() == '/') ns.erase(ns.begin());
      while (!ns.empty() && ns.back() == '/') ns.pop_back();
      sio.frame = frame(c.text("frameName"));
      std::string topics;
      if (c.kind == "laser") {
        sio.scan = nh_.advertise<sensor_msgs::LaserScan>(topic_in(ns, c.text("topicName")), 10);
        topics = sio.scan.getTopic();
      } else if (c.kind == "openni_kinect" || c.kind == "camera") {
        std::string base = ns;
        const std::string cam = frame(c.text("cameraName"));
        if (!cam.empty()) base = base.empty() ? cam : base + "/" + cam;
        sio.image = nh_.advertise<sensor_msgs::Image>(topic_in(base, c.text("imageTopicName")), 2);
        sio.info_pub = nh_.advertise<sensor_msgs::CameraInfo>(topic_in(base, c.text("cameraInfoTopicName")), 2);
        topics = sio.image.getTopic() + ", " + sio.info_pub.getTopic();
        if (c.kind == "openni_kinect") {
          sio.depth = nh_.advertise<sensor_msgs::Image>(topic_in(base, c.text("depthImageTopicName")), 2);
          sio.depth_info =
              nh_.advertise<sensor_msgs::CameraInfo>(topic_in(base, c.text("depthImageCameraInfoTopicName")), 2);
          sio.points = nh_.advertise<sensor_msgs::PointCloud2>(topic_in(base, c.text("pointCloudTopicName")), 2);
          topics += ", " + sio.depth.getTopic() + ", " + sio.depth_info.getTopic() + ", " + sio.points.getTopic();
        }
        const double r = c.number("updateRate");
        sio.info_period = r > 0 ? 1.0 / r : 0.0;
      } else if (c.kind == "imu") {
        sio.imu = nh_.advertise<sensor_msgs::Imu>(topic_in(ns, c.text("topicName")), 10);
        topics = sio.imu.getTopic();
      }
      ROS_INFO("car: %s: sensor '%s' (%s, %s) on %s at %g Hz, frame %s: %s", name.c_str(), c.sensor.c_str(),
               c.sensor_type.empty() ? c.kind.c_str() : c.sensor_type.c_str(), c.filename.c_str(), si.link.c_str(),
               si.rate, sio.frame.c_str(), topics.c_str());
      io.sensors.push_back(std::move(sio));
    }
    io_[name] = std::move(io);
  }

  // rosDebugLevel (Debug, Info, Warn, Error, Fatal; "na" leaves it) sets this node's logger level, as upstream.
  void set_debug_level(const car_sim::DiffDriveConfig& cfg) {
    static const std::map<std::string, ros::console::levels::Level> levels = {
        {"debug", ros::console::levels::Debug}, {"info", ros::console::levels::Info},
        {"warn", ros::console::levels::Warn},   {"error", ros::console::levels::Error},
        {"fatal", ros::console::levels::Fatal}};
    std::string l = cfg.ros_debug_level;
    for (auto& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const auto it = levels.find(l);
    if (it == levels.end()) return;
    if (ros::console::set_logger_level(ROSCONSOLE_DEFAULT_NAME, it->second)) ros::console::notifyLoggerLevelsChanged();
  }

  void on_cmd_vel(const std::string& robot, const geometry_msgs::Twist& m) {
    if (!std::isfinite(m.linear.x) || !std::isfinite(m.angular.z)) {
      // throttled in wall time: sim time stands still while paused and restarts at 0 after a reset
      auto& last = last_nan_warning_[robot];
      const auto now = std::chrono::steady_clock::now();
      if (last.time_since_epoch().count() == 0 || now - last > std::chrono::seconds(1)) {
        ROS_WARN("car: %s: rejected a cmd_vel with a non-finite value (linear.x %g, angular.z %g)", robot.c_str(),
                 m.linear.x, m.angular.z);
        last = now;
      }
      return;
    }
    if (world_->has_model(robot)) world_->set_cmd_vel(robot, m.linear.x, m.angular.z);
  }

  static bool world_frame(const std::string& f) { return f.empty() || f == "world" || f == "map"; }

  bool spawn(car::SpawnModel::Request& req, car::SpawnModel::Response& res) {
    res.success = false;
    if (!world_frame(req.reference_frame)) {
      res.status_message = "reference_frame '" + req.reference_frame + "' is not supported (use '' or 'world')";
      return true;
    }
    try {
      const car_sim::RobotModel model = car_sim::load_urdf_string(req.model_xml, req.model_name);
      for (const auto& d : model.diagnostics)
        if (d.severity == car_sim::Severity::Warning)
          ROS_WARN("car: %s: %s: %s", req.model_name.c_str(), d.element.c_str(), d.message.c_str());
      world_->spawn(model, req.model_name, from_pose(req.initial_pose), req.robot_namespace);
      for (const auto& d : world_->robot(req.model_name).config.diagnostics)
        if (d.severity == car_sim::Severity::Warning)
          ROS_WARN("car: %s: %s: %s", req.model_name.c_str(), d.element.c_str(), d.message.c_str());
    } catch (const std::exception& e) {
      res.status_message = std::string("SpawnModel: failure - ") + e.what();
      ROS_ERROR("car: %s", res.status_message.c_str());
      return true;
    }
    make_io(req.model_name);
    const auto& info = world_->robot(req.model_name);
    const Eigen::Vector3d p = info.spawn_pose.translation();
    ROS_INFO("car: spawned '%s' (%zu links, %zu joints, %zu plug-ins) at (%.3f %.3f %.3f)", req.model_name.c_str(),
             info.model.links.size(), info.model.joints.size(), info.config.plugins.size(), p.x(), p.y(), p.z());
    res.success = true;
    res.status_message = "SpawnModel: Successfully spawned entity";
    return true;
  }

  bool remove(car::DeleteModel::Request& req, car::DeleteModel::Response& res) {
    try {
      world_->remove(req.model_name);
    } catch (const std::exception& e) {
      res.success = false;
      res.status_message = std::string("DeleteModel: ") + e.what();
      return true;
    }
    io_.erase(req.model_name);
    ROS_INFO("car: deleted '%s'", req.model_name.c_str());
    res.success = true;
    res.status_message = "DeleteModel: successfully deleted model";
    return true;
  }

  bool get_state(car::GetModelState::Request& req, car::GetModelState::Response& res) {
    res.header.stamp = sim_time(world_->tick(), world_->dt());
    res.header.frame_id = "world";
    if (!world_frame(req.relative_entity_name)) {
      res.success = false;
      res.status_message = "GetModelState: relative_entity_name '" + req.relative_entity_name + "' is not supported";
      return true;
    }
    try {
      const car_sim::ModelState s = world_->model_state(req.model_name);
      res.pose = to_pose(s.pose);
      res.twist = to_twist(s.linear, s.angular);
    } catch (const std::exception& e) {
      res.success = false;
      res.status_message = std::string("GetModelState: ") + e.what();
      return true;
    }
    res.success = true;
    res.status_message = "GetModelState: got properties";
    return true;
  }

  bool set_state(car::SetModelState::Request& req, car::SetModelState::Response& res) {
    const auto& m = req.model_state;
    if (!world_frame(m.reference_frame)) {
      res.success = false;
      res.status_message = "SetModelState: reference_frame '" + m.reference_frame + "' is not supported";
      return true;
    }
    car_sim::ModelState s;
    s.pose = from_pose(m.pose);
    s.linear = Eigen::Vector3d(m.twist.linear.x, m.twist.linear.y, m.twist.linear.z);
    s.angular = Eigen::Vector3d(m.twist.angular.x, m.twist.angular.y, m.twist.angular.z);
    try {
      world_->set_model_state(m.model_name, s);
    } catch (const std::exception& e) {
      res.success = false;
      res.status_message = std::string("SetModelState: ") + e.what();
      return true;
    }
    res.success = true;
    res.status_message = "SetModelState: set model state done";
    return true;
  }

  bool properties(car::GetWorldProperties::Request&, car::GetWorldProperties::Response& res) {
    res.sim_time = world_->time();
    res.model_names = world_->model_names();
    res.rendering_enabled = false;
    res.success = true;
    res.status_message = "GetWorldProperties: got properties";
    return true;
  }

  bool reset_simulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    world_->reset();
    ROS_INFO("car: simulation reset: time 0, every model where it started");
    publish_clock();
    return true;
  }

  bool reset_world(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    world_->reset_poses();
    ROS_INFO("car: world reset: every model where it started");
    return true;
  }

  bool pause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    paused_ = true;
    return true;
  }

  bool unpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    paused_ = false;
    return true;
  }

  ros::NodeHandle nh_, pnh_, gz_;
  std::unique_ptr<World> world_;
  double rtf_ = 1.0, clock_rate_ = 100.0, joint_state_rate_ = 50.0, model_states_rate_ = 100.0;
  int solver_iterations_ = 10;
  bool paused_ = false;
  ros::Publisher clock_pub_, model_states_pub_;
  std::vector<ros::ServiceServer> services_;
  std::map<std::string, RobotIO> io_;
  std::map<std::string, std::chrono::steady_clock::time_point> last_nan_warning_;
  tf2_ros::TransformBroadcaster tf_;
};

}  // namespace car_ros

int main(int argc, char** argv) {
  // Camera frames are several MB each: keep freed blocks in the heap instead of returning them to the kernel,
  // so the next frame does not pay page faults (glibc otherwise mmaps blocks over 128 kB).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  ros::init(argc, argv, "gazebo");
  car_ros::SimNode node;
  if (!node.init()) return 1;
  node.run();
  return 0;
}
