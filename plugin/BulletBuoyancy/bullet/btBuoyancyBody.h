#pragma once
/// @file btBuoyancyBody.h
/// The body a btBuoyancyAction floats, as the action sees it: what it reads each substep (pose, centre of mass,
/// velocities, inverse mass and inertia, gravity, the forces waiting for the next integration, whether it is in a
/// world and awake) and what it writes (impulses at the centre of mass, sleeping thresholds, wake-ups, mass and
/// inertia). btBuoyancyRigidBody implements it for a btRigidBody (what the action's btRigidBody constructors use);
/// another body type implements it once and floats through the same action (design.md 8.3).
///
/// The contract follows Bullet's order of a substep (design.md 3): the action reads the body after the engine has
/// integrated the transforms and before it applies the next substep's forces, and its impulses change the velocities
/// the next integration starts from. Read calls are made from the batch's worker threads for different bodies at
/// once (one body is only ever read by one thread at a time); write calls come from the thread that steps the world.

#include <LinearMath/btMatrix3x3.h>
#include <LinearMath/btScalar.h>
#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

class btCollisionObject;
class btRigidBody;

/// A body that floats: the reads and writes of btBuoyancyAction. All quantities are in the world frame and SI units.
class btBuoyancyBody {
public:
    virtual ~btBuoyancyBody() = default;

    ///@name Read each substep
    /// The centre-of-mass frame in the world: origin at the centre of mass, axes the principal axes of inertia (m).
    virtual const btTransform& getWorldTransform() const = 0;
    /// The centre of mass in the world, m (the origin of getWorldTransform; the reference point of the torques).
    const btVector3& getCenterOfMassPosition() const { return getWorldTransform().getOrigin(); }
    /// Velocity of the centre of mass, m/s.
    virtual const btVector3& getLinearVelocity() const = 0;
    /// Angular velocity, rad/s.
    virtual const btVector3& getAngularVelocity() const = 0;
    /// Inverse mass, 1/kg; 0 for a body that does not move under forces (static or kinematic: it gets no buoyancy).
    virtual btScalar getInvMass() const = 0;
    /// Inverse principal moments of inertia about the centre of mass, in the axes of getWorldTransform, 1/(kg m²);
    /// a component 0 is a locked or infinitely heavy axis.
    virtual const btVector3& getInvInertiaDiagLocal() const = 0;
    /// The inverse inertia tensor in world axes, 1/(kg m²) (R diag(getInvInertiaDiagLocal) Rᵀ).
    virtual const btMatrix3x3& getInvInertiaTensorWorld() const = 0;
    /// The acceleration the engine adds to this body's velocity at its next integration (its weight per unit mass),
    /// m/s².
    virtual const btVector3& getGravity() const = 0;
    /// Per-axis scale of linear velocity changes (1 free, 0 locked), dimensionless.
    virtual const btVector3& getLinearFactor() const = 0;
    /// Per-axis scale of angular velocity changes (1 free, 0 locked), dimensionless.
    virtual const btVector3& getAngularFactor() const = 0;
    /// The force accumulated on the body for its next integration (the user's forces; not the impulses), N.
    virtual const btVector3& getTotalForce() const = 0;
    /// The torque accumulated on the body for its next integration, N m.
    virtual const btVector3& getTotalTorque() const = 0;
    /// True while the body is in the world being stepped (a body taken out of its world gets nothing).
    virtual bool isInWorld() const = 0;
    /// True while the body is awake (a sleeping body in calm water is left asleep).
    virtual bool isActive() const = 0;
    /// The body's own linear sleeping threshold, m/s (read once, when the action is made).
    virtual btScalar getLinearSleepingThreshold() const = 0;
    /// The body's own angular sleeping threshold, rad/s (read once, when the action is made).
    virtual btScalar getAngularSleepingThreshold() const = 0;
    /// The principal moments of inertia, kg m² (0 where the inverse is 0).
    btVector3 getLocalInertia() const {
        const btVector3& inv = getInvInertiaDiagLocal();
        return btVector3(inv.x() != btScalar(0) ? btScalar(1) / inv.x() : btScalar(0),
                         inv.y() != btScalar(0) ? btScalar(1) / inv.y() : btScalar(0),
                         inv.z() != btScalar(0) ? btScalar(1) / inv.z() : btScalar(0));
    }

    ///@name Write, at the action's turn
    /// Apply an impulse at the centre of mass (N s) and an angular impulse (N m s): the velocities change by
    /// linearImpulse × invMass × linearFactor and invInertiaWorld × angularImpulse × angularFactor.
    virtual void applyCentralImpulses(const btVector3& linearImpulse, const btVector3& angularImpulse) = 0;
    /// Wake the body (forceActivation: also one whose activation state forbids it, as btCollisionObject::activate).
    virtual void activate(bool forceActivation) = 0;
    /// Set the speeds under which the engine counts the body down to sleep, m/s and rad/s (the action opens them to
    /// let a body at rest on the water sleep, and puts the body's own back).
    virtual void setSleepingThresholds(btScalar linear, btScalar angular) = 0;
    /// Set the mass (kg, > 0) and the principal moments of inertia about the centre of mass (kg m², in the axes of
    /// getWorldTransform), and update the world inverse inertia (btBuoyancyAction::setBodyMassFromShape).
    virtual void setMassProps(btScalar mass, const btVector3& localInertia) = 0;

    ///@name The engine's objects behind it
    /// The Bullet rigid body, or nullptr when the body is not one.
    virtual btRigidBody* getRigidBody() const { return nullptr; }
    /// The collision object that is in the world when the body is (a debug-build misuse check looks for it in the
    /// world being stepped), or nullptr.
    virtual const btCollisionObject* getCollisionObject() const { return nullptr; }
};

/// btBuoyancyBody for a btRigidBody: every call forwards to the body (the action's btRigidBody constructors make one).
class btBuoyancyRigidBody final : public btBuoyancyBody {
public:
    /// @param body  the rigid body (not owned; must outlive this)
    explicit btBuoyancyRigidBody(btRigidBody* body) : m_body(body) {}

    const btTransform& getWorldTransform() const override;
    const btVector3& getLinearVelocity() const override;
    const btVector3& getAngularVelocity() const override;
    btScalar getInvMass() const override;
    const btVector3& getInvInertiaDiagLocal() const override;
    const btMatrix3x3& getInvInertiaTensorWorld() const override;
    const btVector3& getGravity() const override;
    const btVector3& getLinearFactor() const override;
    const btVector3& getAngularFactor() const override;
    const btVector3& getTotalForce() const override;
    const btVector3& getTotalTorque() const override;
    /// In a world: the body has a broadphase handle.
    bool isInWorld() const override;
    bool isActive() const override;
    btScalar getLinearSleepingThreshold() const override;
    btScalar getAngularSleepingThreshold() const override;
    /// applyCentralImpulse, then applyTorqueImpulse (Bullet's order and rounding).
    void applyCentralImpulses(const btVector3& linearImpulse, const btVector3& angularImpulse) override;
    void activate(bool forceActivation) override;
    void setSleepingThresholds(btScalar linear, btScalar angular) override;
    /// setMassProps, then updateInertiaTensor.
    void setMassProps(btScalar mass, const btVector3& localInertia) override;
    btRigidBody* getRigidBody() const override { return m_body; }
    const btCollisionObject* getCollisionObject() const override;

private:
    btRigidBody* m_body;
};
