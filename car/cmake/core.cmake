# car's core (no ROS): the library car_sim and the Python module car._core, as both builds make them. Included by
# car/CMakeLists.txt (catkin, after find_package(catkin)) and by cmake/pip/CMakeLists.txt (pip, no catkin, no ROS;
# docs/INSTALL.md "Python only"). Before including it, the includer sets the C++ standard and, where _core is wanted,
# finds Python (pip) or lets pybind11 find it (catkin). Defines CAR_DIR, car_sim, _core.
get_filename_component(CAR_DIR "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

# ---- system libraries: each missing one named by its Debian package, all in one message --------------------------
# (tools/setup.sh installs them; a plain REQUIRED find would stop at the first with a CMake trace instead)
# (the includer may have found some missing already: the pip entry, python3-dev)
set(_car_missing ${CAR_MISSING_DEBS})
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  # Bullet in double precision (Debian ships both builds; double matches PyBullet's and keeps mm-level contacts).
  pkg_check_modules(BULLET QUIET IMPORTED_TARGET bullet-float64)
  if(NOT BULLET_FOUND)
    list(APPEND _car_missing libbullet-dev)
  endif()
else()
  list(APPEND _car_missing pkg-config libbullet-dev)
endif()
find_package(urdfdom QUIET)
find_package(tinyxml2 QUIET)
find_package(Eigen3 QUIET)
find_package(sdformat12 QUIET)
find_package(embree 3 QUIET)
find_package(assimp QUIET)
find_package(OpenMP QUIET)
if(NOT "python3-dev" IN_LIST _car_missing)  # pybind11 needs Python's headers to be found at all
  find_package(pybind11 QUIET)
endif()
# each CMake package with the Debian package that provides it (OpenMP: the compiler's own, or clang's libomp)
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  set(_car_omp libomp-dev)
else()
  set(_car_omp build-essential)
endif()
foreach(_dep urdfdom=liburdfdom-dev tinyxml2=libtinyxml2-dev Eigen3=libeigen3-dev sdformat12=libsdformat-dev
             embree=libembree-dev assimp=libassimp-dev OpenMP_CXX=${_car_omp} pybind11=pybind11-dev)
  string(REPLACE "=" ";" _dep "${_dep}")
  list(GET _dep 0 _pkg)
  list(GET _dep 1 _deb)
  if(NOT ${_pkg}_FOUND AND NOT (_pkg STREQUAL "pybind11" AND "python3-dev" IN_LIST _car_missing))
    list(APPEND _car_missing ${_deb})
  endif()
endforeach()
if(_car_missing)
  list(JOIN _car_missing " " _car_missing)
  message(FATAL_ERROR "car: system libraries missing. On Debian 12 install them with:\n"
                      "  sudo apt-get install ${_car_missing}\n(docs/INSTALL.md lists what car needs)")
endif()

# ---- core library: no ROS headers ----------------------------------------------------------------
# model/ (URDF + <gazebo>) and description/ (SDF, URI and colour rules) load; physics/ (Bullet) and raycast/
# (Embree) simulate; plugins/<kind>/ are the parts, registered in plugins/registry.cpp; world/ runs a step;
# util/ holds what every layer may use (the thread pool).
file(GLOB CAR_PLUGIN_SOURCES CONFIGURE_DEPENDS ${CAR_DIR}/src/plugins/*/*.cpp)
add_library(car_sim
  ${CAR_DIR}/src/model/xml_util.cpp
  ${CAR_DIR}/src/model/urdf_loader.cpp
  ${CAR_DIR}/src/model/gazebo_ext.cpp
  ${CAR_DIR}/src/model/lumping.cpp
  ${CAR_DIR}/src/model/spawn_ns.cpp
  ${CAR_DIR}/src/model/package_path.cpp
  ${CAR_DIR}/src/model/validate.cpp
  ${CAR_DIR}/src/description/sdf_world.cpp
  ${CAR_DIR}/src/description/sdf_model.cpp
  ${CAR_DIR}/src/description/sdf_flatten.cpp
  ${CAR_DIR}/src/description/materials.cpp
  ${CAR_DIR}/src/physics/bodies.cpp
  ${CAR_DIR}/src/physics/physics.cpp
  ${CAR_DIR}/src/physics/bullet_robot.cpp
  ${CAR_DIR}/src/physics/world_models.cpp
  ${CAR_DIR}/src/physics/plane_collision.cpp
  ${CAR_DIR}/src/physics/surface.cpp
  ${CAR_DIR}/src/physics/surface_solver.cpp
  ${CAR_DIR}/src/physics/contact_rows.cpp
  ${CAR_DIR}/src/physics/island_world.cpp
  ${CAR_DIR}/src/physics/inverse_mass.cpp
  ${CAR_DIR}/src/physics/guard.cpp
  ${CAR_DIR}/src/physics/services.cpp
  ${CAR_DIR}/src/physics/velocity_motor.cpp
  ${CAR_DIR}/src/raycast/raycast.cpp
  ${CAR_DIR}/src/raycast/coherent.cpp
  ${CAR_DIR}/src/mesh/mesh.cpp
  ${CAR_DIR}/src/plugins/plugin.cpp
  ${CAR_DIR}/src/plugins/resolve.cpp
  ${CAR_DIR}/src/plugins/registry.cpp
  ${CAR_PLUGIN_SOURCES}
  ${CAR_DIR}/src/world/world.cpp
  ${CAR_DIR}/src/util/parallel.cpp
)
target_include_directories(car_sim PUBLIC ${CAR_DIR}/include ${EIGEN3_INCLUDE_DIR}
  PRIVATE ${CAR_DIR}/src/model ${CAR_DIR}/src/description ${CAR_DIR}/src/physics ${CAR_DIR}/src/plugins
          ${urdfdom_INCLUDE_DIRS})
target_link_libraries(car_sim PUBLIC ${urdfdom_LIBRARIES} tinyxml2::tinyxml2 OpenMP::OpenMP_CXX
  PRIVATE sdformat12::sdformat12 PkgConfig::BULLET ${EMBREE_LIBRARY} assimp::assimp)
target_include_directories(car_sim PRIVATE ${EMBREE_INCLUDE_DIRS})
set_target_properties(car_sim PROPERTIES POSITION_INDEPENDENT_CODE ON)
# the solver's own calls (a row's update, the triangular solves) straight to the function, not through the PLT: a
# shared library's functions may otherwise be replaced at load time, so the compiler neither inlines nor calls them
# directly. No arithmetic changes (docs/BENCH.md "Profile").
set_source_files_properties(${CAR_DIR}/src/physics/surface.cpp ${CAR_DIR}/src/physics/surface_solver.cpp
  ${CAR_DIR}/src/physics/contact_rows.cpp ${CAR_DIR}/src/physics/inverse_mass.cpp PROPERTIES
  COMPILE_OPTIONS -fno-semantic-interposition)
# model:// falls back to the package's own models/ (sun, ground_plane), as Gazebo's built-ins
# the source package: car's data folder in the devel space (an install finds share/car beside its library instead,
# a wheel car/data/ beside car/_core; src/model/package_path.cpp)
target_compile_definitions(car_sim PRIVATE CAR_PACKAGE_DIR="${CAR_DIR}")

# ---- Python module car._core -------------------------------------------------------------------------
pybind11_add_module(_core ${CAR_DIR}/src/python/module.cpp)
target_link_libraries(_core PRIVATE car_sim)
target_include_directories(_core PRIVATE ${CAR_DIR}/src/description)
