// package://PKG and $(find PKG) as rospack resolves them (private header). Rules: docs/COMPAT-spawn.md
// "package:// lookup".
#pragma once

#include <string>
#include <vector>

namespace car_sim {
namespace detail {

// Folder of the ROS package named `name` (its package.xml <name>) under the given ROS_PACKAGE_PATH entries, in
// order, the first entry that holds it winning. Each entry is crawled as rospack does: a folder with a package.xml
// is a package and is not searched below; dot-folders and folders holding CATKIN_IGNORE are skipped. So
// catkin_ws/src/universal_robot/ur_description is found from catkin_ws/src. "" when no entry holds it.
std::string find_ros_package(const std::string& name, const std::vector<std::string>& entries);

// car's own data folder (config/, models/, urdf/, worlds/): <prefix>/share/car beside the loaded libcar_sim where
// car is installed (catkin_make install, the .debs: relocatable), else the source package it was built from (the
// devel space). A wheel (pip) has it as car/data/ beside car/_core, the library the core is linked into. Docs: docs/INSTALL.md "Where car finds its files".
const std::string& car_package_dir();

}  // namespace detail
}  // namespace car_sim
