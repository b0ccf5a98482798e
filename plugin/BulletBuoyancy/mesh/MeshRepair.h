#pragma once
/// @file MeshRepair.h
/// Welding and topology checks that turn an imported triangle soup into a closed, outward mesh.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace buoyancy {

/// How prepareMesh treats a mesh that fails its checks. The defaults refuse every problem: a model is changed
/// only when the caller asks for it.
struct PrepareMeshOptions {
    /// Repair what can be repaired safely instead of refusing it: faces given twice are removed, faces are turned
    /// to a consistent orientation, and each hole is closed by the least-area triangulation of its rim (no new
    /// vertices); edges shared by 4, 6, … faces that pair up are accepted, and parts that then enclose no volume
    /// (sheets, fins) are removed. What was done is in MeshReport::repair. Still refused: faces that cannot be
    /// oriented consistently (a one-sided surface), holes larger than maxHoleEdges or enclosing no area (cracks).
    bool repair = false;
    /// Accept edges shared by 4, 6, … faces that pair up, half each way (solids touching along an edge: a closed
    /// surface for the integrals) without repairing anything else. Implied by `repair`; btBuoyancyShape sets it so
    /// that a mesh repair accepted is accepted again.
    bool acceptTouchingParts = false;
    /// Largest hole closed, in boundary edges (closing costs O(n³) time and O(n²) memory: 1000 edges ≈ 1 s).
    std::size_t maxHoleEdges = 1000;
};

/// What prepareMesh repaired (all zero when nothing was, or PrepareMeshOptions::repair is off).
struct MeshRepairReport {
    std::size_t duplicate_faces_removed = 0; ///< faces with the same three vertices as another (a pair facing
                                             ///< opposite ways, an inner double wall, is removed whole)
    std::size_t faces_reoriented = 0;        ///< faces turned over to agree with their neighbours
    std::size_t paired_nonmanifold_edges = 0; ///< edges shared by 4, 6, … faces that pair up (kept, not refused)
    std::size_t holes_closed = 0;            ///< boundary loops closed
    std::size_t hole_edges = 0;              ///< boundary edges of those loops
    double area_added = 0.0;                 ///< area of the closing triangles, m²
    std::size_t flat_parts_removed = 0;      ///< parts enclosing no volume removed (sheets, fins closed on themselves)
    /// Indices (in the prepared mesh) of the triangles that close the holes; hole_of_triangle[k] is the hole
    /// (0-based) that triangle hole_triangles[k] closes. An open-deck hull's deck is one hole.
    std::vector<std::size_t> hole_triangles;
    std::vector<std::size_t> hole_of_triangle; ///< see hole_triangles
    /// Volume enclosed by the surface before the repair, m³ (for an open surface, the volume closed by the cone
    /// from its bounding-box centre: meaningful when the holes are small); NaN when nothing was repaired.
    double volume_before = std::numeric_limits<double>::quiet_NaN();
    double volume_after = std::numeric_limits<double>::quiet_NaN(); ///< volume after the repair, m³; NaN as above
    /// True when anything was changed.
    bool changed() const {
        return duplicate_faces_removed + faces_reoriented + holes_closed + flat_parts_removed > 0;
    }
};

/// What prepareMesh found and did.
struct MeshReport {
    std::size_t input_triangles = 0;        ///< before welding and removing degenerates
    std::size_t degenerate_removed = 0;     ///< zero-area / repeated-vertex triangles dropped
    std::size_t welded_vertices = 0;        ///< vertices merged by position
    std::size_t components = 0;             ///< connected closed components
    std::size_t flipped_components = 0;     ///< inward components inside nothing, flipped outward
    std::size_t cavities = 0;               ///< inward components inside an outward one (kept as cavities)
    std::vector<MeshWarning> warnings;      ///< things the user should know (flips, intersecting components)
    MeshRepairReport repair;                ///< what was repaired (PrepareMeshOptions::repair)
};

/// Weld vertices by position (within 1e-6 × the bounding-box diagonal D), drop degenerate triangles
/// (repeated vertex, or area ≤ 1e-12 D²), and check: finite coordinates with |x| ≤ 1e6 m and D ≥ 1e-6 m,
/// closed (every edge shared by exactly two faces), consistently oriented, outward per component
/// (an inward component inside nothing is flipped with a warning; inside an outward one it is a cavity
/// and kept; intersecting components get a warning). Rules and sources: MeshRepair.cpp header.
/// A clean mesh keeps its vertex order and indices. With options.repair, the problems listed in
/// PrepareMeshOptions are repaired first and reported in MeshReport::repair (and as a warning).
/// @param[in,out] mesh  repaired in place (UVs follow their triangles; dropped when holes are closed)
/// @param[in] sourceName  file name used in error messages
/// @param[in] options  what may be repaired (default: nothing)
/// @throws MeshError naming sourceName and the problem with a count, e.g. "open surface: 12 boundary edges"
///         (with a hint to repair when repairing is off)
MeshReport prepareMesh(TriangleMesh& mesh, const std::string& sourceName, const PrepareMeshOptions& options = {});

}  // namespace buoyancy
