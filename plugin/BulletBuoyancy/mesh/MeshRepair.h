#pragma once
/// @file MeshRepair.h
/// Welding and topology checks that turn an imported triangle soup into a closed, outward mesh.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <string>
#include <vector>

namespace buoyancy {

/// What prepareMesh found and did.
struct MeshReport {
    std::size_t input_triangles = 0;        ///< before welding and removing degenerates
    std::size_t degenerate_removed = 0;     ///< zero-area / repeated-vertex triangles dropped
    std::size_t welded_vertices = 0;        ///< vertices merged by position
    std::size_t components = 0;             ///< connected closed components
    std::size_t flipped_components = 0;     ///< inward components inside nothing, flipped outward
    std::size_t cavities = 0;               ///< inward components inside an outward one (kept as cavities)
    std::vector<MeshWarning> warnings;      ///< things the user should know (flips, intersecting components)
};

/// Weld vertices by position (within 1e-6 × the bounding-box diagonal D), drop degenerate triangles
/// (repeated vertex, or area ≤ 1e-12 D²), and check: finite coordinates with |x| ≤ 1e6 m and D ≥ 1e-6 m,
/// closed (every edge shared by exactly two faces), consistently oriented, outward per component
/// (an inward component inside nothing is flipped with a warning; inside an outward one it is a cavity
/// and kept; intersecting components get a warning). Rules and sources: MeshRepair.cpp header.
/// A clean mesh keeps its vertex order and indices.
/// @param[in,out] mesh  repaired in place (UVs follow their triangles)
/// @param[in] sourceName  file name used in error messages
/// @throws MeshError naming sourceName and the problem with a count, e.g. "open surface: 12 boundary edges"
MeshReport prepareMesh(TriangleMesh& mesh, const std::string& sourceName);

}  // namespace buoyancy
