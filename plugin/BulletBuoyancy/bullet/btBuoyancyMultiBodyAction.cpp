#include <BulletBuoyancy/bullet/btBuoyancyMultiBodyAction.h>

#include <BulletBuoyancy/bullet/btBuoyancyBody.h>
#include <BulletBuoyancy/bullet/btBuoyancyImmediate.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace {

/// One part (the base or a link) of a multibody as a btBuoyancyBody: its collider's pose, its velocity at its centre of
/// mass (Bullet's link frame) and its own mass and inertia, set by the action before each evaluation; the impulse it is
/// given is kept for the action, which applies the parts' impulses through the chain's Jacobians. It has no force of
/// its own waiting (the evaluation then starts from the velocity given) and never sleeps (the action skips a sleeping
/// multibody).
class btBuoyancyMultiBodyPart final : public btBuoyancyBody {
public:
    /// @param mass  kg (0: a fixed base); inertia: principal moments, kg m²
    btBuoyancyMultiBodyPart(btScalar mass, const btVector3& inertia) {
        m_invMass = mass != btScalar(0) ? btScalar(1) / mass : btScalar(0);
        setInvInertia(inertia);
    }
    /// The part's state before its evaluation: pose of its centre-of-mass frame, world velocities, the weight per
    /// unit mass.
    void setState(const btTransform& pose, const btVector3& linearVelocity, const btVector3& angularVelocity,
                  const btVector3& gravity) {
        m_pose = pose;
        m_v = linearVelocity;
        m_w = angularVelocity;
        m_gravity = gravity;
        updateWorldInertia();
    }

    const btTransform& getWorldTransform() const override { return m_pose; }
    const btVector3& getLinearVelocity() const override { return m_v; }
    const btVector3& getAngularVelocity() const override { return m_w; }
    btScalar getInvMass() const override { return m_invMass; }
    const btVector3& getInvInertiaDiagLocal() const override { return m_invInertia; }
    const btMatrix3x3& getInvInertiaTensorWorld() const override { return m_invInertiaWorld; }
    const btVector3& getGravity() const override { return m_gravity; }
    const btVector3& getLinearFactor() const override { return m_one; }
    const btVector3& getAngularFactor() const override { return m_one; }
    const btVector3& getTotalForce() const override { return m_zero; }
    const btVector3& getTotalTorque() const override { return m_zero; }
    bool isInWorld() const override { return true; }
    bool isActive() const override { return true; }
    /// Bullet's defaults for a rigid body (0.8 m/s, 1 rad/s).
    btScalar getLinearSleepingThreshold() const override { return m_linearSleep; }
    btScalar getAngularSleepingThreshold() const override { return m_angularSleep; }
    /// Kept for the action (the multibody's velocities change only through its generalized impulse).
    void applyCentralImpulses(const btVector3&, const btVector3&) override {}
    void activate(bool) override {}
    void setSleepingThresholds(btScalar linear, btScalar angular) override {
        m_linearSleep = linear;
        m_angularSleep = angular;
    }
    void setMassProps(btScalar mass, const btVector3& inertia) override {
        m_invMass = mass != btScalar(0) ? btScalar(1) / mass : btScalar(0);
        setInvInertia(inertia);
        updateWorldInertia();
    }

private:
    void setInvInertia(const btVector3& inertia) {
        m_invInertia = btVector3(inertia.x() != btScalar(0) ? btScalar(1) / inertia.x() : btScalar(0),
                                 inertia.y() != btScalar(0) ? btScalar(1) / inertia.y() : btScalar(0),
                                 inertia.z() != btScalar(0) ? btScalar(1) / inertia.z() : btScalar(0));
    }
    void updateWorldInertia() {
        // R diag(I⁻¹) Rᵀ, as btRigidBody::updateInertiaTensor.
        m_invInertiaWorld = m_pose.getBasis().scaled(m_invInertia) * m_pose.getBasis().transpose();
    }
    btTransform m_pose = btTransform::getIdentity();
    btVector3 m_v{0, 0, 0}, m_w{0, 0, 0}, m_gravity{0, 0, 0};
    btScalar m_invMass = 0;
    btVector3 m_invInertia{0, 0, 0};
    btMatrix3x3 m_invInertiaWorld = btMatrix3x3::getIdentity();
    btScalar m_linearSleep = btScalar(0.8), m_angularSleep = btScalar(1.0);
    const btVector3 m_one{1, 1, 1}, m_zero{0, 0, 0};
};

}  // namespace

