// The triggered camera: the camera kind's renderer, run only for pending triggers, one frame a step.
// Behaviour per docs/COMPAT-sensors.md: the sensor's <update_rate> and the plug-in's <updateRate> play no part; a
// trigger is used up whether or not anyone takes the frame.
#include "triggered_camera.hpp"

#include "../common/camera_render.hpp"

namespace car_sim {

namespace {

class TriggeredCamera : public CameraPlugin, public CameraTrigger {
 public:
  TriggeredCamera(const PluginConfig& c, const std::string& robot, uint64_t seed) : CameraPlugin(c, robot, seed, false) {}
  // every step: a pending trigger renders at the first step after it
  double update_rate() const override { return 0.0; }
  void reset() override {
    CameraPlugin::reset();
    pending_ = 0;
  }
  void trigger() override { ++pending_; }
  void command(const std::string&, const Command&, CommandResult*) override { trigger(); }
  void post_physics(const StepContext& ctx, const RobotHandle& robot, OutputQueue* out) override {
    if (pending_ == 0) return;
    --pending_;
    CameraPlugin::post_physics(ctx, robot, out);
  }

 private:
  int pending_ = 0;  // triggers not yet rendered
};

}  // namespace

const PluginKind& triggered_camera_kind() {
  static const PluginKind k = [] {
    PluginKind k = camera_kind_record();
    k.name = "triggered_camera";
    k.filenames = {"libgazebo_ros_triggered_camera.so"};
    k.namespace_rule = NamespaceRule::EmptyIsModel;  // GetRobotNamespace (gazebo_ros_camera_utils.cpp)
    k.schema.push_back({"triggerTopicName", ParamType::Text, "image_trigger", ""});
    // not lazy: a trigger is used up even while nobody listens, as upstream's OnNewFrame does
    k.lazy = false;
    // the trigger topic sits beside the image: under <robotNamespace>/<cameraName>
    k.inputs = [](const PluginConfig& c, const std::string& robot) {
      InputPort p;
      p.name = "trigger";
      p.type = InputType::Trigger;
      p.topic = resolve_topic(camera_base(c, robot), c.text("triggerTopicName"));
      return std::vector<InputPort>{p};
    };
    // upstream publishes image and camera_info while either has subscribers (camera_info is advertised with the
    // image's connect callbacks): each port to its own subscribers
    k.outputs = [](const PluginConfig& c, const std::string& robot, const Environment&) {
      return camera_ports(c, robot, "", 0, c.number("hackBaseline"));
    };
    k.make = [](const PluginConfig& c, const std::string& robot, uint64_t seed) -> std::unique_ptr<Plugin> {
      return std::make_unique<TriggeredCamera>(c, robot, seed);
    };
    return k;
  }();
  return k;
}

}  // namespace car_sim
