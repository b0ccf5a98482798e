#pragma once
/// @file DragKernel.h
/// The drag sum over the drag clusters of one body (design.md 2.6; the per-cluster formulas of
/// geometry/SampleFormulas.h: bb_drag_wet_ramp and bb_drag_cluster_accumulate), several clusters per instruction
/// (SSE2, AVX2 or AVX-512, chosen at run time as for the Gerstner queries; plugin/BulletBuoyancy/geometry/VectorMath.h). The same terms
/// as the scalar formulas up to the order of the additions (tests/integrals/DragKernelTest.cpp).

#include <BulletBuoyancy/integrals/DragClusters.h>

#include <cstddef>

namespace buoyancy {

/// The clusters of one body at one substep, structure of arrays (n entries each), world frame unless noted.
struct DragClusterBatch {
    std::size_t n = 0;                                   ///< number of clusters
    const double *x = nullptr, *y = nullptr, *z = nullptr;    ///< cluster centre, m
    const double *ax = nullptr, *ay = nullptr, *az = nullptr; ///< area vector (area × outward normal), m²
    const double* area = nullptr;                        ///< unsigned area, m²
    /// Area-weighted spread about the centre, body frame (cxx, cxy, cxz, cyy, cyz, czz), m² (DragClusters.h).
    const double *cxx = nullptr, *cxy = nullptr, *cxz = nullptr, *cyy = nullptr, *cyz = nullptr, *czz = nullptr;
    const double* halfHeight = nullptr;                  ///< vertical half extent (bb_cluster_half_extent), m
    const double* waterHeight = nullptr;                 ///< water height at (x, z), m
    const double *ux = nullptr, *uy = nullptr, *uz = nullptr; ///< water velocity at the cluster, m/s
};

/// The body's motion and the drag coefficients for accumulateClusterDrag.
struct DragMotion {
    double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< body → world rotation, row-major
    double com[3] = {0, 0, 0};                   ///< centre of mass, world, m
    double v[3] = {0, 0, 0};                     ///< linear velocity, m/s
    double w[3] = {0, 0, 0};                     ///< angular velocity, rad/s
    double kd = 0;                               ///< ½ ρ C_d, kg/m³
    double kf = 0;                               ///< ½ ρ C_f, kg/m³
    double kl = 0;                               ///< ρ b (linear damping: radiation and viscous), kg/(m²·s)
};

/// Add the drag of every cluster to part[11] (BB_DRAG_TERMS: force, torque about the centre of mass, area-weighted
/// water velocity, wetted area, the linear damping's power), as bb_drag_wet_ramp + bb_drag_cluster_accumulate would
/// for each cluster in turn.
/// @param lanes  0: the widest the CPU runs (dragKernelLanes()); 2, 4 or 8 asks for that width (the tests run every
///               width the CPU has), a width the CPU lacks falls back to the widest it has below it
void accumulateClusterDrag(const DragClusterBatch& clusters, const DragMotion& motion, double part[11], int lanes = 0);

/// Where posing the clusters writes (n entries each; DragClusterBatch's world-frame inputs).
struct DragClusterPose {
    double *x = nullptr, *y = nullptr, *z = nullptr;     ///< cluster centre, world, m
    double *ax = nullptr, *ay = nullptr, *az = nullptr;  ///< area vector, world, m²
    double* halfHeight = nullptr;                        ///< vertical half extent sqrt(3 r_yᵀ C r_y), m
};

/// Move the clusters to the world: centre R p + t, area vector R a, and the vertical half extent of design.md 2.4's
/// covariance ramp, sqrt(3 max(r_yᵀ C r_y, 0)) with r_y the world-y row of R (for one fine sample it is
/// sqrt(area)/2 · sqrt(1 − n_y²), SampleFormulas.h). Several clusters per instruction, as accumulateClusterDrag.
/// @param R  body → world rotation, row-major; t  translation, m
/// @param lanes  as for accumulateClusterDrag
void poseDragClusters(const DragClusters& clusters, const double R[9], const double t[3], const DragClusterPose& out,
                      int lanes = 0);

/// Lanes the batch uses on this CPU (8 AVX-512F, 4 AVX2, 2 otherwise); for the tests and the benchmark log.
int dragKernelLanes();

}  // namespace buoyancy
