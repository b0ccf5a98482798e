# Dependencies of BulletBuoyancy, shared by our own build and by BulletBuoyancyConfig.cmake (consumers).
# All come from Debian packages; nothing is downloaded.
include(CMakeFindDependencyMacro)
find_package(PkgConfig REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)

# Bullet's own BulletConfig.cmake exports variables, not targets: wrap the pkg-config module of the chosen
# precision into one imported target. The precision define (BT_USE_DOUBLE_PRECISION) travels with it as a
# PUBLIC usage requirement, so a float/double mismatch shows at build time.
#
# Or a Bullet of the same CMake build (BULLET_BUOYANCY_BULLET_SOURCE_DIR, set in our CMakeLists.txt; empty by default):
# the folder of a Bullet source tree added with add_subdirectory before this project. Its library targets and src/
# folder are wrapped into the same imported target, with Bullet's BT_* definitions of that folder (precision
# included), so exactly one Bullet is linked into a program (scripts/example-browser.sh builds Bullet's
# ExampleBrowser this way).
if(NOT TARGET BulletBuoyancy::Bullet AND BULLET_BUOYANCY_BULLET_SOURCE_DIR)
  if(NOT TARGET BulletDynamics OR NOT TARGET BulletCollision OR NOT TARGET LinearMath)
    message(FATAL_ERROR "BULLET_BUOYANCY_BULLET_SOURCE_DIR=${BULLET_BUOYANCY_BULLET_SOURCE_DIR}: add Bullet's source "
                        "tree with add_subdirectory() before BulletBuoyancy (no targets BulletDynamics, "
                        "BulletCollision, LinearMath yet)")
  endif()
  get_directory_property(_bb_bullet_defs DIRECTORY "${BULLET_BUOYANCY_BULLET_SOURCE_DIR}" COMPILE_DEFINITIONS)
  list(FILTER _bb_bullet_defs INCLUDE REGEX "^BT_")
  set(_bb_bullet_double OFF)
  if("BT_USE_DOUBLE_PRECISION" IN_LIST _bb_bullet_defs)
    set(_bb_bullet_double ON)
  endif()
  set(_bb_want_double OFF)
  if(BULLET_BUOYANCY_DOUBLE_PRECISION)
    set(_bb_want_double ON)
  endif()
  if(NOT _bb_want_double STREQUAL _bb_bullet_double)
    message(FATAL_ERROR "BulletBuoyancy: BULLET_BUOYANCY_DOUBLE_PRECISION=${BULLET_BUOYANCY_DOUBLE_PRECISION} but the "
                        "Bullet in ${BULLET_BUOYANCY_BULLET_SOURCE_DIR} has USE_DOUBLE_PRECISION=${_bb_bullet_double}: "
                        "build both with the same precision")
  endif()
  add_library(BulletBuoyancy::Bullet INTERFACE IMPORTED GLOBAL)
  set_target_properties(BulletBuoyancy::Bullet PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${BULLET_BUOYANCY_BULLET_SOURCE_DIR}/src"
    INTERFACE_LINK_LIBRARIES "BulletDynamics;BulletCollision;LinearMath"
    INTERFACE_COMPILE_DEFINITIONS "${_bb_bullet_defs}")
  message(STATUS "BulletBuoyancy: Bullet of this build (${BULLET_BUOYANCY_BULLET_SOURCE_DIR}; ${_bb_bullet_defs}), "
                 "not Debian's")
endif()
if(NOT TARGET BulletBuoyancy::Bullet)
  if(BULLET_BUOYANCY_DOUBLE_PRECISION)
    pkg_check_modules(BULLET_BUOYANCY_BULLET REQUIRED IMPORTED_TARGET GLOBAL bullet-float64>=3.24)
  else()
    pkg_check_modules(BULLET_BUOYANCY_BULLET REQUIRED IMPORTED_TARGET GLOBAL bullet>=3.24)
  endif()
  add_library(BulletBuoyancy::Bullet ALIAS PkgConfig::BULLET_BUOYANCY_BULLET)
endif()

find_package(assimp 5.2 REQUIRED)
