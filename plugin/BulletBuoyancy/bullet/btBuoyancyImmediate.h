#pragma once
/// @file btBuoyancyImmediate.h
/// Immediate mode: buoyancy for users who run their own loop. One call per body and step evaluates the body in the
/// water at its current pose and velocity and applies the impulses for the step, through the same per-body
/// evaluation as btBuoyancyAction (exact hydrostatics, waves, drag, added mass, temporal level of detail); the object
/// holds what that evaluation keeps from step to step (level-of-detail history, water-query caches).

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <cstddef>
#include <memory>
#include <vector>

class btRigidBody;
class btWaterSurface;

/// The buoyancy state of one body stepped by its owner's loop (not added to a Bullet world as an action).
///
/// Usage, once per step of your loop, after gravity has been applied to the body's velocity (as Bullet's
/// stepSimulation does before it calls actions) and before you move the body by its velocity:
/// @code
///   btBuoyancyImmediate buoyancy(&body);                       // geometry from the body's collision shape
///   ...
///   const btBuoyancyResult& r = buoyancy.applyBuoyancyImpulse(water, gravity, 1000.0, time, dt);
/// @endcode
/// The impulses are applied to the body and returned in the result (linearImpulse, angularImpulse). The added mass
/// counts on the gravity your loop applies (m g dt), as it counts on Bullet's: each call sets the body's own gravity
/// (btRigidBody::setGravity, the weight Bullet's integrateVelocities would apply) to the `gravity` given.
class btBuoyancyImmediate {
public:
    /// Your body as it is: the geometry is its collision shape (btBuoyancyShape::fromCollisionShape), the mass and
    /// inertia are the body's own. @throws std::invalid_argument as btBuoyancyAction's constructor
    explicit btBuoyancyImmediate(btRigidBody* body, const btBuoyancySettings& settings = btBuoyancySettings());
    /// A body floating with an explicit buoyancy shape held at `meshInCom` in the body's centre-of-mass frame.
    /// @throws std::invalid_argument as btBuoyancyAction's constructor
    btBuoyancyImmediate(btRigidBody* body, std::shared_ptr<const btBuoyancyShape> shape,
                        const btBuoyancySettings& settings = btBuoyancySettings(),
                        const btTransform& meshInCom = btTransform::getIdentity());
    /// A body of another type (btBuoyancyBody.h) floating with `shape` held at `meshInCom` in its centre-of-mass frame.
    /// Its getGravity() must return the gravity given to applyBuoyancyImpulse (the weight your loop applies).
    /// @throws std::invalid_argument as btBuoyancyAction's constructor
    btBuoyancyImmediate(btBuoyancyBody& body, std::shared_ptr<const btBuoyancyShape> shape,
                        const btBuoyancySettings& settings = btBuoyancySettings(),
                        const btTransform& meshInCom = btTransform::getIdentity());
    btBuoyancyImmediate(const btBuoyancyImmediate&) = delete;
    btBuoyancyImmediate& operator=(const btBuoyancyImmediate&) = delete;

    /// Evaluate the body in `water` and apply the impulses for a step of `dt`.
    /// @param water         the surface, a height field along the water frame's up (not kept beyond the call)
    /// @param gravity       the gravity your loop applies, m/s², world frame; "up" is −gravity. The water frame
    ///                      (btWaterFrame::fromGravity) is derived from the first non-zero gravity and kept; a later
    ///                      gravity not along it gives status GravityNotAlongWaterUp and no impulse; zero gravity
    ///                      gives no buoyancy
    /// @param fluidDensity  ρ, kg/m³, > 0
    /// @param time          the water's time at the pose the body has now (the end of the step), s
    /// @param dt            step, s; a zero, negative or non-finite step applies nothing
    /// @return the evaluation (the same fields as btBuoyancyAction::getLastResult), valid until the next call
    /// @throws std::invalid_argument for a non-finite gravity or a bad density (nothing applied)
    const btBuoyancyResult& applyBuoyancyImpulse(const btWaterSurface& water, const btVector3& gravity,
                                                 double fluidDensity, double time, double dt);

    /// The per-body evaluation (settings, shape, setBodyMassFromShape, the last result).
    btBuoyancyAction& getAction() { return *m_action; }
    /// The private context: its water frame (setWaterFrame for a frame of your own) and clock.
    btBuoyancyWorld& getContext() { return m_context; }

    /// The state this object carries from step to step, as bytes (btBuoyancyState.h): its context's (water frame,
    /// clock, gravity) and its evaluation's (level-of-detail history, the water queries' warm starts, sleep decision,
    /// last result). The warm starts belong to the water last given to applyBuoyancyImpulse (remembered by address
    /// only, never read). With your body's own state (transform, velocities, activation state, deactivation time,
    /// sleeping thresholds) restored too, the next steps repeat bit for bit.
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote into an object built the same way (same shape and settings). `water` is the
    /// surface the next steps will use, whose warm starts the blob holds (nullptr: the water last given to
    /// applyBuoyancyImpulse; with neither, the warm starts are dropped and the next results differ in the last bits).
    /// Read and checked whole; a blob either applies completely or not at all.
    /// @throws std::invalid_argument naming the problem (wrong kind, truncated, checksum, another body's state, ...)
    void restoreState(const unsigned char* data, std::size_t size, const btWaterSurface* water = nullptr);
    /// restoreState of a whole vector. @throws std::invalid_argument (see above)
    void restoreState(const std::vector<unsigned char>& blob, const btWaterSurface* water = nullptr) {
        restoreState(blob.data(), blob.size(), water);
    }

private:
    btBuoyancyWorld m_context;
    std::unique_ptr<btBuoyancyAction> m_action;
    const btWaterSurface* m_lastWater = nullptr;  ///< the water of the last call, by address (its warm starts' owner)
};
