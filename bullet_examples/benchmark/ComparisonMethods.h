#pragma once
/// @file ComparisonMethods.h
/// The methods other engines use, implemented here only to be measured against ours (design.md
/// 6); they are not part of the library.
///  - probes: point probes as spheres ("pontoons", the Unreal/Crest way). Each probe stands for a share of
///    the body's volume and pushes up with ρ g × the submerged volume of a sphere of that volume, applied at
///    its centre. "hull" probes sit on the surface (area-weighted clusters of the triangles), "grid" probes at
///    the centres of the interior cells of a voxel grid.
///  - downward-faces: the AQUAS way the paper compares with. Every triangle whose outward normal points down
///    and whose centroid is under water pushes up with ρ g depth(centroid) × its horizontal projected area,
///    applied at its centroid; upward-facing and side faces are ignored.
/// Both come with drag of the same kind as the library's (quadratic pressure drag on front-facing elements
/// plus linear damping, design.md 2.6) so that a body-substep does comparable work.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <BulletDynamics/Dynamics/btActionInterface.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

class btBuoyancyWorld;
class btRigidBody;
class btWaterSurface;

namespace buoyancy::bench {

/// Point probes, body (mesh) frame.
struct ProbeSet {
    std::vector<double> x, y, z;  ///< #P probe centres, m
    std::vector<double> radius;   ///< #P sphere radii, m (sphere volume = the probe's share)
    std::vector<double> share;    ///< #P volume shares, m³ (Σ = the body's volume)
    std::string variant;          ///< "hull-32", "grid-512", ...
    std::size_t size() const { return x.size(); }
};

/// About `target` probes on the hull: triangles clustered by a voxel grid over their centroids (cell size
/// tuned until the cluster count is within 25 % of target), one probe per cluster at the area-weighted
/// centroid, with a volume share proportional to the cluster's area. @param volume the body's volume, m³
ProbeSet makeHullProbes(const TriangleMesh& mesh, int target, double volume);

/// About `target` probes at the centres of the cells of a cubic grid whose centres are inside the mesh
/// (generalised winding number ≥ ½); shares equal, Σ = volume.
ProbeSet makeGridProbes(const TriangleMesh& mesh, int target, double volume);

/// Triangle centroids and area vectors, body frame (the elements of downward-faces).
struct FaceSet {
    std::vector<double> cx, cy, cz; ///< #T centroids, m
    std::vector<double> ax, ay, az; ///< #T area vectors (area × outward normal), m²
    std::size_t size() const { return cx.size(); }
};

/// The faces of a mesh.
FaceSet makeFaceSet(const TriangleMesh& mesh);

/// Result of a comparison method, world frame.
struct ComparisonResult {
    double volume = 0;                                    ///< the volume the method implies (F_y / ρ g), m³
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();     ///< where the resultant acts (force-weighted), m
    Eigen::Vector3d force = Eigen::Vector3d::Zero();      ///< N
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();     ///< about the reference point, N·m
};

/// Scratch arrays of one body (sized once).
struct ComparisonWorkspace {
    std::vector<double> wx, wy, wz, h;   ///< world positions and water heights
    std::vector<double> ax, ay, az;      ///< world area vectors (faces only)
    std::vector<double> ux, uy, uz;      ///< water velocity
    void resize(std::size_t n);
};

/// Probe buoyancy: per probe ρ g V_cap(depth) upward at the probe centre (V_cap: the submerged part of the
/// probe's sphere, π h² (3r − h)/3 with h = clamp(f − y + r, 0, 2r)).
ComparisonResult probeHydrostatics(const ProbeSet& probes, const Eigen::Isometry3d& pose, const btWaterSurface& water,
                                   double time, double rho, double g, const Eigen::Vector3d& ref, ComparisonWorkspace& ws);

/// AQUAS-style buoyancy: downward faces with a submerged centroid push up with ρ g (f − y_c) |A_y|.
ComparisonResult downwardFaceHydrostatics(const FaceSet& faces, const Eigen::Isometry3d& pose, const btWaterSurface& water,
                                          double time, double rho, double g, const Eigen::Vector3d& ref,
                                          ComparisonWorkspace& ws);

/// A Bullet action running one comparison method per substep on one body (the counterpart of
/// btBuoyancyAction for timing): buoyancy, drag (C_d = 1, linear damping 0.3 m/s as in btBuoyancySettings'
/// defaults) and the impulses F·dt, τ·dt. No added mass, no drag limiter, no sleeping logic.
class ComparisonAction : public btActionInterface {
public:
    /// Exactly one of probes/faces is non-null. The mesh sits at `meshInCom` in the body's COM frame.
    /// @param rho    water density, kg/m³   @param g  gravity, m/s²
    /// @param clock  optional: the water's time is this buoyancy world's (advanced per substep as btBuoyancyAction
    ///               does); nullptr: the action's own clock, from 0 by dt per call
    /// @param drag   false: buoyancy and its impulses only (the hydrostatics-only timing of the wave rows)
    ComparisonAction(btRigidBody* body, const ProbeSet* probes, const FaceSet* faces, const btWaterSurface* water,
                     const Eigen::Isometry3d& meshInCom, double rho = 1000.0, double g = 9.81,
                     btBuoyancyWorld* clock = nullptr, bool drag = true);
    void updateAction(btCollisionWorld* world, btScalar dt) override;
    void debugDraw(btIDebugDraw*) override {}
    /// Result of the last substep.
    const ComparisonResult& lastResult() const { return m_last; }

private:
    btRigidBody* m_body;
    const ProbeSet* m_probes;
    const FaceSet* m_faces;
    const btWaterSurface* m_water;
    Eigen::Isometry3d m_meshInCom;
    double m_rho, m_g, m_time = 0;
    btBuoyancyWorld* m_clock;
    std::uint64_t m_lastSubstep = 0;
    bool m_drag;
    ComparisonWorkspace m_ws;
    ComparisonResult m_last;
};

}  // namespace buoyancy::bench
