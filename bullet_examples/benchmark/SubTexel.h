#pragma once
/// @file SubTexel.h
/// The sub-texel waterline method of design.md 2.4 (benchmark rows `sub-texel`; not a library method):
/// exact-coverage samples, but a sample straddling the waterline counts only its wet part. Each sample is
/// treated as a uniform strip along world y of half extent h_V = sqrt(area)/2 · sqrt(1 − n_y²) (a square
/// piece of the sample's area, tilted by its normal; the drag ramp's estimate, no stored covariance). Its wet
/// part is the fraction w = clamp((f − (y − h_V)) / 2h_V, 0, 1) with centroid y_w at the middle of the wet
/// strip; the fields of design.md 2.2 / 2.3 are summed as w × (their value at y_w), with the strip's own
/// variance L_w²/12 in the ∫y field. A horizontal sample (h_V = 0) is wet by its centre, as in exact-coverage.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <BulletDynamics/Dynamics/btActionInterface.h>
#include <Eigen/Geometry>

#include <memory>

class btRigidBody;
class btWaterSurface;
class btBuoyancyAction;

namespace buoyancy::bench {

/// Sub-texel hydrostatics of `samples` at `pose` (body → world) in `water` at `time`; torque about `ref`.
HydrostaticsResult subTexelHydrostatics(const SurfaceSamples& samples, const Eigen::Isometry3d& pose,
                                        const btWaterSurface& water, double time, double rho, double g,
                                        const Eigen::Vector3d& ref, SampleWorkspace& ws);

/// A Bullet action for timing the sub-texel method: the hydrostatic impulse from subTexelHydrostatics plus the
/// drag of a btBuoyancyAction with buoyancy disabled (the library's drag, same settings otherwise).
class SubTexelAction : public btActionInterface {
public:
    /// @param drag    a btBuoyancyAction on the same body with settings.buoyancyEnabled = false (not owned)
    SubTexelAction(btRigidBody* body, const SurfaceSamples* samples, const btWaterSurface* water,
                   const Eigen::Isometry3d& meshInCom, btActionInterface* drag, double rho = 1000.0, double g = 9.81);
    void updateAction(btCollisionWorld* world, btScalar dt) override;
    void debugDraw(btIDebugDraw*) override {}

private:
    btRigidBody* m_body;
    const SurfaceSamples* m_samples;
    const btWaterSurface* m_water;
    Eigen::Isometry3d m_meshInCom;
    btActionInterface* m_drag;
    double m_rho, m_g;
    SampleWorkspace m_ws;
};

}  // namespace buoyancy::bench
