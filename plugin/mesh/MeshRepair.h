#pragma once
/// @file MeshRepair.h
/// Welding and topology checks that turn an imported triangle soup into a closed, outward mesh.

#include "mesh/TriangleMesh.h"

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

/// Weld vertices by position (tolerance relative to the bounding-box diagonal, default 1e-9 of it... see
/// implementation doc), drop degenerate triangles, and check: finite coordinates of sane magnitude, closed
/// (every edge shared by exactly two faces), consistently oriented, outward per component (cavities kept).
/// @param[in,out] mesh  repaired in place (UVs follow their triangles)
/// @param[in] sourceName  file name used in error messages
/// @throws MeshError naming sourceName and the problem with a count, e.g. "open surface: 12 boundary edges"
MeshReport prepareMesh(TriangleMesh& mesh, const std::string& sourceName);

}  // namespace buoyancy
