// The Kinect: the shared ray-cast camera with depth; its outputs are camera frames (CameraOut with depth).
#include "openni_kinect.hpp"

#include "../common/camera_render.hpp"

namespace car_sim {

namespace {

constexpr ParamType T = ParamType::Text;
constexpr ParamType N = ParamType::Number;
constexpr ParamType F = ParamType::Flag;

void finish(ResolveContext& ctx) {
  finish_camera(ctx);
  const PluginConfig& c = ctx.config();
  // upstream keeps no depth then (every pixel NaN, or 0 in 16UC1): a warning, not a refusal
  if (c.number("pointCloudCutoff") >= c.number("pointCloudCutoffMax"))
    ctx.warn(Severity::Warning, "kinect-band", "pointCloudCutoff",
             "pointCloudCutoff " + c.text("pointCloudCutoff") + " >= pointCloudCutoffMax " +
                 c.text("pointCloudCutoffMax") + ": no pixel has a depth, as upstream");
}

}  // namespace

const PluginKind& openni_kinect_kind() {
  static const PluginKind k = [] {
    PluginKind k;
    k.name = "openni_kinect";
    k.filenames = {"libgazebo_ros_openni_kinect.so"};
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
        {"pointCloudCutoffMax", N, "5.0", "m"},
        {"useDepth16UC1Format", F, "false", ""},
    };
    k.schema.insert(k.schema.end(), extra.begin(), extra.end());
    k.ignored = camera_ignored_keys();
    k.ignored["borderCrop"] = "";
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
