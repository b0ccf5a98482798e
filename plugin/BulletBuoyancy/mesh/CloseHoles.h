#pragma once
/// @file CloseHoles.h
/// Closing the holes of an open triangle mesh: each boundary loop is filled with the triangulation of its own
/// vertices that has the least total area (design.md, "Repairing a model").

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <cstddef>
#include <vector>

namespace buoyancy {

/// What closeHoles did.
struct HoleClosing {
    std::size_t holes = 0;                  ///< boundary loops closed
    std::size_t boundary_edges = 0;         ///< edges those loops had
    double area_added = 0.0;                ///< total area of the closing triangles, m²
    std::vector<std::size_t> triangles;     ///< indices (in the mesh) of the closing triangles, appended at the end
    std::vector<std::size_t> hole_of_triangle; ///< #triangles: which hole (0-based) each closing triangle closes
};

/// Closes every hole of `mesh`. A boundary edge is a directed edge a→b of a triangle that no triangle traverses
/// as b→a (the surface is then a 2-cycle: every edge pairs up, which is what the surface integrals need). The
/// boundary edges form closed loops (at every vertex as many start as end); each loop is filled, without new
/// vertices, by the triangulation of its vertices with the least total area (dynamic programming over the
/// loop, O(n³) for n edges: for a planar hole this is a triangulation of the polygon itself, for a curved rim a
/// soap-film-like cap). The closing triangles are oriented to pair with the loop's edges and appended to
/// `mesh.triangles`; the mesh's UVs, if any, are dropped (the caps have none).
/// Expects a welded mesh without degenerate triangles and with consistently oriented faces.
/// @param[in,out] mesh  closed in place
/// @param[in] maxLoopEdges  largest loop that is closed (larger ones throw)
/// @param[in] minDoubleArea  twice the smallest area a closing triangle may have, m² (smaller ones are never
///                            chosen: no zero-area caps)
/// @throws MeshError for a loop longer than maxLoopEdges, or one whose vertices enclose no area (a crack)
HoleClosing closeHoles(TriangleMesh& mesh, std::size_t maxLoopEdges, double minDoubleArea);

}  // namespace buoyancy
