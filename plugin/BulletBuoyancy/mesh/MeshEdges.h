#pragma once
/// @file MeshEdges.h
/// The unique edges of a triangle mesh and, per triangle, the edge of each side: the exact-mesh evaluation on waves
/// samples the water at every wet edge's midpoint once, shared by the two triangles of the edge (design.md 2.5).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <array>
#include <vector>

namespace buoyancy {

/// Edges of one mesh (immutable once built).
struct MeshEdges {
    /// Vertex indices of each unique edge (the smaller first).
    std::vector<std::array<int, 2>> edges;
    /// Per triangle t with corners (a, b, c): the edges of its sides a–b, b–c, c–a.
    std::vector<std::array<int, 3>> triangleEdges;
};

/// Build the edges of `mesh` (O(T log T)). @throws std::invalid_argument for a vertex index out of range
MeshEdges buildMeshEdges(const TriangleMesh& mesh);

}  // namespace buoyancy
