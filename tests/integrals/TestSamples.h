#pragma once
/// @file TestSamples.h
/// Surface samples built inside the tests, independent of the baker: each triangle is split into k²
/// congruent sub-triangles (barycentric grid) and each sub-triangle gives one sample at its centroid with
/// A = area × outward normal. This is a valid "texture" for the divergence identities (design.md 2):
/// integrands linear over a piece (the volume) are exact.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include "oracles/OracleMeshes.h"

#include <Eigen/Geometry>

namespace buoyancy_test {

inline void pushSubTriangle(buoyancy::SurfaceSamples& s, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c, std::uint32_t tri) {
    const Eigen::Vector3d A = 0.5 * (b - a).cross(c - a);
    const Eigen::Vector3d p = (a + b + c) / 3.0;
    s.push(p.x(), p.y(), p.z(), A.x(), A.y(), A.z(), A.norm(), 0u, tri);
}

/// k² samples per triangle of `m` (k ≥ 1).
inline buoyancy::SurfaceSamples subdividedSamples(const OracleMesh& m, int k) {
    buoyancy::SurfaceSamples s;
    s.reserve(m.tris.size() * std::size_t(k) * std::size_t(k));
    for (std::size_t t = 0; t < m.tris.size(); ++t) {
        const Eigen::Vector3d& p0 = m.verts[m.tris[t][0]];
        const Eigen::Vector3d e1 = (m.verts[m.tris[t][1]] - p0) / k;
        const Eigen::Vector3d e2 = (m.verts[m.tris[t][2]] - p0) / k;
        for (int i = 0; i < k; ++i)
            for (int j = 0; i + j < k; ++j) {
                const Eigen::Vector3d q = p0 + double(i) * e1 + double(j) * e2;
                pushSubTriangle(s, q, q + e1, q + e2, std::uint32_t(t));
                if (i + j + 1 < k) pushSubTriangle(s, q + e1, q + e1 + e2, q + e2, std::uint32_t(t));
            }
    }
    return s;
}

}  // namespace buoyancy_test
