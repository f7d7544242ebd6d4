// Internal: an sdformat DOM model to the core's RobotModel (sdf_model.cpp), shared by the SDF robot loader and the
// world loader (models inside a world that have plug-ins, sensors or joints), with the DOM readers both use: poses,
// shapes, sdformat's errors. docs/COMPAT-sdf.md.
#pragma once

#include <sdf/Error.hh>
#include <sdf/Geometry.hh>
#include <sdf/Link.hh>
#include <sdf/Joint.hh>
#include <sdf/Model.hh>
#include <sdf/Sensor.hh>
#include <sdf/Visual.hh>

#include <optional>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/sdf_model.hpp"

namespace car_sim {
namespace detail {

Eigen::Isometry3d to_iso(const ignition::math::Pose3d& p);

// An element's line in its file; 0 when sdformat does not know it.
int line_of(const sdf::ElementPtr& e);

// sdformat's first error as a LoadError (with how many more there were); returns when there is none. An error
// inside an included file names that file; one in the text itself names source (sdformat calls such text
// "data-string"). Not errors, as Gazebo 11 loads the model or world: LINK_INERTIA_INVALID (car warns itself) and,
// with warnings given, an <include> that resolves nowhere (a warning "include-missing"; the rest loads).
void refuse_errors(const std::string& source, const sdf::Errors& errors, std::vector<Diagnostic>* warnings);

// Rule 9: box, cylinder, sphere, mesh, plane as a Shape (origin identity); anything else is nullopt with a warning
// at `where` (line: its line, 0 = unknown) appended to *diagnostics.
std::optional<Shape> to_shape(const sdf::Geometry& g, const std::string& where, int line,
                              std::vector<Diagnostic>* diagnostics);

// A <visual> of link `where` ("model[M]/link[L]"): its shape in the link frame, its material (script name, rgba from
// <diffuse>, <ambient>); nullopt for a geometry car does not draw (to_shape's warning appended). The one reader of
// visuals, for robots and world models alike.
std::optional<WorldVisual> read_visual(const sdf::Visual& v, const std::string& where,
                                       std::vector<Diagnostic>* diagnostics);

// A link's <inertial> as the DOM gives it: SDF's default (1 kg, unit inertia at the link origin) when absent (Rule 3).
// The one reader of inertials, for robots and world models alike.
Inertial read_inertial(const sdf::Link& l);

// A model as Gazebo 11 loads it (docs/COMPAT-sdf.md 16a): the nested models libsdformat 12 made from an <include>
// (or from a name `a::b` in an SDF <= 1.7 file) flattened into it as sdformat 9's addNestedModel does, their links,
// joints, frames and written nested models named `N::name`, their plug-in and sensor text renamed, their plug-ins
// appended; the <model>s written inside it kept apart. Everything in document order.
struct FlatLink {
  std::string name;           // `N::link` for an included model N's link
  const sdf::Link* link;      // in its own model's scope
  Eigen::Isometry3d pose;     // the link frame in the flattened model's frame
};
struct FlatJoint {
  std::string name;           // `N::joint`
  const sdf::Joint* joint;    // its parent and child are named in its own model's scope
  std::string prefix;         // what turns a name of that scope into the flattened model's (`N::`)
};
struct FlatPlugin {
  std::string xml;            // the <plugin> element's text, renamed
  std::string name, filename;
  int line = 0;
};
struct FlatSensor {
  const sdf::Sensor* sensor;
  std::string name;           // after the renaming (a sensor named like a link of its model is renamed too)
  std::string link;           // the flattened link's name
  std::string local_link;     // the link's name in the sensor's own scope (for SemanticPose)
  std::string xml;            // the <sensor> element's text, renamed
};
struct FlatNested {
  std::string name;           // `W`, or `N::W` for a model written inside an included model N
  const sdf::Model* model;
  Eigen::Isometry3d pose;     // its frame in the flattened model's frame
};
struct FlatModel {
  std::vector<FlatLink> links;
  std::vector<FlatJoint> joints;
  std::vector<FlatPlugin> plugins;      // the model's <plugin>s (not its sensors')
  std::vector<FlatSensor> sensors;
  std::vector<FlatNested> nested;       // written <model>s: models of their own in Gazebo 11
  std::vector<std::string> frames;      // explicit frames, for the renaming
  std::optional<bool> is_static;        // the first <static> written in document order (the model's own or an
                                        // included model's, appended as sdformat 9 appends it)
  // Rule 16: a joint, a plug-in or a sensor anywhere in it.
  bool is_robot() const { return !joints.empty() || !plugins.empty() || !sensors.empty(); }
  const FlatLink* link(const std::string& name) const;
};
FlatModel flatten_model(const sdf::Model& m);

// True when libsdformat 12 made this nested model from an <include> or from a name `a::b` (it has no element line
// of its own), so Gazebo 11 would have flattened it into its parent.
bool flattened_in_gazebo11(const sdf::Model& nested);

// A warning `plugin-not-loaded` for each <plugin> of f (its sensors' too) that car leaves out, naming the plug-in,
// its file and model `model`, saying why: a plug-in never vanishes silently.
void warn_plugins_dropped(const FlatModel& f, const std::string& model, const std::string& why,
                          std::vector<Diagnostic>* diagnostics);

// Converts one model; the returned root_pose is the root link in the frame the model's own pose is given in.
// Throws LoadError naming source, element and reason for what car cannot simulate.
SdfRobot convert_sdf_model(const sdf::Model& m, const std::string& source, const LoadOptions& options);


}  // namespace detail
}  // namespace car_sim