/// One floating part: its collider, the part as a btBuoyancyBody and its evaluation's state.
struct btBuoyancyMultiBodyAction::Part {
    Part(btScalar mass, const btVector3& inertia) : body(mass, inertia) {}
    int link = -1;  ///< −1: the base
    btMultiBodyLinkCollider* collider = nullptr;
    btBuoyancyMultiBodyPart body;
    std::unique_ptr<btBuoyancyImmediate> buoyancy;
};

btBuoyancyMultiBodyAction::btBuoyancyMultiBodyAction(btMultiBody* multiBody, btBuoyancyWorld* world,
                                                     const btBuoyancySettings& settings)
    : m_multiBody(multiBody), m_world(world) {
    if (!multiBody) throw std::invalid_argument("btBuoyancyMultiBodyAction: multiBody is null");
    if (!world) throw std::invalid_argument("btBuoyancyMultiBodyAction: world is null");
    btBuoyancySettings partSettings = settings;
    partSettings.addedMass = false;
    partSettings.validate();
    for (int link = -1; link < multiBody->getNumLinks(); ++link) {
        btMultiBodyLinkCollider* collider = link < 0 ? multiBody->getBaseCollider() : multiBody->getLinkCollider(link);
        if (!collider || !collider->getCollisionShape()) continue;
        const std::string name = link < 0 ? std::string("base") : "link " + std::to_string(link);
        const double mass = double(link < 0 ? multiBody->getBaseMass() : multiBody->getLinkMass(link));
        const btVector3 inertia = link < 0 ? multiBody->getBaseInertia() : multiBody->getLinkInertia(link);
        const bool fixedPart = link < 0 && multiBody->hasFixedBase();
        if (!fixedPart && !(mass > 0))
            throw std::invalid_argument("btBuoyancyMultiBodyAction: " + name + " has mass " + std::to_string(mass) +
                                        " kg: a floating part needs a positive mass");
        auto part = std::make_unique<Part>(btScalar(fixedPart ? 0.0 : mass), fixedPart ? btVector3(0, 0, 0) : inertia);
        part->link = link;
        part->collider = collider;
        try {
            part->buoyancy = std::make_unique<btBuoyancyImmediate>(
                part->body, btBuoyancyShape::fromCollisionShape(*collider->getCollisionShape(), partSettings),
                partSettings);
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("btBuoyancyMultiBodyAction: " + name + ": " + e.what());
        }
        m_parts.push_back(std::move(part));
    }
    if (m_parts.empty())
        throw std::invalid_argument("btBuoyancyMultiBodyAction: the multibody has no collider on its base or links "
                                    "(each floating part floats with its collider's shape)");
}

btBuoyancyMultiBodyAction::~btBuoyancyMultiBodyAction() = default;

const btBuoyancyResult* btBuoyancyMultiBodyAction::getPartResult(int link) const {
    for (const auto& p : m_parts)
        if (p->link == link) return &p->buoyancy->getAction().getLastResult();
    return nullptr;
}

double btBuoyancyMultiBodyAction::getSubmergedVolume() const {
    double v = 0;
    for (const auto& p : m_parts) v += p->buoyancy->getAction().getLastResult().submergedVolume;
    return v;
}

