#pragma once
/// @file AutoWaterGraph.h
/// A water graph made automatically from a closed mesh (design.md 4, the permissive default; the
/// paper's CGAL SDF segmentation is GPL and not used): voxelise the interior (ray parity along x per
/// voxel row), cluster the interior voxels into k nodes (k-means, deterministic farthest-point start),
/// one node per cluster at its centroid with its share of the volume, and an edge between clusters that
/// touch (pipe cross-section = their shared voxel-face area, length = centroid distance).

#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

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

/// The interior voxels of a closed mesh (ray parity along x per voxel row), shared by autoWaterGraph and
/// the optional CGAL SDF graph (graph/cgal/SdfWaterGraph.h).
struct InteriorVoxels {
    Eigen::Vector3d lo = Eigen::Vector3d::Zero(); ///< corner of voxel (0, 0, 0) = the mesh's bounding-box minimum, m
    double h = 0;                                 ///< voxel edge, m (the longest bounding-box side / resolution)
    int nx = 0, ny = 0, nz = 0;                   ///< grid size, voxels
    std::vector<unsigned char> inside;            ///< nx·ny·nz flags (1 = centre inside), x fastest
    /// Flat index of voxel (i, j, k).
    std::size_t index(int i, int j, int k) const { return (std::size_t(k) * ny + j) * nx + i; }
    /// Centre of voxel (i, j, k), m.
    Eigen::Vector3d centre(int i, int j, int k) const { return lo + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5); }
};

/// Voxelise the interior of a closed mesh with `resolution` voxels along its longest bounding-box side.
/// @throws std::invalid_argument for a mesh with no triangles or an empty bounding box (may return no interior voxel)
InteriorVoxels voxeliseInterior(const TriangleMesh& mesh, int resolution);

/// Build the graph (nodes "auto0", "auto1", … ordered by cluster, sphere level models, no water).
/// @throws std::invalid_argument for bad settings or a mesh with no interior voxel at this resolution
WaterGraph autoWaterGraph(const TriangleMesh& mesh, const AutoWaterGraphSettings& settings);

}  // namespace buoyancy
