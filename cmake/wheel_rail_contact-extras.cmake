# Included by wheel_rail_contactConfig.cmake (catkin CFG_EXTRAS), devel and install space alike:
# the imported target wheel_rail_contact::core, with Eigen3::Eigen it links, and its former name
# wheel_rail_contact::wheel_rail_contact_core. wheel_rail_contact_DIR is the config's own directory
# (devel/share or install share), where the exported targets are; this file itself is read from the
# source tree in the devel space. (Without catkin, cmake/wheel_rail_contactConfig.cmake.in.)
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.3 NO_MODULE)
find_dependency(hwy 1.0)  # a static core links it (LINK_ONLY)
if(NOT TARGET wheel_rail_contact::core)
  include(${wheel_rail_contact_DIR}/wheel_rail_contactTargets.cmake)
endif()
if(NOT TARGET wheel_rail_contact::wheel_rail_contact_core)
  add_library(wheel_rail_contact::wheel_rail_contact_core INTERFACE IMPORTED)
  set_target_properties(wheel_rail_contact::wheel_rail_contact_core PROPERTIES
    INTERFACE_LINK_LIBRARIES wheel_rail_contact::core)
endif()
