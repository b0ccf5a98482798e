#pragma once
/// @file SdfWaterGraph.h
/// The paper's automatic water graph (section 4, [YL18]): segment the surface with CGAL's Shape Diameter
/// Function (sdf_values + segmentation_from_sdf_values, a graph cut over k SDF clusters), then turn the
/// segments into nodes. Optional: compiled only with the CMake option BULLET_BUOYANCY_CGAL=ON (CGAL is GPL,
/// see third_party_notes/cgal.md), which defines BULLET_BUOYANCY_HAS_CGAL. The permissive default is
/// autoWaterGraph (graph/AutoWaterGraph.h).
///
/// Nodes: the interior is voxelised exactly as autoWaterGraph does (voxeliseInterior); each interior voxel
/// belongs to the segment of its nearest surface face; one node per segment that owns a voxel, at its voxels'
/// centroid, capacity = its voxel share of fill × the enclosed volume (so Σ capacity = fill × volume exactly).
/// Edges: between segments with face-adjacent voxels, pipe cross-section = their shared voxel-face area,
/// length = centroid distance (at least one voxel), as in autoWaterGraph. (The paper connects segments that
/// are adjacent on the surface; voxel contact also says the water can actually pass inside.)

#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <cstdint>

namespace buoyancy {

/// Settings of sdfWaterGraph.
struct SdfWaterGraphSettings {
    /// k, the number of SDF clusters of the segmentation (CGAL's number_of_clusters), 1..64. Each connected
    /// part of a cluster on the surface is one segment, so the graph may get more nodes than k (a dumbbell with
    /// k = 2 gives its two lobes and the bar), or fewer (segments that own no interior voxel make no node).
    int nodes = 4;
    double smoothing = 0.26;   ///< graph-cut smoothing λ of segmentation_from_sdf_values (CGAL's default), [0, 1]
    double coneAngle = 2.0943951023931957; ///< SDF ray cone opening angle, rad (CGAL's default 2π/3), (0, π)
    int rays = 25;             ///< SDF rays per face (CGAL's default), 1..1000
    int resolution = 32;       ///< voxels along the mesh's longest bounding-box side, 4..256
    double fill = 0.9;         ///< Σ capacity = fill × the mesh's enclosed volume (the rest is material), (0, 1]
    std::uint64_t seed = 1;    ///< the graph's seed (findDischargeNode order)
    /// @throws std::invalid_argument naming the bad field ("sdf.nodes: must be in [1, 64]")
    void validate() const;
};

/// Build the graph (nodes "sdf0", "sdf1", … in CGAL's segment order, sphere level models, no water).
/// @throws std::invalid_argument for bad settings, a mesh CGAL cannot take as a closed 2-manifold (naming the
///         triangle), or a mesh with no interior voxel at this resolution
WaterGraph sdfWaterGraph(const TriangleMesh& mesh, const SdfWaterGraphSettings& settings);

}  // namespace buoyancy
