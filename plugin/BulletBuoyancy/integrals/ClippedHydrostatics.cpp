/// @file ClippedHydrostatics.cpp
/// Exact-mesh hydrostatics (declared in Hydrostatics.h): every triangle of the posed mesh is clipped
/// against the water and the fields of design.md 2.2 / pressure of 2.3 are integrated exactly over
/// the wetted pieces. Exact for flat water (the integrands are polynomials of degree ≤ 2 over each flat
/// piece, integrated with the edge-midpoint rule, exact for quadratics). On waves the water over each
/// triangle is replaced by the plane through its corners' heights: an approximation, not exact.

#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/integrals/WetTriangleIntegrals.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

/// Thread-local scratch: posed vertices and their water heights (grows, never shrinks).
struct ClipScratch {
    std::vector<Eigen::Vector3d> world;
    std::vector<double> x, z, f;
};

}  // namespace

HydrostaticsResult clippedHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference) {
    return clippedHydrostatics(mesh, pose, water, time, fluidDensity, gravity, torqueReference, nullptr);
}

HydrostaticsResult clippedHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference,
                                       const WaterPatch* patch) {
    if (!std::isfinite(fluidDensity) || fluidDensity < 0)
        throw std::invalid_argument("clippedHydrostatics: fluid density must be finite and ≥ 0, got " +
                                    std::to_string(fluidDensity));
    if (!std::isfinite(gravity)) throw std::invalid_argument("clippedHydrostatics: gravity is not finite");
    const std::size_t nv = mesh.vertices.size();
    if (mesh.triangles.empty() || nv == 0) return HydrostaticsResult{};

    thread_local ClipScratch s;
    if (s.world.size() < nv) {
        s.world.resize(nv);
        s.x.resize(nv);
        s.z.resize(nv);
        s.f.resize(nv);
    }
    double minX = std::numeric_limits<double>::infinity(), minY = minX, minZ = minX;
    double maxX = -minX, maxZ = -minX;
    for (std::size_t i = 0; i < nv; ++i) {
        const Eigen::Vector3d w = pose * mesh.vertices[i];
        if (!w.allFinite())
            throw std::invalid_argument("clippedHydrostatics: vertex " + std::to_string(i) +
                                        " is not finite after the pose (non-finite vertex or pose)");
        s.world[i] = w;
        s.x[i] = w.x();
        s.z[i] = w.z();
        minX = std::min(minX, w.x());
        maxX = std::max(maxX, w.x());
        minY = std::min(minY, w.y());
        minZ = std::min(minZ, w.z());
        maxZ = std::max(maxZ, w.z());
    }
    double hMin = 0, hMax = 0;
    water.heightBounds(minX, minZ, maxX, maxZ, time, hMin, hMax);
    if (minY >= hMax) return HydrostaticsResult{};  // entirely above the water (design.md 2.5)

    double flatH = 0;
    if (water.isFlat(time, flatH))
        std::fill(s.f.begin(), s.f.begin() + nv, flatH);
    else if (patch)
        patch->heights(s.x.data(), s.z.data(), nv, s.f.data());  // interpolated (design.md 2.5)
    else
        water.heights(s.x.data(), s.z.data(), nv, time, s.f.data());  // heights at the corners, one batch
    for (std::size_t i = 0; i < nv; ++i)
        if (!std::isfinite(s.f[i]))
            throw std::runtime_error("clippedHydrostatics: the water surface returned a non-finite height at x=" +
                                     std::to_string(s.x[i]) + ", z=" + std::to_string(s.z[i]));

    const Eigen::Vector3d& r = torqueReference;
    WetIntegrals I;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        PieceVertex in[3];
        for (int k = 0; k < 3; ++k) {
            const int idx = tri[k];
            if (idx < 0 || std::size_t(idx) >= nv)
                throw std::invalid_argument("clippedHydrostatics: triangle " + std::to_string(t) +
                                            " has vertex index " + std::to_string(idx) + " out of range");
            in[k].p = s.world[idx] - r;
            in[k].f = s.f[idx] - r.y();
        }
        I.addClippedTriangle(in);  // Sutherland–Hodgman against y − f ≤ 0 (WetTriangleIntegrals.h)
    }

    return I.result(fluidDensity * gravity, r, "clippedHydrostatics");
}

}  // namespace buoyancy
