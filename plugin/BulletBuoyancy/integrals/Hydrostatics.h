#pragma once
/// @file Hydrostatics.h
/// Submerged volume, centre of buoyancy, pressure force and torque, waterline area of a posed body in a
/// height-field water (design.md 2.2–2.3), from samples or by exact clipping of the mesh.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Geometry>
#include <vector>

class btWaterSurface;
struct btWaterQueryCache;

namespace buoyancy {

class WaterPatch;
struct MeshEdges;
struct MeshMomentTree;
struct VertexShares;

/// Area moments of the waterplane: the region the waterline encloses, projected on the horizontal plane, about a
/// reference point r (x' = x − r_x, z' = z − r_z, world axes). With the waterline area they give the linear
/// hydrostatic stiffness of a floating body in heave, roll and pitch (design.md 2.7; e.g. Faltinsen, "Sea Loads
/// on Ships and Offshore Structures", 1990, ch. 2: C₃₃ = ρ g A, C₃₅ = −ρ g ∫x dA, C₅₅ = ρ g ∫x² dA + …).
struct WaterplaneMoments {
    double x = 0;    ///< ∫ x' dA, m³
    double z = 0;    ///< ∫ z' dA, m³
    double xx = 0;   ///< ∫ x'² dA, m⁴
    double xz = 0;   ///< ∫ x' z' dA, m⁴
    double zz = 0;   ///< ∫ z'² dA, m⁴
    /// True when computed (the exact-mesh methods and the closed forms, from the waterline's segments, when the
    /// loop they form encloses the waterline area); false for the sampled methods and the device backends.
    bool valid = false;
};

/// Result of one hydrostatic evaluation, world frame.
struct HydrostaticsResult {
    double submerged_volume = 0;                          ///< m³
    Eigen::Vector3d centre_of_buoyancy = Eigen::Vector3d::Zero(); ///< m, world; meaningless when volume is 0
    Eigen::Vector3d force = Eigen::Vector3d::Zero();      ///< pressure force −Σ P_i A_i, N
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();     ///< about the reference point given, N·m
    double waterline_area = 0;                            ///< −Σ_wet A^y for samples; cap area for clipping, m²
    double wetted_area = 0;                               ///< wetted surface area, m²
    WaterplaneMoments waterplane;                         ///< about the reference point given
};

/// Per-body scratch arrays (world positions, area vectors, water heights), sized once and reused every
/// substep so the hot path allocates nothing.
struct SampleWorkspace {
    std::vector<double> wx, wy, wz;   ///< world positions, m
    std::vector<double> wax, way, waz; ///< world area vectors, m²
    std::vector<double> waterHeight;  ///< f at (wx, wz), m
    std::vector<double> warea;        ///< unsigned sample areas, m² (copied; when empty |A_i| is used)
    /// Resize every array to n (no-op when already n).
    void resize(std::size_t n);
};

/// Transform body-frame samples by `pose` (body → world) into ws (positions and area vectors).
void transformSamples(const SurfaceSamples& samples, const Eigen::Isometry3d& pose, SampleWorkspace& ws);

/// Sum hydrostatics over wetted samples (y_i < f_i) of a transformed workspace whose waterHeight is
/// filled. Fields of design.md 2.2 (not the paper's eq. 11): V = Σ A^y (y − f), ∫x = Σ A^y x (y − f),
/// ∫y = Σ A^y (y² − f²)/2, ∫z = Σ A^y z (y − f); P_i = ρ g (f_i − y_i), F = −Σ P_i A_i,
/// τ = Σ (p_i − ref) × (−P_i A_i). Sums in double.
/// @param fluidDensity ρ, kg/m³ (water 1000)   @param gravity g, m/s² (9.81)
HydrostaticsResult integrateWettedSamples(const SampleWorkspace& ws, double fluidDensity, double gravity,
                                          const Eigen::Vector3d& torqueReference);

/// Convenience: transform, query the surface once (batch), integrate.
/// @param cache  optional per-body warm-start memory for the height query (btWaterSurface::heightsCached)
/// @param patch  optional: heights interpolated from this per-body grid instead of queried (design.md 2.5)
HydrostaticsResult sampledHydrostatics(const SurfaceSamples& samples, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference,
                                       SampleWorkspace& ws, btWaterQueryCache* cache = nullptr,
                                       const WaterPatch* patch = nullptr);

/// Exact-mesh method: clip every triangle of the posed mesh against the water (exact for flat water;
/// on waves each triangle is cut against the plane through its corners' water heights), and integrate
/// the same fields over the wetted pieces exactly (they are polynomial over a flat piece).
HydrostaticsResult clippedHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference);

/// clippedHydrostatics with the corner heights interpolated from `patch` (built over this body at `time`)
/// instead of queried one by one, when the surface is not flat (design.md 2.5: fewer wave queries).
/// `patch` null: same as the overload above.
HydrostaticsResult clippedHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference,
                                       const WaterPatch* patch);

/// Split scale of curvedHydrostatics, dimensionless: a triangle is split 1:4 while K₃ h³ (K₃ the surface's or patch's
/// third-derivative scale, h its longest side) exceeds this × the body's mean thickness V / A. Calibrated against the
/// divergence-theorem reference on low-poly shapes (a 12-triangle box, a 14-sided cylinder, a 64-triangle ellipsoid) in
/// a long and a short Gerstner sea (tests/integrals/WaveAccuracyTest.cpp): at 20 the worst volume error is ≤ 0.011 %
/// of V; at 100 the 4 m box in the long sea is no longer split and its centre of buoyancy misses the bar
/// (1.6e-3 V·D as a first moment).
constexpr double kCurvedWaterTolerance = 20.0;

