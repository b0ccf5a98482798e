#pragma once
/// @file btBuoyancyDeviceBackend.h
/// The seam between btBuoyancyAction and a batching compute backend: a backend installed on a
/// btBuoyancyWorld computes the hydrostatics (and then the drag) of every sampled body of the world in one
/// batch per substep, when the first action of the substep asks, and answers the other actions from it.
/// A backend may decline any body (return false): the action then computes it on the CPU, so results never
/// depend on which bodies a backend handles. Implementation: btOpenClBuoyancyBackend.

#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <Eigen/Geometry>
#include <string>

class btBuoyancyAction;

/// Abstract batching backend of one btBuoyancyWorld.
class btBuoyancyDeviceBackend {
public:
    virtual ~btBuoyancyDeviceBackend() = default;

    /// Called by btBuoyancyWorld::beginSubstepIfNew when a new substep starts (the world's clock already advanced).
    /// @param dt  the substep, s
    virtual void beginSubstep(double dt) = 0;

    /// This substep's hydrostatics (design.md 2.2–2.3, torque about `com`) of `action`'s body at `pose`.
    /// The first call of a substep computes every body of the world in one batch.
    /// @return false when the backend does not handle this body (or the pose differs from the batch's): compute on the CPU
    virtual bool hydrostatics(const btBuoyancyAction& action, const Eigen::Isometry3d& pose, const Eigen::Vector3d& com,
                              buoyancy::HydrostaticsResult& out) = 0;

    /// This substep's drag (design.md 2.6) of `action`'s body evaluated at velocities (v, w), after
    /// hydrostatics() answered true for it. The first call of a substep computes every body in one batch, each at
    /// btBuoyancyAction::dragEvaluationVelocity of its hydrostatics.
    /// Each body's linear damping coefficient is btBuoyancyAction::linearDampingNow of its hydrostatics and pose.
    /// @param[out] force, torque  N, N·m   @param[out] meanWaterVelocity  area-weighted over the wetted clusters, m/s
    /// @param[out] linearDampingPower  the power of the linear damping alone, W (≤ 0; BB_DRAG_TERMS' part[10])
    /// @return false when not handled or when (com, v, w) differ from the batch's: compute on the CPU
    virtual bool drag(const btBuoyancyAction& action, const Eigen::Vector3d& com, const Eigen::Vector3d& v,
                      const Eigen::Vector3d& w, Eigen::Vector3d& force, Eigen::Vector3d& torque,
                      Eigen::Vector3d& meanWaterVelocity, double& linearDampingPower) = 0;

    /// One line for logs, e.g. "OpenCL: pthread-skylake (Portable Computing Language), double (cl_khr_fp64)".
    virtual std::string describe() const = 0;
};
