#pragma once
/// @file DragClusters.h
/// Drag level of detail (design.md 2.5: "evaluate drag on a coarser level of the same samples"): the fine
/// drag samples of a shape (face sub-samples or texture samples, often thousands) merged into a few dozen
/// clusters of nearby samples facing about the same way. Drag (design.md 2.6) is then summed over the
/// clusters, with one water query per cluster instead of one per fine sample. Drag coefficients are
/// uncertain to ±20 % anyway; the difference to the fine sum is measured in tests/integrals and docs/benchmarks.

#include <BulletBuoyancy/bake/SurfaceSamples.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace buoyancy {

/// Clustered drag samples, body frame, structure of arrays. Cluster k stands for the fine samples merged
/// into it: p_k is their area-weighted centroid (m), A_k = Σ A_i (m², outward), area_k = Σ area_i (m²), and
/// C_k their area-weighted spread about p_k (m²; each fine sample counted as a square of its own area),
/// so the vertical half extent of the cluster at any rotation R is sqrt(3 r_yᵀ C_k r_y) with r_y the second
/// row of R (a uniform segment of length L has variance L²/12).
struct DragClusters {
    std::vector<double> px, py, pz;                ///< #K centroids, m
    std::vector<double> ax, ay, az;                ///< #K summed area vectors, m²
    std::vector<double> area;                      ///< #K summed unsigned areas, m²
    std::vector<double> cxx, cxy, cxz, cyy, cyz, czz; ///< #K spread (covariance) about the centroid, m²
    int grid = 0;                                  ///< cells per side of the spatial grid used (1..64)
    /// Water-velocity probes (assignVelocityProbes): the water velocity is queried at these body-frame points and
    /// cluster k uses probe probeOf[k]'s (the orbital velocity of 10–60 m waves varies little over a probe's region).
    std::vector<double> probeX, probeY, probeZ;    ///< #P probe points, m
    std::vector<std::uint32_t> probeOf;            ///< #K probe index per cluster
    std::size_t fineCount = 0;                     ///< number of fine samples merged
    /// Number of clusters.
    std::size_t size() const { return px.size(); }
};

/// Number of normal-direction bins a cluster is confined to: the 6 faces of the cube map, each split into
/// 4 quadrants (a cone of roughly ±30–45° about each bin's centre).
constexpr int kDragNormalBins = 24;

/// Merge `fine` into at most `maxClusters` clusters: the finest spatial grid (G³ cells over the samples'
/// bounding box, G = 64 down to 1) whose non-empty (cell, normal bin) pairs number ≤ maxClusters (below 24
/// clusters the normal bins coarsen to the 6 cube faces, then to one). With
/// maxClusters = 0, or ≥ the fine count, every fine sample becomes its own cluster (no merging).
/// Samples with zero area are dropped. Cost O(S log G), once per shape.
DragClusters clusterDragSamples(const SurfaceSamples& fine, std::size_t maxClusters);

/// Fill the water-velocity probes of `clusters`: the clusters themselves merged again into at most `maxProbes`
/// groups (clusterDragSamples on the cluster centroids), each cluster assigned to the nearest group centroid.
/// maxProbes = 0 or ≥ the cluster count: one probe per cluster (at its centroid).
void assignVelocityProbes(DragClusters& clusters, std::size_t maxProbes);

}  // namespace buoyancy
