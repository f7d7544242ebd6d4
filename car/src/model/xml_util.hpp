// Small XML and text helpers shared by the core's loaders (private header).
#pragma once

#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "car_sim/model.hpp"

namespace car_sim {
namespace detail {

std::string trim(const std::string& s);
// A number as the load messages write it: 6 significant digits ("0.001", "1e+06").
std::string short_number(double v);
std::vector<std::string> split_ws(const std::string& s);

// Parses a decimal number; nullopt when the whole text is not one finite number.
std::optional<double> parse_number(const std::string& text);
// Parses exactly n numbers separated by white space.
std::optional<std::vector<double>> parse_numbers(const std::string& text, size_t n);

// Rotation from roll, pitch, yaw [rad] in the URDF/SDF convention R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d rpy_to_matrix(double roll, double pitch, double yaw);
// "x y z roll pitch yaw" as SDF writes a pose.
std::optional<Eigen::Isometry3d> parse_pose6(const std::string& text);

// Text of an element, trimmed; "" for none.
std::string text_of(const tinyxml2::XMLElement* e);

// A <gazebo> value as sdformat's URDF reader takes it (GetKeyValueAsString in parser_urdf.cc): the `value`
// attribute when there is one (<mu1 value="0.5"/>), else the element's text (<mu1>0.5</mu1>); trimmed.
std::string value_of(const tinyxml2::XMLElement* e);

// Appends every leaf element below e as "a/b/c" -> text, in document order.
void flatten(const tinyxml2::XMLElement* e, const std::string& prefix, ParamList* out);

}  // namespace detail
}  // namespace car_sim
