/// @file MeshEdges.cpp
/// Unique edges of a triangle mesh (declared in MeshEdges.h).

#include <BulletBuoyancy/mesh/MeshEdges.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace buoyancy {

MeshEdges buildMeshEdges(const TriangleMesh& mesh) {
    const std::size_t nt = mesh.triangles.size();
    const std::int64_t nv = std::int64_t(mesh.vertices.size());
    // Every side as (key, side index), sorted by key: equal keys are one edge.
    std::vector<std::pair<std::int64_t, std::size_t>> sides;
    sides.reserve(3 * nt);
    for (std::size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const std::int64_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
            if (a < 0 || a >= nv || b < 0 || b >= nv)
                throw std::invalid_argument("buildMeshEdges: triangle " + std::to_string(t) +
                                            " has a vertex index out of range");
            sides.emplace_back(std::min(a, b) * nv + std::max(a, b), 3 * t + std::size_t(k));
        }
    std::sort(sides.begin(), sides.end());
    MeshEdges e;
    e.triangleEdges.resize(nt);
    for (std::size_t i = 0; i < sides.size(); ++i) {
        if (i == 0 || sides[i].first != sides[i - 1].first)
            e.edges.push_back({int(sides[i].first / nv), int(sides[i].first % nv)});
        e.triangleEdges[sides[i].second / 3][sides[i].second % 3] = int(e.edges.size() - 1);
    }
    return e;
}

}  // namespace buoyancy
