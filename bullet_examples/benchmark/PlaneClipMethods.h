#pragma once
/// @file PlaneClipMethods.h
/// Two comparison methods for waves that replace the water under a body by one plane and clip the mesh exactly
/// against it (benchmark rows `tangent-plane` and `fitted-plane`; not library methods):
///  - tangent-plane: the plane through the surface point vertically above the body's centre of mass (the height
///    query at the COM's (x, z), not the wave particle at rest there) with the surface's normal there (central
///    differences of four more height queries). This is Jolt's approach (Body::ApplyBuoyancyImpulse takes one
///    surface position and normal per body).
///  - fitted-plane: the least-squares plane through the water heights at the four corners and the centre of the
///    body's horizontal bounding box.
/// The part of the mesh below the plane is found exactly: the mesh is posed in the plane's frame, where the plane
/// is y' = 0, and clipped by the library's flat-water exact clip (buoyancy::clippedHydrostatics with a
/// btFlatWaterSurface at 0); its volume and centroid are rotated back to world. The force is Archimedes' ρ g V_sub
/// straight up (against gravity, as Jolt applies it) at that centroid.

#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btActionInterface.h>

#include <Eigen/Geometry>
#include <cstdint>

class btBuoyancyWorld;
class btRigidBody;

namespace buoyancy::bench {

/// A plane standing for the water surface, world frame.
struct WaterPlane {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< a point on the plane, m
    Eigen::Vector3d normal = Eigen::Vector3d::UnitY(); ///< unit normal pointing up out of the water
};

/// Central-difference step of the tangent plane's slope, m.
constexpr double kTangentPlaneStep = 1e-3;

/// The tangent plane of the water at (x, z): the height there and the normal (−η_x, 1, −η_z)/|·| from central
/// differences with step `step`; five heights in one batch query.
/// @param x,z    world position, m   @param time  water time, s   @param step  central-difference step, m
/// @param cache  optional per-caller warm-start memory of the surface (btWaterSurface::heightsCached)
WaterPlane tangentWaterPlane(const btWaterSurface& water, double x, double z, double time,
                             double step = kTangentPlaneStep, btWaterQueryCache* cache = nullptr);

/// The least-squares plane h = a + b (x − c_x) + c (z − c_z) through the water heights at the four corners and the
/// centre (c_x, c_z) of the rectangle [minX, maxX] × [minZ, maxZ] (world, m) at `time` (s); five heights in one batch
/// query. For this symmetric stencil a is the mean height, b and c the corner differences over the extents.
WaterPlane fittedWaterPlane(const btWaterSurface& water, double minX, double minZ, double maxX, double maxZ,
                            double time, btWaterQueryCache* cache = nullptr);

/// Exact part of the mesh (posed by `pose`, mesh → world) below `plane`: submerged volume (m³) and centre of
/// buoyancy (world, m) by the library's flat-water clip in the plane's frame; force ρ g V_sub straight up (N), its
/// torque about `torqueReference` (world, m; N·m). Waterline and wetted areas are the clip's (m²); no waterplane
/// moments.
/// @param fluidDensity ρ, kg/m³   @param gravity g, m/s²
HydrostaticsResult planeClipHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                         const WaterPlane& plane, double fluidDensity, double gravity,
                                         const Eigen::Vector3d& torqueReference);

/// Which plane.
enum class PlaneMethod {
    Tangent, ///< tangent-plane: under the centre of mass
    Fitted,  ///< fitted-plane: least squares over the horizontal bounding box
};

/// The CSV name: "tangent-plane" or "fitted-plane".
const char* planeMethodName(PlaneMethod method);

/// One evaluation of a plane method, its wave queries included: the plane (tangent: at the (x, z) of
/// `centreOfMass`; fitted: over the horizontal bounding box of the mesh's bounding box `localBounds` posed by
/// `pose`, its 8 corners transformed), then planeClipHydrostatics with the torque about `centreOfMass`.
/// @param localBounds  the mesh's axis-aligned bounding box in its own frame, m
/// @param time         water time, s   @param fluidDensity ρ, kg/m³   @param gravity g, m/s²
/// @param cache        optional warm-start memory of the height queries
HydrostaticsResult planeMethodHydrostatics(PlaneMethod method, const TriangleMesh& mesh,
                                           const Eigen::AlignedBox3d& localBounds, const Eigen::Isometry3d& pose,
                                           const btWaterSurface& water, double time, double fluidDensity,
                                           double gravity, const Eigen::Vector3d& centreOfMass,
                                           btWaterQueryCache* cache = nullptr);

/// A Bullet action running a plane method per substep on one body (for timing, the counterpart of
/// btBuoyancyAction): the hydrostatic impulses F·dt, τ·dt, plus, when given, the drag of a btBuoyancyAction with
/// buoyancy disabled (the library's default drag path: drag clusters, wave patch, drag limiter). No added mass.
class PlaneMethodAction : public btActionInterface {
public:
    /// @param body       the body (not owned); the mesh sits at `meshInCom` in its COM frame
    /// @param mesh       the body's mesh (not owned)
    /// @param water      the water (not owned)
    /// @param clock      the buoyancy world whose time the water is evaluated at (advanced per substep as
    ///                   btBuoyancyAction does; not owned)
    /// @param drag       optional: a btBuoyancyAction on the same body and clock with settings.buoyancyEnabled = false
    ///                   (not owned); nullptr: hydrostatics only
    /// @param fluidDensity ρ, kg/m³   @param gravity g, m/s²
    PlaneMethodAction(btRigidBody* body, PlaneMethod method, const TriangleMesh* mesh, const btWaterSurface* water,
                      btBuoyancyWorld* clock, const Eigen::Isometry3d& meshInCom, btActionInterface* drag = nullptr,
                      double fluidDensity = 1000.0, double gravity = 9.81);
    void updateAction(btCollisionWorld* world, btScalar dt) override;
    void debugDraw(btIDebugDraw*) override {}
    /// Result of the last substep (world frame, torque about the COM).
    const HydrostaticsResult& lastResult() const { return m_last; }

private:
    btRigidBody* m_body;
    PlaneMethod m_method;
    const TriangleMesh* m_mesh;
    Eigen::AlignedBox3d m_bounds;
    const btWaterSurface* m_water;
    btBuoyancyWorld* m_clock;
    Eigen::Isometry3d m_meshInCom;
    btActionInterface* m_drag;
    double m_rho, m_g;
    std::uint64_t m_lastSubstep = 0;
    btWaterQueryCache m_cache;
    HydrostaticsResult m_last;
};

}  // namespace buoyancy::bench
