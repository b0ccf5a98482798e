#pragma once
/// @file btBuoyancyDeviceBackend.h
/// The seam between btBuoyancyAction and a batching compute backend: a backend installed on a
/// btBuoyancyWorld computes the hydrostatics (and then the drag) of every sampled body of the world in one
/// batch per substep, when the first action of the substep asks, and answers the other actions from it.
/// A backend may decline any body (return false): the action then computes it on the CPU, so results never
/// depend on which bodies a backend handles. A backend sees each body through btBuoyancyDeviceBody (a record per
/// substep and the two per-body quantities of the drag batch), never the action. Implementation: btOpenClBuoyancyBackend.

#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <Eigen/Geometry>
#include <memory>
#include <string>

namespace buoyancy {
struct SurfaceSamples;
struct DragClusters;
}  // namespace buoyancy
class btBuoyancyDeformable;
class btWaterSurface;

/// One body of this substep as a batching backend sees it (btBuoyancyDeviceBody::deviceRecord), in the world's water
/// frame (btBuoyancyWorld::getWaterFrame). Pointers stay valid until the end of the substep.
struct btBuoyancyDeviceRecord {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< the mesh's pose, water frame
    Eigen::Vector3d com = Eigen::Vector3d::Zero();           ///< centre of mass, water frame, m
    const buoyancy::SurfaceSamples* samples = nullptr;       ///< the hydrostatic samples in use, mesh frame
    /// The shape or deformable that owns `samples`: bodies with the same owner share one copy on the device, which
    /// keeps it alive while it holds that copy.
    std::shared_ptr<const void> samplesOwner;
    /// Non-null when the samples follow a deformable mesh (the backend re-bakes them when its vertices change).
    const btBuoyancyDeformable* deformable = nullptr;
    const buoyancy::DragClusters* dragClusters = nullptr;    ///< the drag clusters (none or empty: no drag)
    double dragCoefficient = 0;  ///< C_d of the pressure drag, dimensionless
    double skinFriction = 0;     ///< C_f of the skin friction, dimensionless
    bool dragOn = false;         ///< any drag term (pressure drag, skin friction, linear or radiation damping) is on
};

/// What a batching backend needs of one body, without the body's type (implemented by btBuoyancyAction): the bodies
/// of a world are btBuoyancyWorld::getDeviceBodies.
class btBuoyancyDeviceBody {
public:
    /// This substep's record of the body when it is one the backend may compute: a sampled method, buoyancy on, in
    /// reach of the water, neither dry nor under flat water (the closed form), awake or in changing water. The same
    /// gating as the body's own evaluation, so a backend never computes a body that would not ask.
    /// @param water  the world's water   @param time  its time, s
    /// @return false when the body computes itself (`out` unspecified)
    virtual bool deviceRecord(const btWaterSurface& water, double time, btBuoyancyDeviceRecord& out) const = 0;
    /// The velocities its drag is evaluated at this substep, given its hydrostatics `h` (water frame).
    /// @param dt  substep, s   @param[out] v  m/s   @param[out] w  rad/s
    virtual void dragEvaluationVelocity(const buoyancy::HydrostaticsResult& h, double dt, Eigen::Vector3d& v,
                                        Eigen::Vector3d& w) const = 0;
    /// The linear damping coefficient of this substep's drag, m/s, given its hydrostatics and the mesh's pose (water
    /// frame).
    virtual double linearDampingNow(const buoyancy::HydrostaticsResult& h, const Eigen::Isometry3d& pose) const = 0;

protected:
    ~btBuoyancyDeviceBody() = default;
};

/// Abstract batching backend of one btBuoyancyWorld.
class btBuoyancyDeviceBackend {
public:
    virtual ~btBuoyancyDeviceBackend() = default;

    /// Called by btBuoyancyWorld::beginSubstepIfNew when a new substep starts (the world's clock already advanced).
    /// @param dt  the substep, s
    virtual void beginSubstep(double dt) = 0;

    /// This substep's hydrostatics (design.md 2.2–2.3, torque about `com`) of `body` at `pose`.
    /// The first call of a substep computes every body of the world in one batch.
    /// @return false when the backend does not handle this body (or the pose differs from the batch's): compute on the CPU
    virtual bool hydrostatics(const btBuoyancyDeviceBody& body, const Eigen::Isometry3d& pose, const Eigen::Vector3d& com,
                              buoyancy::HydrostaticsResult& out) = 0;

    /// This substep's drag (design.md 2.6) of `body` evaluated at velocities (v, w), after hydrostatics() answered
    /// true for it. The first call of a substep computes every body in one batch, each at
    /// btBuoyancyDeviceBody::dragEvaluationVelocity of its hydrostatics, with the linear damping coefficient
    /// btBuoyancyDeviceBody::linearDampingNow.
    /// @param[out] force, torque  N, N·m   @param[out] meanWaterVelocity  area-weighted over the wetted clusters, m/s
    /// @param[out] linearDampingPower  the power of the linear damping alone, W (≤ 0; BB_DRAG_TERMS' part[10])
    /// @return false when not handled or when (com, v, w) differ from the batch's: compute on the CPU
    virtual bool drag(const btBuoyancyDeviceBody& body, const Eigen::Vector3d& com, const Eigen::Vector3d& v,
                      const Eigen::Vector3d& w, Eigen::Vector3d& force, Eigen::Vector3d& torque,
                      Eigen::Vector3d& meanWaterVelocity, double& linearDampingPower) = 0;

    /// One line for logs, e.g. "OpenCL: pthread-skylake (Portable Computing Language), double (cl_khr_fp64)".
    virtual std::string describe() const = 0;
};
