#pragma once
/// @file BodyTiming.h
/// Timing one body-substep: a Bullet world holding one dynamic body in flat water at y = 0 (or in a given water
/// surface), and a timer that calls an action's updateAction (the work Bullet does per body per substep) many times
/// at a fixed pose with a fixed velocity (so drag is on), reporting nanoseconds per call. Give the timed actions
/// hydrostaticsInterval = 1: at a fixed pose the temporal level of detail would predict every other call.

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>

#include <Eigen/Geometry>
#include <memory>

class btActionInterface;
class btRigidBody;
class btBuoyantBody;
class btBuoyancyWorld;
class btDiscreteDynamicsWorld;
class btFlatWaterSurface;
class btWaterSurface;

namespace buoyancy::bench {

/// How long to time.
struct TimingOptions {
    double minBatchSeconds = 2e-3; ///< each batch repeats the call until at least this long, s
    int batches = 3;               ///< batches; the reported time is the fastest batch's mean (least disturbed)
};

/// One body (density 500 kg/m³, convex-hull collision) in a btDiscreteDynamicsWorld with flat water at 0, or in
/// the water surface given.
class SingleBodyRig {
public:
    /// @param shape  buoyancy data of the body (its mesh gives the mass properties)
    /// @param water  the water of the rig's buoyancy world (not owned, outlives the rig); nullptr: flat water at 0
    explicit SingleBodyRig(std::shared_ptr<const btBuoyancyShape> shape, const btWaterSurface* water = nullptr);
    ~SingleBodyRig();
    SingleBodyRig(const SingleBodyRig&) = delete;
    SingleBodyRig& operator=(const SingleBodyRig&) = delete;

    /// The body as built by the library.
    btBuoyantBody& body();
    /// The buoyancy context (flat water at 0, ρ = 1000, g = 9.81).
    btBuoyancyWorld& buoyancyWorld();
    /// The rig's own flat water at 0 (the buoyancy world's water when no surface was given).
    const btFlatWaterSurface& water() const;
    /// The water the buoyancy world uses: the surface given to the constructor, else water().
    const btWaterSurface& surface() const;
    /// The mesh frame in the body's COM frame.
    Eigen::Isometry3d meshInCom() const;

    /// Mean time of one action.updateAction(world, 1/240 s) with the mesh at `meshPose` and the body moving
    /// at v = (0.5, −0.3, 0.2) m/s, ω = (0.2, 0.1, −0.3) rad/s (reset before every call, outside nothing:
    /// the reset, two setters, is included and costs a few ns), ns. The buoyancy world's clock is set before every
    /// call so that the calls evaluate the water at `time` and `time` + 1/240 s in turn (s): on waves every call then
    /// makes its wave queries as in a running simulation, warm-started one substep away (btWaterQueryCache), never
    /// answered from a repeat at the same time, while the body stays at the same place on the wave. Actions that
    /// follow the water's clock: btBuoyancyAction, and the benchmark's actions given the rig's buoyancyWorld().
    double nsPerSubstep(btActionInterface& action, const Eigen::Isometry3d& meshPose, const TimingOptions& options,
                        double time = 0.0);

    /// Put the body at `meshPose` (the mesh frame in world) and return the mesh pose as the body holds it (Bullet's
    /// btScalar rounding; what the actions see), m.
    Eigen::Isometry3d heldMeshPose(const Eigen::Isometry3d& meshPose);
    /// The body's centre of mass, world, m (after heldMeshPose: the torque reference the actions use).
    Eigen::Vector3d centreOfMass() const;

    /// One action.updateAction(world, 1/240 s) at `meshPose`, body at rest, with the water evaluated at `time` (s);
    /// returns what it computed (getLastResult()).
    const btBuoyancyResult& evaluate(btBuoyancyAction& action, const Eigen::Isometry3d& meshPose, double time);

private:
    /// Set the body's transform so that the mesh is at meshPose.
    void place(const Eigen::Isometry3d& meshPose);
    struct Impl;
    std::unique_ptr<Impl> m;
};

}  // namespace buoyancy::bench
