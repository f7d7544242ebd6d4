# car_gazebo: a subset of Gazebo 11's C++ plug-in API (headers at Gazebo's paths under include/gazebo_api/, so that
# #include <gazebo/gazebo.hh> works) as thin handles over car_sim::World's public API (docs/PLUGINS.md). Included
# from car's CMakeLists.txt after the core and its tests. The core includes no header of this layer; this layer
# includes no private header of the core.
find_package(ignition-math6 REQUIRED)  # Debian's libignition-math-dev (sdformat 12's maths)
find_package(Boost REQUIRED)           # boost::shared_ptr, as Gazebo 11's pointer types

add_library(car_gazebo src/gazebo/common.cpp src/gazebo/entity.cpp src/gazebo/factory.cpp src/gazebo/host.cpp
            src/gazebo/physics.cpp src/gazebo/motion.cpp src/gazebo/sensors.cpp src/gazebo/transport.cpp)
target_include_directories(car_gazebo PUBLIC include/gazebo_api ${Boost_INCLUDE_DIRS} PRIVATE src/gazebo)
target_link_libraries(car_gazebo PUBLIC car_sim sdformat12::sdformat12 ignition-math6::ignition-math6)
set_target_properties(car_gazebo PROPERTIES POSITION_INDEPENDENT_CODE ON)

# Gazebo 11's plug-in base libraries that users link by name (target_link_libraries(x RayPlugin)), beside car_gazebo
# in GAZEBO_LIBRARY_DIRS
foreach(_base RayPlugin CameraPlugin DepthCameraPlugin)
  add_library(${_base} SHARED src/gazebo/plugins/${_base}.cc)
  target_link_libraries(${_base} PUBLIC car_gazebo)
endforeach()

