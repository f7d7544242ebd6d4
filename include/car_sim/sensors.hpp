// Sensors: one interface, a factory keyed by plug-in kind, each on its own sim-time schedule, with noise from a
// generator seeded by (seed, robot/sensor). Outputs are plain structs; the ROS node only packs them. No ROS headers.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "car_sim/plugins.hpp"
#include "car_sim/raycast.hpp"

namespace car_sim {

// ---- outputs ----------------------------------------------------------------------------------------------

struct LaserScanOut {
  std::string robot, sensor, plugin;
  uint64_t tick = 0;
  float angle_min = 0, angle_max = 0, angle_increment = 0;  // [rad]
  float range_min = 0, range_max = 0;                       // [m]
  std::vector<float> ranges;       // [m]; +inf: no hit within range_max
  std::vector<float> intensities;  // laser_retro of the hit surface
};

struct CameraOut {
  std::string robot, sensor, plugin;
  uint64_t tick = 0;
  int width = 0, height = 0;
  double f = 0, cx = 0, cy = 0;    // [px] one focal length; cx = (W-1)/2, cy = (H-1)/2
  std::string encoding;            // "rgb8", "bgr8", "mono8"
  std::vector<uint8_t> image;      // row-major, top row first
  bool has_depth = false;
  std::vector<float> depth;        // [m] along the optical axis; NaN outside (cutoff, cutoff_max) and for no hit
  std::vector<float> points;       // x y z per pixel [m], optical frame (z forward, x right, y down); NaN with depth
  std::vector<uint8_t> point_rgb;  // r g b per pixel
};

struct ImuOut {
  std::string robot, sensor, plugin;
  uint64_t tick = 0;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // sensor frame in the world
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();       // [rad/s], sensor frame
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();    // [m/s^2], sensor frame, gravity included
};

struct SensorOutputs {
  std::vector<LaserScanOut> scans;
  std::vector<CameraOut> images;
  std::vector<ImuOut> imus;
};

// ---- inputs -------------------------------------------------------------------------------------------

// What a sensor sees at one update.
struct SensorInput {
  uint64_t tick = 0;
  double dt = 0.0;                   // [s] physics step
  Eigen::Isometry3d pose;            // sensor frame in the world
  const RayScene* scene = nullptr;   // committed, bodies at their current poses
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.8);
  Eigen::Vector3d sun_direction = Eigen::Vector3d(-0.5, 0.1, -0.9).normalized();  // light travels along it
  double ambient = 0.4;              // scene ambient light
  Eigen::Vector3d background = Eigen::Vector3d(0.7, 0.7, 0.7);
  // the sensor frame's last three poses (oldest first), for the IMU's finite differences
  const Eigen::Isometry3d* history = nullptr;
};

class Sensor {
 public:
  virtual ~Sensor() = default;
  // Called when the sensor is due; appends its measurement to out.
  virtual void update(const SensorInput& in, std::mt19937_64& rng, SensorOutputs* out) = 0;
  virtual bool needs_rays() const { return true; }
  virtual bool needs_history() const { return false; }
};

// Builds the sensor of a resolved plug-in (kind laser, openni_kinect, camera, imu). robot names the model.
std::unique_ptr<Sensor> make_sensor(const PluginConfig& config, const std::string& robot);

// The generator of one sensor: the same seed and name give the same noise, whatever else runs.
std::mt19937_64 sensor_rng(uint64_t seed, const std::string& robot, const std::string& sensor);

}  // namespace car_sim
