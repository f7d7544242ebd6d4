// car's Gazebo 11 API (docs/PLUGINS.md): the version macros of Gazebo's gazebo/gazebo_config.h, the version
// compat/gazebo's find_package(gazebo) reports (GAZEBO_VERSION 11.10.2), so that a plug-in's
// `#if GAZEBO_MAJOR_VERSION >= 9` takes its Gazebo 11 branch. Included by gazebo/gazebo.hh and
// gazebo/common/common.hh.
#pragma once

#define GAZEBO_MAJOR_VERSION 11
#define GAZEBO_MINOR_VERSION 10
#define GAZEBO_PATCH_VERSION 2
#define GAZEBO_VERSION "11.10"
#define GAZEBO_VERSION_FULL "11.10.2"
