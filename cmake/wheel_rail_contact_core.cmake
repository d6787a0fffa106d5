# The ROS-free core library wheel_rail_contact_core (Eigen and Highway): its sources, compile flags and the
# tables compiled into it, in one place for every build that compiles it: the package
# (CMakeLists.txt, catkin or plain CMake) and the fuzz build (test/fuzz). Also sets WRC_WARNINGS,
# the warnings every target of ours builds clean with. The library is shared or static as
# BUILD_SHARED_LIBS says (catkin and the plain package: shared; the fuzz build: static).
get_filename_component(WRC_ROOT ${CMAKE_CURRENT_LIST_DIR}/.. ABSOLUTE)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
# Highway (libhwy-dev): the marches' vector path (src/core/fastsim/strip_lanes.cpp), its target
# chosen at run time. Private: no public header of ours includes it.
find_package(hwy 1.0 REQUIRED)

# CI adds -Werror (WRC_WERROR=ON).
option(WRC_WERROR "Treat compiler warnings as errors (CI)" OFF)
set(WRC_WARNINGS -Wall -Wextra -Wshadow)
if(WRC_WERROR)
  list(APPEND WRC_WARNINGS -Werror)
endif()

file(GLOB_RECURSE WRC_CORE_SOURCES CONFIGURE_DEPENDS ${WRC_ROOT}/src/core/*.cpp)
# Tables shipped inside the library (shippedTable(name)): no data file to find once installed.
include(${WRC_ROOT}/cmake/shipped_tables.cmake)  # sets WRC_SHIPPED_TABLES
wrc_generate_shipped_tables(${CMAKE_CURRENT_BINARY_DIR}/generated/shipped_tables_data.cpp
  ${WRC_ROOT}/config ${WRC_SHIPPED_TABLES})
wrc_embed_calibration(${WRC_ROOT}/src/core/calibration/calibration_data.cpp
  ${WRC_ROOT}/config/calibration.bin)
add_library(wheel_rail_contact_core ${WRC_CORE_SOURCES}
  ${CMAKE_CURRENT_BINARY_DIR}/generated/shipped_tables_data.cpp)
# Installed and imported as wheel_rail_contact::core.
set_target_properties(wheel_rail_contact_core PROPERTIES EXPORT_NAME core
  POSITION_INDEPENDENT_CODE ON)
target_include_directories(wheel_rail_contact_core PUBLIC
  $<BUILD_INTERFACE:${WRC_ROOT}/include> $<INSTALL_INTERFACE:include>)
# Private headers (march internals, the half-space solver, the model classes) live beside their
# sources as "core/...": visible to the core, the validation library, tools, benchmarks and tests.
target_include_directories(wheel_rail_contact_core PRIVATE ${WRC_ROOT}/src)
target_link_libraries(wheel_rail_contact_core PUBLIC Eigen3::Eigen PRIVATE hwy::hwy)
target_compile_options(wheel_rail_contact_core PRIVATE ${WRC_WARNINGS})
# TransientStorage::lazyBefore writes each strip's few nodes outside the patch; GCC turns those
# runs of stores into memset calls, dearer per step (doc/performance.md). Results are the same.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set_source_files_properties(${WRC_ROOT}/src/core/fastsim/transient_fastsim.cpp PROPERTIES
    COMPILE_OPTIONS "-fno-tree-loop-distribute-patterns")
endif()
