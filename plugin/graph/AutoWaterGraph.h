#pragma once
/// @file AutoWaterGraph.h
/// A water graph made automatically from a closed mesh (DESIGN-NOTES 4, the permissive default; the
/// paper's CGAL SDF segmentation is GPL and not used): voxelise the interior (ray parity along x per
/// voxel row), cluster the interior voxels into k nodes (k-means, deterministic farthest-point start),
/// one node per cluster at its centroid with its share of the volume, and an edge between clusters that
/// touch (pipe cross-section = their shared voxel-face area, length = centroid distance).

#include "graph/WaterGraph.h"
#include "mesh/TriangleMesh.h"

namespace buoyancy {

/// Settings of autoWaterGraph.
struct AutoWaterGraphSettings {
    int nodes = 4;          ///< k, the number of nodes wanted (fewer if the interior has fewer voxels), 1..256
    int resolution = 32;    ///< voxels along the mesh's longest bounding-box side, 4..256
    double fill = 0.9;      ///< Σ capacity = fill × the mesh's enclosed volume (the rest is material), (0, 1]
    std::uint64_t seed = 1; ///< the graph's seed (findDischargeNode order)
    /// @throws std::invalid_argument naming the bad field
    void validate() const;
};

/// Build the graph (nodes "auto0", "auto1", … ordered by cluster, sphere level models, no water).
/// @throws std::invalid_argument for bad settings or a mesh with no interior voxel at this resolution
WaterGraph autoWaterGraph(const TriangleMesh& mesh, const AutoWaterGraphSettings& settings);

}  // namespace buoyancy
