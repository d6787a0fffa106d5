# Included by wheel_rail_contactConfig.cmake (catkin CFG_EXTRAS), devel and install space alike:
# the imported target wheel_rail_contact::wheel_rail_contact_core, with Eigen3::Eigen it links.
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.3 NO_MODULE)
if(NOT TARGET wheel_rail_contact::wheel_rail_contact_core)
  include(${CMAKE_CURRENT_LIST_DIR}/wheel_rail_contactTargets.cmake)
endif()