install(TARGETS car_gazebo RayPlugin CameraPlugin DepthCameraPlugin
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(DIRECTORY include/gazebo_api/ DESTINATION ${CATKIN_GLOBAL_INCLUDE_DESTINATION}/gazebo_api)

# ---- bench (bench/run.sh): the step cost of 0, 1 and 10 model plug-ins with an empty WorldUpdateBegin callback on
# the seed car; the plug-in's folder goes to bench_physics.py through the devel space (lib/car/bench_plugins)
set(_car_bench_plugins ${CATKIN_DEVEL_PREFIX}/lib/car/bench_plugins)
add_library(car_bench_empty_update MODULE bench/plugins/empty_update.cc)
target_link_libraries(car_bench_empty_update car_gazebo)
set_target_properties(car_bench_empty_update PROPERTIES OUTPUT_NAME car_bench_empty_update PREFIX "lib"
  LIBRARY_OUTPUT_DIRECTORY ${_car_bench_plugins})
add_executable(bench_gazebo bench/bench_gazebo.cpp)
target_link_libraries(bench_gazebo car_gazebo)
add_dependencies(bench_gazebo car_bench_empty_update)

# ---- tests: model plug-ins in the style of Gazebo's tutorials, built as .so files and loaded by the world's plug-in
# table in test_core (test/gazebo/); their folder goes to the tests as CAR_GAZEBO_TEST_PLUGINS.
if(CATKIN_ENABLE_TESTING AND TARGET test_core)
  set(_car_gz_plugins ${CMAKE_CURRENT_BINARY_DIR}/gazebo_test_plugins)
  foreach(_p hello_world model_push parameters velocity_pid throws_in_load forces motion world_hello world_factory
           world_events world_parameters system_args sensor_probe sensor_finder entity
           transport_probe time_reset link_enabled camera_transport free_functions joint_list)
    add_library(car_gz_test_${_p} MODULE EXCLUDE_FROM_ALL test/gazebo/plugins/${_p}.cc)
    target_link_libraries(car_gz_test_${_p} car_gazebo)
    set_target_properties(car_gz_test_${_p} PROPERTIES OUTPUT_NAME ${_p} PREFIX "lib"
      LIBRARY_OUTPUT_DIRECTORY ${_car_gz_plugins})
    add_dependencies(test_core car_gz_test_${_p})
  endforeach()
  # a RayPlugin, a CameraPlugin and a DepthCameraPlugin of ours, each linked to its base's library as Gazebo users
  # link it
  foreach(_pair ray:RayPlugin camera:CameraPlugin depth_camera:DepthCameraPlugin)
    string(REPLACE ":" ";" _pair ${_pair})
    list(GET _pair 0 _probe)
    list(GET _pair 1 _base)
    add_library(car_gz_test_${_probe}_plugin_probe MODULE EXCLUDE_FROM_ALL test/gazebo/plugins/${_probe}_plugin_probe.cc)
    target_link_libraries(car_gz_test_${_probe}_plugin_probe car_gazebo ${_base})
    set_target_properties(car_gz_test_${_probe}_plugin_probe PROPERTIES OUTPUT_NAME ${_probe}_plugin_probe PREFIX "lib"
      LIBRARY_OUTPUT_DIRECTORY ${_car_gz_plugins})
    add_dependencies(test_core car_gz_test_${_probe}_plugin_probe)
  endforeach()
  # the model push plug-in under a file name car simulates natively, for the switch CAR_UPSTREAM_PLUGINS
  add_library(car_gz_test_native_name MODULE EXCLUDE_FROM_ALL test/gazebo/plugins/model_push.cc)
  target_link_libraries(car_gz_test_native_name car_gazebo)
  set_target_properties(car_gz_test_native_name PROPERTIES OUTPUT_NAME gazebo_ros_planar_move PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${_car_gz_plugins})
  add_dependencies(test_core car_gz_test_native_name)
  # a library with no RegisterPlugin, for the loader's error
  add_library(car_gz_test_no_register MODULE EXCLUDE_FROM_ALL test/gazebo/plugins/no_register.c)
  set_target_properties(car_gz_test_no_register PROPERTIES OUTPUT_NAME no_register PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${_car_gz_plugins})
  add_dependencies(test_core car_gz_test_no_register)
  file(GLOB _car_gz_tests CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/test/gazebo/*.cpp)
  target_sources(test_core PRIVATE ${_car_gz_tests})
  target_compile_definitions(test_core PRIVATE CAR_GAZEBO_TEST_PLUGINS="${_car_gz_plugins}")
  # the node runs the model push plug-in as libcar_test_model_push.so in the devel space's lib/, where the loader
  # looks through CMAKE_PREFIX_PATH as for any sourced workspace (no argument: the result file's name stays the
  # same wherever the workspace is, for its floor in tools/test_floors.txt)
  add_library(car_gz_test_node_push MODULE EXCLUDE_FROM_ALL test/gazebo/plugins/model_push.cc)
  target_link_libraries(car_gz_test_node_push car_gazebo)
  set_target_properties(car_gz_test_node_push PROPERTIES OUTPUT_NAME car_test_model_push PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/lib)
  add_rostest(test/ros/gazebo_plugin.test DEPENDENCIES car_gz_test_node_push)
  # the world plug-ins' rostest: the factory and events plug-ins in the devel space's lib/, as above
  foreach(_p world_factory world_events)
    add_library(car_gz_test_node_${_p} MODULE EXCLUDE_FROM_ALL test/gazebo/plugins/${_p}.cc)
    target_link_libraries(car_gz_test_node_${_p} car_gazebo)
    set_target_properties(car_gz_test_node_${_p} PROPERTIES OUTPUT_NAME car_test_${_p} PREFIX "lib"
      LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/lib)
  endforeach()
  add_rostest(test/ros/gazebo_world_plugin.test DEPENDENCIES car_gz_test_node_world_factory car_gz_test_node_world_events)
  # a model plug-in using roscpp as upstream's drives do (its own callback-queue thread), in the devel space's lib/
  add_library(car_gz_test_node_ros_thread_probe MODULE EXCLUDE_FROM_ALL test/gazebo/plugins/ros_thread_probe.cc)
  target_include_directories(car_gz_test_node_ros_thread_probe PRIVATE ${catkin_INCLUDE_DIRS})
  target_link_libraries(car_gz_test_node_ros_thread_probe car_gazebo ${catkin_LIBRARIES})
  set_target_properties(car_gz_test_node_ros_thread_probe PROPERTIES OUTPUT_NAME car_test_ros_thread_probe PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/lib)
  add_rostest(test/ros/gazebo_ros_threads.test DEPENDENCIES car_gz_test_node_ros_thread_probe)
endif()
