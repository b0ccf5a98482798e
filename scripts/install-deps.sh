#!/usr/bin/env bash
# Install the Debian 12 packages BulletBuoyancy needs (run as root). Skips apt when everything is present.
set -euo pipefail
PACKAGES=(
  cmake g++ make pkg-config python3
  libbullet-dev            # Bullet 3.24, float (bullet.pc) and double (bullet-float64.pc) builds
  libeigen3-dev            # Eigen 3.4
  libassimp-dev            # assimp 5.2 mesh import
  zlib1g-dev               # assimp's CMake package links /usr/lib/x86_64-linux-gnu/libz.so by path, and
                           # libassimp-dev does not depend on zlib1g-dev (checked by scripts/fresh-debian-check.sh)
  assimp-testmodels        # real models used by the tests (and the demo)
  catch2                   # Catch2 2.13 tests
  libcli11-dev             # CLI11 command-line parsing
  nlohmann-json3-dev       # JSON (CLI output, scene files)
  libtbb-dev               # oneTBB: the world's threads (OpenMP, part of g++, is the fallback without it)
  # offscreen pictures (`buoyancy run --png`), the scene browser and its test under Xvfb
  libopengl-dev libgl-dev  # OpenGL 3.3 core entry points (GLVND libOpenGL) and GL/glcorearb.h
  libegl-dev libegl-mesa0 libgl1-mesa-dri  # EGL surfaceless + Mesa's llvmpipe: rendering without a display
  libstb-dev               # stb_image_write (PNG) and stb_image (tests, permeability textures in plugin/graph)
  libglfw3-dev             # the browser's window
  libimgui-dev             # Dear ImGui 1.86 with its GLFW/OpenGL 3 backends (the browser's panels)
  xvfb xauth               # xvfb-run: the browser test and scripts/pictures.sh without a display
  ocl-icd-opencl-dev       # OpenCL ICD loader (libOpenCL) for the OpenCL backend
  opencl-c-headers         # OpenCL C headers
  opencl-clhpp-headers     # OpenCL C++ bindings <CL/opencl.hpp>
  pocl-opencl-icd          # PoCL: an OpenCL CPU device, so the OpenCL tests run without a GPU
)
# `scripts/install-deps.sh --extra`: also what scripts/ci-extra.sh needs (clang + libFuzzer runtime for
# fuzz/, llvm-symbolizer for sanitizer stack traces). The default run does not need them.
if [ "${1:-}" = "--extra" ]; then
  PACKAGES+=(
    clang                  # clang 14: libFuzzer targets (fuzz/)
    libclang-rt-14-dev     # libFuzzer + ASan/UBSan runtimes for clang
    llvm                   # llvm-symbolizer: readable sanitizer stack traces
    libomp-dev             # LLVM's OpenMP runtime and its ThreadSanitizer tool (libarcher) for the TSan build
  )
fi
# `scripts/install-deps.sh --bench`: also what scripts/bench.sh needs for its plots (matplotlib). The default
# run and the tests do not need it.
if [ "${1:-}" = "--bench" ]; then
  PACKAGES+=(
    python3-matplotlib     # docs/benchmarks/*.png (scripts/bench_plots.py)
  )
fi
# `scripts/install-deps.sh --cgal`: also CGAL 5.5 for the optional, GPL-licensed SDF water graph
# (cmake -DBULLET_BUOYANCY_CGAL=ON, plugin/BulletBuoyancy/graph/cgal/, third_party_notes/cgal.md). Never in the default build.
if [ "${1:-}" = "--cgal" ]; then
  PACKAGES+=(
    libcgal-dev            # CGAL 5.5 headers (Surface_mesh_segmentation; pulls Boost, GMP, MPFR)
  )
fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
