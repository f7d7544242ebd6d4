# find_package(gazebo) as Gazebo 11's gazebo-config.cmake: GAZEBO_INCLUDE_DIRS, GAZEBO_LIBRARIES,
# GAZEBO_LIBRARY_DIRS, GAZEBO_CXX_FLAGS, for car's subset of Gazebo 11's C++ plug-in API (car_gazebo: the headers
# at Gazebo's paths, <gazebo/gazebo.hh>, ...; car/docs/PLUGINS.md says what it offers). A plug-in built with them
# is loaded by car from GAZEBO_PLUGIN_PATH, the ROS library folders or LD_LIBRARY_PATH.
if(NOT car_FOUND)
  find_package(car REQUIRED)
endif()
find_package(sdformat12 REQUIRED)
find_package(ignition-math6 REQUIRED)
find_package(Boost REQUIRED)

set(GAZEBO_INCLUDE_DIRS "")
foreach(_gz_dir ${car_INCLUDE_DIRS})
  if(EXISTS "${_gz_dir}/gazebo_api/gazebo/gazebo.hh")
    list(APPEND GAZEBO_INCLUDE_DIRS "${_gz_dir}/gazebo_api")
  endif()
endforeach()
if(NOT GAZEBO_INCLUDE_DIRS)
  message(FATAL_ERROR "gazebo (car's drop-in): car's Gazebo API headers (gazebo_api/gazebo/gazebo.hh) are not in "
                      "car's include folders: ${car_INCLUDE_DIRS}")
endif()
get_target_property(_gz_sdf_inc sdformat12::sdformat12 INTERFACE_INCLUDE_DIRECTORIES)
get_target_property(_gz_ign_inc ignition-math6::ignition-math6 INTERFACE_INCLUDE_DIRECTORIES)
list(APPEND GAZEBO_INCLUDE_DIRS ${car_INCLUDE_DIRS} ${_gz_sdf_inc} ${_gz_ign_inc} ${Boost_INCLUDE_DIRS})
# Gazebo 11 exports ignition-common's headers too (gazebo_plugins include ignition/common/Profiler.hh; with the
# profiler off, as Debian builds it, its IGN_PROFILE macros expand to nothing): car adds Debian's ignition-common 4
# headers where libignition-common-core-dev is installed. It is not a dependency of car: without it, code that
# includes them does not build (car/docs/PLUGINS.md).
find_path(_gz_ign_common_inc ignition/common/Profiler.hh PATH_SUFFIXES ignition/common4)
if(_gz_ign_common_inc)
  list(APPEND GAZEBO_INCLUDE_DIRS ${_gz_ign_common_inc})
endif()
list(REMOVE_DUPLICATES GAZEBO_INCLUDE_DIRS)
set(GAZEBO_LIBRARIES ${car_LIBRARIES} sdformat12::sdformat12 ignition-math6::ignition-math6)
# Gazebo 11 needs C++17. Upstream's maths and SDF targets ask for it as the compile feature cxx_std_17, which
# CMake meets on Debian 12's g++ (C++17 by default) by adding no flag, so a package's own -std=c++11 in
# CMAKE_CXX_FLAGS (kobuki_gazebo_plugins') would win; where the default is older (Noetic's g++ 9) CMake adds
# -std=gnu++17 after that flag. This interface target puts -std=c++17 after it here too.
if(NOT TARGET car_gazebo_cxx17)
  add_library(car_gazebo_cxx17 INTERFACE IMPORTED)
  set_target_properties(car_gazebo_cxx17 PROPERTIES INTERFACE_COMPILE_OPTIONS "$<$<COMPILE_LANGUAGE:CXX>:-std=c++17>")
endif()
list(APPEND GAZEBO_LIBRARIES car_gazebo_cxx17)
set(GAZEBO_LIBRARY_DIRS ${car_LIBRARY_DIRS})
set(GAZEBO_CXX_FLAGS "-std=c++17")
set(GAZEBO_VERSION 11.10.2)
set(GAZEBO_MAJOR_VERSION 11)
set(GAZEBO_MINOR_VERSION 10)
set(GAZEBO_PATCH_VERSION 2)
set(GAZEBO_FOUND TRUE)
