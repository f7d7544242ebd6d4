// car's Gazebo 11 API (docs/PLUGINS.md): the version macros of Gazebo 11's gazebo_config.h, so that code written for
// several Gazebo versions (`#if GAZEBO_MAJOR_VERSION >= 8`) takes Gazebo 11's branch. Gazebo's HAVE_* feature macros
// are not defined: car has none of those optional parts.
#pragma once

#define GAZEBO_MAJOR_VERSION 11
#define GAZEBO_MINOR_VERSION 10
#define GAZEBO_PATCH_VERSION 2
#define GAZEBO_VERSION "11.10"
#define GAZEBO_VERSION_FULL "11.10.2"
