// A user's program built against the installed package: half-submerged unit cube, exact clipping.
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <cmath>
#include <cstdio>

int main() {
    const buoyancy::TriangleMesh cube = buoyancy::makeBoxMesh(1.0, 1.0, 1.0);
    const btFlatWaterSurface water(0.0);
    const auto r = buoyancy::clippedHydrostatics(cube, Eigen::Isometry3d::Identity(), water, 0.0, 1000.0, 9.81,
                                                 Eigen::Vector3d::Zero());
    std::printf("submerged volume %.6f m3 (expected 0.5)\n", r.submerged_volume);
    return std::fabs(r.submerged_volume - 0.5) < 1e-9 ? 0 : 1;
}
