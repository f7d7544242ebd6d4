// libgazebo_ros_camera.so on a <sensor type="camera">, and the ray-cast camera renderer the depth camera kinds
// (openni_kinect, ...) share: one ray per pixel through the collision geometry, the hit surface's colour lit by
// the world's ambient and directional light; depth, optical points and colour per pixel.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

struct CameraOut : Output {
  std::string sensor;
  int width = 0, height = 0;
  double f = 0, cx = 0, cy = 0;    // [px] one focal length; cx = (W-1)/2, cy = (H-1)/2
  std::string encoding;            // "rgb8", "bgr8", "mono8"
  std::vector<uint8_t> image;      // row-major, top row first
  bool has_depth = false;
  std::vector<float> depth;        // [m] along the optical axis; NaN outside (cutoff, cutoff_max) and for no hit
  std::vector<float> points;       // x y z per pixel [m], optical frame (z forward, x right, y down); NaN with depth
  std::vector<uint8_t> point_rgb;  // r g b per pixel
  void visit(FieldVisitor& v) const override;
};

// The <sensor type="camera|depth"> keys every camera kind reads (SDF 1.6 defaults).
const std::vector<ParamDef>& camera_sensor_schema();
// The plug-in keys gazebo_ros's camera utilities read (cameraName, frameName, distortion, ...).
const std::vector<ParamDef>& camera_plugin_schema();
// Keys users write that gazebo_ros ignores, with a note.
const std::map<std::string, std::string>& camera_ignored_keys();
// Checks the sensor keys (sizes, fov, clip, format).
void finish_camera(ResolveContext& ctx);

// A camera plug-in instance: renders colour, and depth with its cloud when depth is set.
class CameraPlugin : public Plugin {
 public:
  CameraPlugin(const PluginConfig& c, const std::string& robot, uint64_t seed, bool depth);
  double update_rate() const override { return rate_; }
  void reset() override { rng_ = rng0_; }
  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override;

 private:
  std::string link_;
  Eigen::Isometry3d sensor_pose_;
  double rate_;
  std::mt19937_64 rng0_, rng_;  // the noise generator as seeded, and as it runs
  CameraOut proto_;             // the fields every frame shares
  int w_ = 0, h_ = 0;
  double near_ = 0.1, far_ = 100.0, cutoff_ = 0.0, cutoff_max_ = 0.0;
  bool gaussian_ = false;
  double noise_mean_ = 0, noise_stddev_ = 0;
  // Rays are cast in 4 x 4 pixel tiles (the 16 rays of one Embree packet cover a square of the image, not a
  // 16-pixel strip: neighbouring rays visit the same BVH nodes); ray k is pixel pixel_[k]. dirs_, cos_, t_near_
  // and hits_ are in ray order, rgb_ and the outputs in pixel order.
  std::vector<int> pixel_;
  std::vector<float> dirs_, cos_, t_near_;
  std::vector<float> rgb_;  // [0, 1] per channel, before rounding
  float t_far_ = 0;
  std::vector<RayHit> hits_;
};

const PluginKind& camera_kind();

}  // namespace car_sim
