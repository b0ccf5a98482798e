#pragma once
/// @file btBuoyancyMultiBodyAction.h
/// Buoyancy on the base and links of a btMultiBody in a btMultiBodyDynamicsWorld (a remotely operated vehicle with
/// an arm, a chain of pontoons joined by hinges): each part that has a collider floats with its collision shape,
/// through the same per-body evaluation as btBuoyancyAction (btBuoyancyImmediate), and its impulse is applied to
/// the multibody's generalized velocities at the end of each substep.

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>

#include <BulletDynamics/Dynamics/btActionInterface.h>
#include <LinearMath/btAlignedObjectArray.h>

#include <cstdint>
#include <memory>
#include <vector>

class btBuoyancyImmediate;
class btBuoyancyWorld;
class btMultiBody;
class btMultiBodyLinkCollider;

/// Buoyancy and drag on every part (base and links with a collider) of one btMultiBody.
///
/// What is modelled: each part's pressure force and torque (exact for its collision shape, flat water or waves) and
/// its drag, evaluated at the part's pose and velocity (its centre of mass: Bullet's link frame) as a btRigidBody of
/// the part's mass and inertia would be; the sum over the parts is applied once per substep as one generalized
/// impulse Σ Jᵀ(τ Δt, F Δt) (the parts' Jacobians at their centres of mass), so it acts through the joints as a
/// force on each link does. Not modelled: added mass (a part's added mass acts through the whole chain's inertia,
/// not as a scaling of its own force, so settings.addedMass is turned off here), water bodies (the parts float in the
/// world's unbounded water), flooding, and the temporal level of detail's exact-evaluation turns across parts.
/// Nothing accumulates in Bullet's link forces: Debian's Bullet clears them once per stepSimulation, not per
/// substep, and not at all for a sleeping multibody, so impulses are applied to the velocities instead. A sleeping
/// multibody gets nothing (its velocities are Bullet's to keep at rest).
class btBuoyancyMultiBodyAction : public btActionInterface {
public:
    /// @param multiBody  the multibody (not owned; must outlive the action's presence in a world); its base and links
    ///                   float with their colliders' collision shapes (btBuoyancyShape::fromCollisionShape) and their
    ///                   own masses and inertias; parts without a collider take no buoyancy
    /// @param world      the buoyancy context (not owned): its water, density, gravity, water frame and clock
    /// @param settings   drag and shape settings for every part (addedMass is turned off: see the class comment)
    /// @throws std::invalid_argument for a null argument, no part with a collider, a part of zero mass on a dynamic
    ///         multibody, an unsupported collision shape (naming the part and the shape type) or a bad setting
    btBuoyancyMultiBodyAction(btMultiBody* multiBody, btBuoyancyWorld* world,
                              const btBuoyancySettings& settings = btBuoyancySettings());
    ~btBuoyancyMultiBodyAction() override;
    btBuoyancyMultiBodyAction(const btBuoyancyMultiBodyAction&) = delete;
    btBuoyancyMultiBodyAction& operator=(const btBuoyancyMultiBodyAction&) = delete;

    /// Called by Bullet once per substep after the multibodies moved: evaluates every part, applies the impulses.
    void updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) override;
    /// Draws nothing.
    void debugDraw(btIDebugDraw*) override {}

    /// The multibody.
    btMultiBody* getMultiBody() const { return m_multiBody; }
    /// The result of the last substep for part `link` (−1: the base), or nullptr when that part has no collider.
    const btBuoyancyResult* getPartResult(int link) const;
    /// Submerged volume of every part together in the last substep, m³.
    double getSubmergedVolume() const;

    /// The state this action carries from substep to substep, as bytes (btBuoyancyState.h): each part's
    /// (btBuoyancyImmediate::saveState). Restore the world (btBuoyancyWorld::restoreState) and the multibody's own
    /// state (base pose and velocity, joint positions and velocities) too, and the next substeps repeat bit for bit.
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote into an action built the same way (same multibody layout and settings). Read and
    /// checked whole; a blob either applies completely or not at all.
    /// @throws std::invalid_argument naming the problem (wrong kind, truncated, checksum, another multibody's parts)
    void restoreState(const unsigned char* data, std::size_t size);
    /// restoreState of a whole vector. @throws std::invalid_argument (see above)
    void restoreState(const std::vector<unsigned char>& blob) { restoreState(blob.data(), blob.size()); }

private:
    struct Part;
    btMultiBody* m_multiBody;
    btBuoyancyWorld* m_world;
    std::vector<std::unique_ptr<Part>> m_parts;
    std::uint64_t m_lastSubstep = 0;
    btAlignedObjectArray<btScalar> m_jacobian, m_force, m_deltaV, m_scratchR;
    btAlignedObjectArray<btVector3> m_scratchV, m_omega, m_velocity;
    btAlignedObjectArray<btMatrix3x3> m_scratchM;
};
