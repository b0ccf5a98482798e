# Dependencies of BulletBuoyancy, shared by our own build and by BulletBuoyancyConfig.cmake (consumers).
# All come from Debian packages; nothing is downloaded.
include(CMakeFindDependencyMacro)
find_package(PkgConfig REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)

# Bullet's own BulletConfig.cmake exports variables, not targets: wrap the pkg-config module of the chosen
# precision into one imported target. The precision define (BT_USE_DOUBLE_PRECISION) travels with it as a
# PUBLIC usage requirement, so a float/double mismatch shows at build time.
if(NOT TARGET BulletBuoyancy::Bullet)
  if(BULLET_BUOYANCY_DOUBLE_PRECISION)
    pkg_check_modules(BULLET_BUOYANCY_BULLET REQUIRED IMPORTED_TARGET GLOBAL bullet-float64>=3.24)
  else()
    pkg_check_modules(BULLET_BUOYANCY_BULLET REQUIRED IMPORTED_TARGET GLOBAL bullet>=3.24)
  endif()
  add_library(BulletBuoyancy::Bullet ALIAS PkgConfig::BULLET_BUOYANCY_BULLET)
endif()

find_package(assimp 5.2 REQUIRED)
