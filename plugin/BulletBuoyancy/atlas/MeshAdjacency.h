#pragma once
/// @file MeshAdjacency.h
/// Triangle neighbourhoods used by the atlas stage: triangles sharing a mesh edge, and UV charts
/// (connected sets of triangles sharing a UV edge, design.md 1.2).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <cstdint>
#include <vector>

namespace buoyancy {

/// Triangles sharing an edge (same two vertex indices), as compressed rows: the neighbours of t are
/// neighbours[start[t] .. start[t+1]). Non-manifold edges link every triangle on them.
struct TriangleAdjacency {
    std::vector<std::uint32_t> start;      ///< #T + 1 row offsets
    std::vector<std::uint32_t> neighbours; ///< neighbour triangle indices
    /// UV continuity of each neighbour link (1 when the shared edge has the same UVs in both triangles).
    std::vector<char> uvContinuous;
};

/// Build the edge adjacency; when `cornerUvs` (3·#T) is non-empty, also mark which links are UV-continuous
/// (UVs at both shared vertices equal within `uvTolerance`).
TriangleAdjacency buildTriangleAdjacency(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs,
                                         double uvTolerance = 1e-9);

/// Label UV charts: connected components of the triangles under UV-continuous links.
/// @param[in]  active  #T flags; inactive triangles get chart −1
/// @return #T chart ids 0..chartCount−1 (or −1)
std::vector<int> labelUvCharts(const TriangleAdjacency& adjacency, const std::vector<char>& active, int& chartCount);

}  // namespace buoyancy
