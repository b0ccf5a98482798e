# OpenCL backend, for our own build. BULLET_BUOYANCY_OPENCL = AUTO (default: on when the OpenCL
# headers, the C++ bindings <CL/opencl.hpp> and the ICD loader library are found, else a message and the
# CPU-only build), ON (required: configuring fails without them) or OFF (CPU only).
# Sets BULLET_BUOYANCY_WITH_OPENCL (ON/OFF) and defines bullet_buoyancy_enable_opencl(target), which embeds the
# kernels and links OpenCL into `target`. Debian packages: ocl-icd-opencl-dev, opencl-c-headers,
# opencl-clhpp-headers; a device at run time: pocl-opencl-icd (third_party_notes/opencl.md).

set(BULLET_BUOYANCY_OPENCL AUTO CACHE STRING
    "OpenCL backend: AUTO = when OpenCL + <CL/opencl.hpp> are found, ON = required, OFF = CPU only")
set_property(CACHE BULLET_BUOYANCY_OPENCL PROPERTY STRINGS AUTO ON OFF)

set(BULLET_BUOYANCY_WITH_OPENCL OFF)
string(TOUPPER "${BULLET_BUOYANCY_OPENCL}" _bb_ocl_mode)
if(_bb_ocl_mode STREQUAL "OFF" OR _bb_ocl_mode STREQUAL "FALSE" OR _bb_ocl_mode STREQUAL "0" OR _bb_ocl_mode STREQUAL "NO")
  message(STATUS "BulletBuoyancy: OpenCL backend off (BULLET_BUOYANCY_OPENCL=${BULLET_BUOYANCY_OPENCL}); CPU path only")
else()
  find_package(OpenCL QUIET)
  set(_bb_ocl_missing "")
  if(NOT OpenCL_FOUND)
    set(_bb_ocl_missing "the OpenCL headers and ICD loader (Debian: ocl-icd-opencl-dev opencl-c-headers)")
  else()
    find_path(BULLET_BUOYANCY_CLHPP_DIR CL/opencl.hpp HINTS ${OpenCL_INCLUDE_DIRS})
    if(NOT BULLET_BUOYANCY_CLHPP_DIR)
      set(_bb_ocl_missing "the OpenCL C++ bindings <CL/opencl.hpp> (Debian: opencl-clhpp-headers)")
    endif()
  endif()
  if(_bb_ocl_missing STREQUAL "")
    set(BULLET_BUOYANCY_WITH_OPENCL ON)
    message(STATUS "BulletBuoyancy: OpenCL backend on (${OpenCL_LIBRARIES}, OpenCL ${OpenCL_VERSION_STRING} headers)")
  elseif(_bb_ocl_mode STREQUAL "AUTO")
    message(STATUS "BulletBuoyancy: OpenCL backend off: not found: ${_bb_ocl_missing}. Building the CPU path only "
                   "(install them, or scripts/install-deps.sh, and reconfigure to get it).")
  else()
    message(FATAL_ERROR "BULLET_BUOYANCY_OPENCL=${BULLET_BUOYANCY_OPENCL} but not found: ${_bb_ocl_missing}")
  endif()
endif()

# Embed plugin/BulletBuoyancy/geometry/SampleFormulas.h + kernels/*.cl into a generated header (one string), so an installed
# library needs no file at run time (Bullet3's *Kernels.h style). Always called; without OpenCL it does nothing
# but define BULLET_BUOYANCY_HAVE_OPENCL=0.
function(bullet_buoyancy_enable_opencl target)
  # The backend's files (bullet/btOpenClBuoyancyBackend.cpp and bullet/opencl/) or, without OpenCL, its stub
  # (bullet/btOpenClBuoyancyBackendStub.cpp): the other is left out of the build.
  set(_bb_ocl_dir ${PROJECT_SOURCE_DIR}/plugin/BulletBuoyancy/bullet)
  file(GLOB _bb_ocl_backend CONFIGURE_DEPENDS ${_bb_ocl_dir}/opencl/*.cpp)
  list(APPEND _bb_ocl_backend ${_bb_ocl_dir}/btOpenClBuoyancyBackend.cpp)
  if(NOT BULLET_BUOYANCY_WITH_OPENCL)
    set_source_files_properties(${_bb_ocl_backend} PROPERTIES HEADER_FILE_ONLY ON)
    target_compile_definitions(${target} PRIVATE BULLET_BUOYANCY_HAVE_OPENCL=0)
    return()
  endif()
  set_source_files_properties(${_bb_ocl_dir}/btOpenClBuoyancyBackendStub.cpp PROPERTIES HEADER_FILE_ONLY ON)
  # In dependency order (each file uses the ones before it); every kernels/*.cl must be listed.
  set(_cl ${PROJECT_SOURCE_DIR}/kernels/water.cl ${PROJECT_SOURCE_DIR}/kernels/samples.cl
          ${PROJECT_SOURCE_DIR}/kernels/rebake.cl)
  file(GLOB _cl_all CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/kernels/*.cl)
  foreach(_f ${_cl_all})
    if(NOT _f IN_LIST _cl)
      message(FATAL_ERROR "kernels/: ${_f} is not listed in cmake/BulletBuoyancyOpenCL.cmake")
    endif()
  endforeach()
  set(_formulas ${PROJECT_SOURCE_DIR}/plugin/BulletBuoyancy/geometry/SampleFormulas.h)
  set(_out ${PROJECT_BINARY_DIR}/generated/BulletBuoyancy/bullet/BuoyancyKernelSource.h)
  add_custom_command(OUTPUT ${_out}
    COMMAND ${CMAKE_COMMAND} "-DOUT=${_out}" "-DINPUTS=${_formulas};${_cl}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedKernels.cmake
    DEPENDS ${_formulas} ${_cl} ${PROJECT_SOURCE_DIR}/cmake/EmbedKernels.cmake
    COMMENT "Embedding OpenCL kernels into BuoyancyKernelSource.h" VERBATIM)
  target_sources(${target} PRIVATE ${_out})
  target_include_directories(${target} PRIVATE $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>)
  target_compile_definitions(${target} PRIVATE BULLET_BUOYANCY_HAVE_OPENCL=1
    CL_HPP_TARGET_OPENCL_VERSION=120 CL_HPP_MINIMUM_OPENCL_VERSION=120 CL_HPP_ENABLE_EXCEPTIONS)
  target_include_directories(${target} PRIVATE ${OpenCL_INCLUDE_DIRS} ${BULLET_BUOYANCY_CLHPP_DIR})
  # Linked as the imported target, so the installed package names no path of this machine: a consumer's
  # BulletBuoyancyConfig.cmake finds OpenCL again (find_dependency).
  target_link_libraries(${target} PRIVATE OpenCL::OpenCL)
endfunction()
