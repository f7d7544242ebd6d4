// The ray-cast camera renderer every camera kind shares (camera, depth_camera, openni_kinect, multicamera,
// triggered_camera): one ray per pixel through the collision geometry, the hit surface's colour lit by the world's
// ambient and directional light; depth, optical points and colour per pixel; the camera's schemas, checks and
// ports. Not a kind: shared code.
#pragma once

#include <array>
#include <memory>
#include <new>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "car_sim/plugin.hpp"

namespace car_sim {

// std::allocator, except that an element made without a value (resize) is left uninitialised: a frame's buffers
// are written in full by the shader, so they are not zero-filled first (about 7 MB per 640 x 480 depth frame).
template <class T>
struct UninitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitAllocator<U>;
  };
  UninitAllocator() = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... A>
  void construct(U* p, A&&... a) {
    ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
  }
};
template <class T>
using FrameBuffer = std::vector<T, UninitAllocator<T>>;

// A camera's output parts (Plugin::set_parts): the colour image, the depth image, the cloud (points with colour).
constexpr uint32_t kCameraImage = 1u, kCameraDepth = 2u, kCameraCloud = 4u;

// One frame. A part nobody takes may be left out (its arrays empty): the image without kCameraImage or kCameraCloud,
// depth without kCameraDepth or kCameraCloud, points and point_rgb without kCameraCloud.
struct CameraOut : Output {
  std::string sensor;
  int width = 0, height = 0;
  double f = 0, cx = 0, cy = 0;    // [px] one focal length; cx = (W-1)/2, cy = (H-1)/2
  std::string encoding;            // "rgb8", "bgr8", "mono8", "rgb16", "mono16"
  FrameBuffer<uint8_t> image;      // row-major, top row first; 16-bit channels little-endian
  bool has_depth = false;          // a depth camera (its depth, points and point_rgb are made when taken)
  FrameBuffer<float> depth;        // [m] along the optical axis; NaN outside (cutoff, cutoff_max) and for no hit
  FrameBuffer<float> points;       // x y z per pixel [m], optical frame (z forward, x right, y down); NaN with depth
  FrameBuffer<uint8_t> point_rgb;  // r g b per pixel
  // Channels per pixel (1 mono, 3 colour) and bytes per channel (2 for the 16-bit encodings).
  int channels() const { return encoding.compare(0, 4, "mono") == 0 ? 1 : 3; }
  int channel_bytes() const { return encoding.size() > 2 && encoding.compare(encoding.size() - 2, 2, "16") == 0 ? 2 : 1; }
  size_t step() const { return static_cast<size_t>(width) * channels() * channel_bytes(); }  // [bytes] per row
  void visit(FieldVisitor& v) const override;
  // The frame as views of its arrays.
  ImageSample frame_view() const;
  void samples(SampleList& list) const override { list.add(frame_view()); }
};

// The image encoding of a sensor <format> (docs/COMPAT-sensors.md "16-bit images"); "" for an unknown one.
std::string camera_encoding(const std::string& format);

// The <sensor type="camera|depth"> keys every camera kind reads (SDF 1.6 defaults).
const std::vector<ParamDef>& camera_sensor_schema();
// The plug-in keys gazebo_ros's camera utilities read (cameraName, frameName, distortion, ...).
const std::vector<ParamDef>& camera_plugin_schema();
// Keys users write that gazebo_ros ignores, with a note.
const std::map<std::string, std::string>& camera_ignored_keys();
// Checks the sensor keys (sizes, fov, clip, format).
void finish_camera(ResolveContext& ctx);

// Where a camera's topics sit: <the plug-in's namespace>/<cameraName><sub>, without cameraName's leading '/'s
// (gazebo_ros_camera_utils; sub: a multicamera's "/left" or "/right").
std::string camera_base(const PluginConfig& c, const std::string& robot, const std::string& sub = "");
// The output ports of one camera (gazebo_ros_camera_utils): the Image on imageTopicName and the CameraInfo on
// cameraInfoTopicName under camera_base (queue 2), header frame frameName, camera_info at updateRate (0: with
// every frame) with D from distortionK1..K3, T1, T2 and P[3] = -f * baseline [m]. frame: the frame of the output.
std::vector<OutputPort> camera_ports(const PluginConfig& c, const std::string& robot, const std::string& sub,
                                     size_t frame, double baseline);
// A depth camera's (openni_kinect, depth_camera): the camera's ports, the depth camera_info (the same message, sent
// with the first), the depth image (useDepth16UC1Format) and the organized cloud; each names the part of the frame
// it takes (kCamera*), camera_info alone the cheapest, depth.
std::vector<OutputPort> depth_camera_ports(const PluginConfig& c, const std::string& robot);

// gazebo_ros_camera's and gazebo_ros_multicamera's OnNewFrame: the image too goes out at most once per 1/updateRate
// of sim time (the camera_info's rule, "Throttled publishers"), where the depth cameras send every frame.
void throttle_images(std::vector<OutputPort>* ports);

// A camera plug-in instance: renders colour, and depth with its cloud when depth is set.
class CameraPlugin : public Plugin {
 public:
  CameraPlugin(const PluginConfig& c, const std::string& robot, uint64_t seed, bool depth);
  double update_rate() const override { return rate_; }
  void reset() override { rng_ = rng0_; }
  void set_parts(uint32_t parts) override { parts_ = parts; }
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
  bool sixteen_ = false;  // 16 bits a channel: shaded as [0, 1] floats (rgb_), then rounded to 0..65535
  double noise_mean_ = 0, noise_stddev_ = 0;
  // Each pixel's ray: unit direction in the sensor frame (its x is the depth per unit distance), in pixel order.
  Pinhole pinhole_;
  std::vector<float> dirs_;
  std::vector<float> rgb_;  // [0, 1] per channel, before rounding (with noise or 16 bits only)
  float t_far_ = 0;
  std::vector<RayHit> hits_;
  uint32_t parts_ = ~0u;  // kCamera* bits someone takes
  // <camera><distortion>: k1 k2 k3 p1 p2, centre [px] (pixel index coordinates); any non-zero: distorted_
  std::array<double, 5> lens_{};
  double lens_cx_ = 0, lens_cy_ = 0;
  bool distorted_ = false;
  std::vector<double> lens_map_;  // [px] per output pixel: its point (u, v) in the pinhole frame
  void make_lens_map();
  bool prepared_ = false;  // the per-pixel arrays made (prepare)
  void prepare();
  // The frame's colour image resampled through the lens (docs/COMPAT-sensors.md "Lens distortion").
  void distort(FrameBuffer<uint8_t>* image, int pixel_bytes, int channel_bytes) const;
};

// The record of libgazebo_ros_camera.so (the camera kind's; triggered_camera starts from it).
PluginKind camera_kind_record();

}  // namespace car_sim
