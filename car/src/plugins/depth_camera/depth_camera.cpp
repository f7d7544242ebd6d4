// The generic depth camera: the shared ray-cast camera with depth, as the Kinect, but a depth is valid whenever it
// is beyond pointCloudCutoff (no upper cutoff). Outputs are camera frames (CameraOut with depth).
// Behaviour per docs/COMPAT-sensors.md.
#include "depth_camera.hpp"

#include "../common/camera_render.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;
constexpr ParamType F = ParamType::Flag;

void finish(ResolveContext& ctx) {
  finish_camera(ctx);
  if (ctx.config().number("pointCloudCutoff") < 0) ctx.fail("pointCloudCutoff", "must be >= 0");
}

}  // namespace

const PluginKind& depth_camera_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "depth_camera";
    k.filenames = {"libgazebo_ros_depth_camera.so"};
    k.namespace_rule = NamespaceRule::EmptyIsModel;  // GetRobotNamespace (gazebo_ros_camera_utils.cpp)
    k.model_level = false;
    k.sensor_types = {"depth"};
    k.sensor_schema = camera_sensor_schema();
    k.schema = camera_plugin_schema();
    const std::vector<ParamDef> extra = {
        {"imageTopicName", T, "ir/image_raw", ""},
        {"cameraInfoTopicName", T, "ir/camera_info", ""},
        {"depthImageTopicName", T, "depth/image_raw", ""},
        {"depthImageCameraInfoTopicName", T, "depth/camera_info", ""},
        {"pointCloudTopicName", T, "points", ""},
        {"pointCloudCutoff", N, "0.4", "m"},
        {"useDepth16UC1Format", F, "false", ""},
    };
    k.schema.insert(k.schema.end(), extra.begin(), extra.end());
    k.ignored = camera_ignored_keys();
    k.ignored["reflectanceTopicName"] = "reflectance is not published (the ray-cast camera has no reflectance channel)";
    k.ignored["normalsTopicName"] = "normals are not published";
    k.ignored["reduceNormals"] = "normals are not published";
    k.ignored["pointCloudCutoffMax"] = "libgazebo_ros_depth_camera.so has no upper cutoff (the Kinect plug-in has)";
    k.lazy = true;
    k.output_group = "images";
    k.finish = finish;
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      return depth_camera_ports(c, robot);
    };
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<CameraPlugin>(c, robot, seed, true);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