void btBuoyancyMultiBodyAction::updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) {
    const double dt = double(deltaTimeStep);
    if (!(dt > 0) || !std::isfinite(dt)) return;
    // The world's clock and gravity advance once per substep, whoever calls first.
    m_world->beginSubstepIfNew(m_lastSubstep, dt, collisionWorld);
    const btWaterSurface* water = m_world->getWater();
    btMultiBody& mb = *m_multiBody;
    if (!water || !mb.isAwake()) return;
    const Eigen::Vector3d& gv = m_world->getGravityVector();
    const btVector3 gravity(btScalar(gv.x()), btScalar(gv.y()), btScalar(gv.z()));
    const double time = m_world->getTime(), rho = m_world->getFluidDensity();

    // Every part's velocity at its centre of mass (the link frame's origin), from the joint velocities.
    const int links = mb.getNumLinks();
    m_omega.resize(links + 1);
    m_velocity.resize(links + 1);
    mb.compTreeLinkVelocities(&m_omega[0], &m_velocity[0]);
    const int dofs = 6 + mb.getNumDofs();
    m_force.resize(dofs);
    for (int i = 0; i < dofs; ++i) m_force[i] = 0;
    m_jacobian.resize(dofs);
    bool any = false;
    for (const auto& part : m_parts) {
        const btTransform& pose = part->collider->getWorldTransform();
        part->body.setState(pose, pose.getBasis() * m_velocity[part->link + 1], pose.getBasis() * m_omega[part->link + 1],
                            gravity);
        if (part->link < 0 && mb.hasFixedBase()) continue;  // a fixed base takes what it is given
        if (!part->buoyancy->getContext().isWaterFrameFixed() && m_world->isWaterFrameFixed())
            part->buoyancy->getContext().setWaterFrame(m_world->getWaterFrame());
        const btBuoyancyResult& r = part->buoyancy->applyBuoyancyImpulse(*water, gravity, rho, time, dt);
        if (!r.applied) continue;
        // The generalized impulse of the spatial impulse (angular L, linear J at the centre of mass): the Jacobian of
        // the direction (L, J) is linear in it and its product with the joint velocities is the power, so Jᵀ·1.
        mb.fillConstraintJacobianMultiDof(part->link, pose.getOrigin(), r.angularImpulse, r.linearImpulse, &m_jacobian[0],
                                         m_scratchR, m_scratchV, m_scratchM);
        for (int i = 0; i < dofs; ++i) m_force[i] += m_jacobian[i];
        any = true;
    }
    if (!any) return;
    m_deltaV.resize(dofs);
    mb.calcAccelerationDeltasMultiDof(&m_force[0], &m_deltaV[0], m_scratchR, m_scratchV);
    mb.applyDeltaVeeMultiDof(&m_deltaV[0], 1);
}

std::vector<unsigned char> btBuoyancyMultiBodyAction::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::MultiBodyAction);
    out.u64(m_lastSubstep);
    out.u64(m_parts.size());
    for (const auto& part : m_parts) {
        out.i32(part->link);
        out.blob(part->buoyancy->saveState());
    }
    return out.bytes();
}

void btBuoyancyMultiBodyAction::restoreState(const unsigned char* data, std::size_t size) {
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::MultiBodyAction, "btBuoyancyMultiBodyAction::restoreState");
    const std::uint64_t lastSubstep = in.u64("last substep");
    in.expectCount(in.u64("part count"), m_parts.size(), "part count");
    std::vector<std::vector<unsigned char>> parts;
    for (const auto& part : m_parts) {
        const std::int32_t link = in.i32("part link");
        if (link != part->link)
            in.fail("a part is link " + std::to_string(link) + " in the blob, link " + std::to_string(part->link) +
                    " here (a state of another multibody)");
        parts.push_back(in.blob("part state"));
    }
    in.finish();
    // Each part checks itself; if one refuses, the parts restored before it are put back as they were.
    std::vector<std::vector<unsigned char>> before;
    for (const auto& part : m_parts) before.push_back(part->buoyancy->saveState());
    std::size_t done = 0;
    try {
        for (; done < m_parts.size(); ++done) m_parts[done]->buoyancy->restoreState(parts[done], m_world->getWater());
    } catch (...) {
        for (std::size_t i = 0; i < done; ++i) m_parts[i]->buoyancy->restoreState(before[i]);
        throw;
    }
    m_lastSubstep = lastSubstep;
}