/// Largest estimated error of the plane through each triangle's corner heights, K₂h²/(8 T) (K₂ the wave patch's
/// curvature, h the mesh's median leaf radius, T its mean thickness V/A), at which treeHydrostatics keeps that plane
/// on waves instead of the curved-water model, dimensionless. The measured error is about a fifth of the estimate
/// (TreeHydrostatics.cpp): at 0.0025 the plane's worst error stays near 0.05 % of V, half the accuracy bar.
constexpr double kPlaneWaterTolerance = 0.0025;
/// Fewest triangles of a mesh for which treeHydrostatics may keep that plane on waves (a low-poly mesh's long
/// triangles are not represented by its median leaf).
constexpr std::size_t kPlaneWaterMinTriangles = 1000;

/// The exact-mesh method on curved water (design.md 2.5): the water over each triangle that can be wet is the
/// quadratic through its heights at the corners and side midpoints (one height per vertex and per edge, from
/// `patch` when given, else from the surface in one batch), the integrands of design.md 2.2–2.3 integrated exactly
/// for that water (degree-4 rule); triangles large against the water's third-derivative scale are split 1:4 first
/// (kCurvedWaterTolerance), a triangle the waterline crosses is cut into its four sub-triangles and each clipped.
/// Flat water: the same result as clippedHydrostatics to rounding (slower).
/// @param edges      buildMeshEdges(mesh)
/// @param thickness  the body's mean thickness V / A (volume over surface area), m: scales the split tolerance
/// @throws std::invalid_argument for edges of another mesh, bad density/gravity or a non-finite pose;
///         std::runtime_error for a non-finite water height or result
HydrostaticsResult curvedHydrostatics(const TriangleMesh& mesh, const MeshEdges& edges, const Eigen::Isometry3d& pose,
                                      const btWaterSurface& water, double time, double fluidDensity, double gravity,
                                      const Eigen::Vector3d& torqueReference, double thickness,
                                      const WaterPatch* patch = nullptr);

/// The exact-mesh method through the moment tree (MeshMomentTree.h, design.md 2.5): nodes entirely under water
/// add closed-form terms, nodes above are skipped, the triangles of straddling leaves are clipped as in
/// clippedHydrostatics. Flat water: the same result as clippedHydrostatics to rounding. Waves given by `patch`: the
/// water over a submerged node or a straddling leaf is the patch's second-order expansion about the node centre
/// (error measured in tests/integrals/TreeHydrostaticsTest.cpp). Non-flat water without a patch, or waves so curved
/// that the mesh's typical leaf is too large for the expansion (TreeHydrostatics.cpp): clippedHydrostatics.
/// On waves the leaves too large for the expansion, or no patch: vertexHydrostatics(tree.shares, …) (the clip-all result).
/// @param tree  buildMeshMomentTree(mesh)
/// @throws std::invalid_argument for a tree of another mesh, bad density/gravity or a non-finite pose
HydrostaticsResult treeHydrostatics(const MeshMomentTree& tree, const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                    const btWaterSurface& water, double time, double fluidDensity, double gravity,
                                    const Eigen::Vector3d& torqueReference, const WaterPatch* patch = nullptr);

/// clippedHydrostatics(mesh, pose, water, time, fluidDensity, gravity, torqueReference, patch) through the per-vertex
/// shares of the mesh (VertexShares.h, design.md 2.5): the same water model and the same result to rounding, with
/// one water height per vertex that can be under water, a few multiply-adds per wet vertex, and an exact clip only
/// for the triangles that straddle the waterline.
/// @param shares  buildVertexShares(mesh)
/// @throws std::invalid_argument for bad density/gravity or a non-finite pose; std::runtime_error for a non-finite
///         water height or result
HydrostaticsResult vertexHydrostatics(const VertexShares& shares, const Eigen::Isometry3d& pose,
                                      const btWaterSurface& water, double time, double fluidDensity, double gravity,
                                      const Eigen::Vector3d& torqueReference, const WaterPatch* patch = nullptr);

/// One water region of regionHydrostatics: the water of `water` (density `fluidDensity`) inside the convex set
/// {p : normal[k] · p ≤ offset[k], k < planeCount} (in the coordinates the pose and the surface use: the water frame).
struct WaterRegion {
    static constexpr int kMaxPlanes = 32;         ///< a box's sides, a footprint triangle's, a convex tank's walls
    const btWaterSurface* water = nullptr;        ///< not owned
    double fluidDensity = 1000.0;                 ///< ρ, kg/m³
    int planeCount = 0;                           ///< number of half-spaces bounding the region
    Eigen::Vector3d normal[kMaxPlanes];           ///< outward unit normals
    double offset[kMaxPlanes] = {};               ///< the region is normal · p ≤ offset, m
};

/// The exact-mesh method for a body in several water regions (design.md 2.9): every triangle of the posed mesh is cut
/// by each region's planes (Sutherland–Hodgman), and the part inside is clipped against that region's water (the plane
/// through the corners' heights, as clippedHydrostatics) and integrated with that region's density. The force and
/// torque are the pressure integral over the body's real wetted surface, each part pressed by its own water: exact for
/// flat waters. The volume and centre of buoyancy sum the parts' ∫(y − f) n_y fields, which cut faces parallel to up
/// (a box's sides) leave unchanged: exact for flat waters while the body stays above the regions' non-vertical cut
/// planes (a box's bottom). Regions must not overlap. No allocation per call (thread-local scratch).
/// @param regions  #count regions   @param gravity g, m/s²
/// @throws std::invalid_argument for bad density/gravity or a non-finite pose; std::runtime_error for a non-finite
///         water height or result
HydrostaticsResult regionHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose, const WaterRegion* regions,
                                      std::size_t count, double time, double gravity,
                                      const Eigen::Vector3d& torqueReference);

}  // namespace buoyancy
