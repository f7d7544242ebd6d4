# As upstream's gazebo_dev: find_package(gazebo) and export its include folders, libraries and library folders as
# this package's (catkin_INCLUDE_DIRS, catkin_LIBRARIES of a package that names gazebo_dev as a component).
find_package(gazebo REQUIRED)
list(APPEND gazebo_dev_INCLUDE_DIRS ${GAZEBO_INCLUDE_DIRS})
list(APPEND gazebo_dev_LIBRARIES ${GAZEBO_LIBRARIES})
list(APPEND gazebo_dev_LIBRARY_DIRS ${GAZEBO_LIBRARY_DIRS})
