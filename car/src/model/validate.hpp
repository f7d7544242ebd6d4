// Limits and validation before allocation (private to the core): every number a URDF or SDF world writes is
// checked before urdfdom, sdformat, the physics or a plug-in allocates anything from it. Errors are LoadErrors
// naming file, line, element and reason with the value as written; out-of-range values the physics can still
// use are warnings.
#pragma once

#include <tinyxml2.h>

#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"

namespace car_sim {
namespace limits {

// [kg] a link mass outside this range is a warning (a unit mistake, or a body the solver handles badly)
constexpr double kMassMin = 1e-6, kMassMax = 1e6;
// [kg m^2] a diagonal inertia entry outside this range is a warning
constexpr double kInertiaMin = 1e-12, kInertiaMax = 1e6;
// [m] shape sizes and positions above this are warnings: the ray scene works in single precision (a float's step
// at 1e6 m is 6 cm). Gazebo 11 loads them.
constexpr double kLengthMax = 1e6;
// [m] above this they are errors: a square of such a length overflows single precision (3.4e38) in the ray scene
// and the physics' distances (docs/COMPAT-validation.md)
constexpr double kLengthRefuse = 1e18;
// includes nested deeper than this are refused (the world tools' flattener has the same limit)
constexpr int kIncludeDepthMax = 32;
// models (and <include>s) in one world: libsdformat 12 holds about 2.5 MB and takes about 15 ms per model while it
// parses (measured: 1000 static boxes, 2.5 GB, 15 s), so a larger world is refused before sdformat sees it
constexpr int kWorldModelsMax = 1000;
// Sensors, checked before anything is allocated, on every path a sensor comes by (check_sensor_limits). Cameras:
// each image side [px], pixels per image (a depth frame holds about 80 bytes a pixel: rays, hits, colour, depth,
// cloud) and per second (pixels x update_rate). Rays: samples and resolution per axis, rays per scan (horizontal x
// vertical samples x resolution; a scan holds 40 bytes a ray; a 64-beam velodyne of 2048 columns is 131072) and
// per second (rays per scan x update_rate).
constexpr double kCameraSideMax = 8192;
constexpr double kCameraPixelsMax = 4194304;  // 2048 x 2048
constexpr double kCameraPixelsPerSecondMax = 1e9;
constexpr double kRaySamplesMax = 100000;
constexpr double kRaysPerScanMax = 1000000;
constexpr double kRaysPerSecondMax = 1e8;

// A limit as the error messages write it: "8192 px", "100000" (10 significant digits, the unit after a space).
std::string text(double v, const char* unit);

}  // namespace limits

namespace detail {

// A URDF document before urdfdom reads it: DTD entity declarations are refused; every number of every link and
// joint (origins, mass, inertia, geometry, axis, limits, dynamics, calibration, mimic, safety controller) must be
// finite; lengths and positions within limits::kLengthRefuse; damping and friction >= 0. Throws LoadError for the
// first error in document order; returns the warnings (mass and inertia out of range, negative effort or velocity
// limits, lengths beyond limits::kLengthMax, shapes with a size <= 0 or a mesh scale component 0, which the loader
// leaves out: degenerate_shape).
std::vector<Diagnostic> validate_urdf(const tinyxml2::XMLDocument& doc, const std::string& source);

// A shape with a size <= 0 (box edge, cylinder radius or length, sphere radius) or a mesh scale component 0: Gazebo
// 11 warns and simulates the model; car leaves such a collision out of the collision world (docs/COMPAT-validation.md).
bool degenerate_shape(const Shape& s);

// Drops a robot's degenerate collisions (the validator warned about them), before lumping.
void drop_degenerate_collisions(RobotModel* m);

// SDF text before sdformat reads it: DTD entities refused, every numeric element finite, every sensor within its
// limits, and every <include> that resolves acyclic and at most limits::kIncludeDepthMax deep (each included file
// checked the same way; one that resolves nowhere is sdformat's to report, a warning). base_dir:
// where relative URIs resolve ("" for text). Throws LoadError naming file, line, element and reason.
void prevalidate_sdf(const std::string& xml, const std::string& source, const std::string& base_dir);
// <sdf version="..."> must be digits and dots ("1.6"): libsdformat throws std::invalid_argument on others (found by
// fuzz_sdf_world and fuzz_sdf_model). A missing version is left to libsdformat, which refuses it.
void check_sdf_version(const tinyxml2::XMLElement* root, const std::string& source);

// A <sensor>'s sizes within the limits above, in URDF (<gazebo><sensor>) and SDF alike: the one check that serves
// URDF robots, SDF robots, world models, nested models and model:// includes (docs/COMPAT-validation.md). Values
// that are no positive finite number are left to the sensor's schema. Throws LoadError(source, line of <sensor>,
// "sensor[NAME]/KEY", reason).
void check_sensor_limits(const tinyxml2::XMLElement* sensor, const std::string& source);

// A DOCTYPE that declares entities is refused (LoadError at "!DOCTYPE"), so no entity is ever expanded (billion
// laughs) or fetched (external).
void refuse_entities(const tinyxml2::XMLDocument& doc, const std::string& source);

// The SDF file a model folder's model.config names: the highest <sdf version> up to 1.9 (the world loader's
// includes and the world flattener). Throws LoadError: (folder, "model.config") when the folder has none,
// (its model.config, "model/sdf") when it names no SDF file.
std::string model_sdf_file(const std::string& folder);

// SDF 1.4 worlds write a material script as bare text, <script>Gazebo/Green</script>; Gazebo 11's sdformat read the
// text as the script's name, libsdformat 12 refuses it. Returns the text with each such element rewritten as
// <script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Green</name></script> on the same
// line (line numbers stay); *changed says whether any was (docs/COMPAT-sdf.md).
std::string rewrite_bare_scripts(const std::string& xml, bool* changed);

// Gazebo 11 reads a camera's <image><format>R16G16B16</format>; libsdformat 12's camera knows that format only as
// RGB_INT16 and refuses the old name. Returns the text with each <format>R16G16B16</format> written as
// <format>RGB_INT16</format> (the same line; car's camera maps both to rgb16); *changed says whether any was.
std::string rewrite_pixel_formats(const std::string& xml, bool* changed);

// The document as Gazebo 11's sdformat read it, for libsdformat 12: rewrite_bare_scripts, then
// rewrite_pixel_formats (docs/COMPAT-sdf.md rules 18 and 20). *changed says whether anything was rewritten.
std::string read_as_gazebo11(const std::string& xml, bool* changed);

// A pose as SDF writes it (sdformat's pose.sdf), "x y z roll pitch yaw": "" when the text is blank or six finite
// numbers (each read as a decimal, as Python's float() reads one: no hexadecimal), else the reason, in the words of
// world_tool check and the flattener: "pose 'TEXT' is not 6 numbers (x y z roll pitch yaw)" or "pose 'TEXT' has a
// non-finite value". values (may be null) gets the numbers: none for a blank text.
std::string pose_problem(const std::string& text, std::vector<double>* values);

// The <geometry> children SDF 1.9 knows (sdformat's geometry.sdf), in the order world_tool check lists them.
const std::vector<std::string>& sdf_geometry_elements();

// world_tool check's rules over a flattened <world> (docs/COMPAT-validation.md "world_tool check"): every <pose>
// without a pose_problem (error "pose-malformed"); every <geometry> holding a shape (error "geometry-empty") that SDF
// knows (error "geometry-unknown"); every <mesh> with a <uri> (error "uri-missing"); a known shape car does not
// simulate is the warning "geometry-unsimulated". <state>, <gui> and <plugin> are not looked into. Element paths
// start at world[NAME] (an element's [NAME] when it has a non-empty name attribute), line 0, in document order.
std::vector<Diagnostic> check_world_xml(const tinyxml2::XMLElement* world);

// A converted world: step size > 0 and finite, gravity finite, real-time factor finite and >= 0; every model's
// poses, masses, inertias and shape sizes by the URDF's rules. Throws LoadError for errors; appends warnings to
// d->diagnostics; degenerate collisions are warned about and removed.
void validate_world(WorldDescription* d);

}  // namespace detail
}  // namespace car_sim
