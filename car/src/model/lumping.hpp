// Fixed-joint lumping, massless-link dropping and world anchoring of a loaded URDF model, as sdformat's URDF
// reader (parser_urdf.cc: ReduceFixedJoints, CreateSDF) does them before Gazebo builds a model (private header).
// Rules: docs/COMPAT-spawn.md.
#pragma once

#include <map>
#include <string>

#include "car_sim/model.hpp"

namespace car_sim {
namespace detail {

// Finds joints from the link `world` (model.world_joints) and notes each as an anchor.
void find_world_anchor(RobotModel* m);

// Merges every child on a fixed joint (not preserved, parent not `world`) into its parent, deepest first:
// mass, centre of mass and inertia combined; collisions, visuals and sensors moved with composed poses;
// joints below re-parented; robot-level plug-ins' bodyName/frameName that name it renamed to the parent, their
// offsets rewritten (plugin_frame_replace).
// One Info diagnostic ("link-lumped") per link. lines: line of each <link>.
void lump_fixed_joints(RobotModel* m, const std::map<std::string, int>& lines);

// sdformat 9's ReduceSDFExtensionPluginFrameReplace for one element ("bodyName", "frameName") of a plug-in's
// keys: when it names `link`, lumped into `parent` by a fixed joint with origin T (link's frame in parent's), it
// names `parent`, and xyzOffset/rpyOffset are rewritten with sdformat 9's arithmetic (docs/COMPAT-spawn.md 11).
void plugin_frame_replace(ParamList* params, const std::string& element, const std::string& link,
                          const std::string& parent, const Eigen::Isometry3d& T);

// Drops every link without mass (no <inertial> or mass 0) on a moving joint, with its joint and subtree, as
// Gazebo does, with one Warning ("link-dropped") naming it; a root without mass is an Error ("root-massless").
void drop_massless_links(RobotModel* m, const std::map<std::string, int>& lines);

}  // namespace detail
}  // namespace car_sim
