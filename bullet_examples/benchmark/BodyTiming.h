#pragma once
/// @file BodyTiming.h
/// Timing one body-substep: a Bullet world holding one dynamic body in flat water at y = 0, and a timer
/// that calls an action's updateAction (the work Bullet does per body per substep) many times at a fixed
/// pose with a fixed velocity (so drag is on), reporting nanoseconds per call. Give the timed actions
/// hydrostaticsInterval = 1: at a fixed pose the temporal level of detail would predict every other call.

#include <BulletBuoyancy/bullet/btBuoyancyShape.h>

#include <Eigen/Geometry>
#include <memory>

class btActionInterface;
class btRigidBody;
class btBuoyantBody;
class btBuoyancyWorld;
class btDiscreteDynamicsWorld;
class btFlatWaterSurface;

namespace buoyancy::bench {

/// How long to time.
struct TimingOptions {
    double minBatchSeconds = 2e-3; ///< each batch repeats the call until at least this long, s
    int batches = 3;               ///< batches; the reported time is the fastest batch's mean (least disturbed)
};

/// One body (density 500 kg/m³, convex-hull collision) in a btDiscreteDynamicsWorld with flat water at 0.
class SingleBodyRig {
public:
    /// @param shape  buoyancy data of the body (its mesh gives the mass properties)
    explicit SingleBodyRig(std::shared_ptr<const btBuoyancyShape> shape);
    ~SingleBodyRig();
    SingleBodyRig(const SingleBodyRig&) = delete;
    SingleBodyRig& operator=(const SingleBodyRig&) = delete;

    /// The body as built by the library.
    btBuoyantBody& body();
    /// The buoyancy context (flat water at 0, ρ = 1000, g = 9.81).
    btBuoyancyWorld& buoyancyWorld();
    /// The water.
    const btFlatWaterSurface& water() const;
    /// The mesh frame in the body's COM frame.
    Eigen::Isometry3d meshInCom() const;

    /// Mean time of one action.updateAction(world, 1/240 s) with the mesh at `meshPose` and the body moving
    /// at v = (0.5, −0.3, 0.2) m/s, ω = (0.2, 0.1, −0.3) rad/s (reset before every call, outside nothing:
    /// the reset, two setters, is included and costs a few ns), ns.
    double nsPerSubstep(btActionInterface& action, const Eigen::Isometry3d& meshPose, const TimingOptions& options);

private:
    struct Impl;
    std::unique_ptr<Impl> m;
};

}  // namespace buoyancy::bench
