// The body interface (btBuoyancyBody.h): a body of the user's own integrator floats through btBuoyancyAction at
// Archimedes' draft (Y-up and Z-up), and a body implemented by forwarding to a btRigidBody moves bit for bit as the
// action's btRigidBody constructor moves it (so every read and write of the action goes through the interface).
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyBody.h>
#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btWaterFrame.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

namespace {

/// A rigid body stepped by the test's own semi-implicit Euler integrator (not a Bullet body): what a user with another
/// engine's bodies writes.
class OwnBody final : public btBuoyancyBody {
public:
    OwnBody(double mass, const btVector3& inertia, const btTransform& pose) : m_pose(pose) {
        m_invMass = btScalar(1.0 / mass);
        m_invInertia = btVector3(btScalar(1) / inertia.x(), btScalar(1) / inertia.y(), btScalar(1) / inertia.z());
        updateWorldInertia();
    }
    /// Before the action's turn in a substep: v += g dt, then the pose moves by the velocities.
    void integrate(const btVector3& gravity, btScalar dt) {
        m_gravity = gravity;
        m_v += gravity * dt;
        m_pose.getOrigin() += m_v * dt;
        const btScalar angle = m_w.length() * dt;
        if (angle > btScalar(0)) {
            btQuaternion q = btQuaternion(m_w / m_w.length(), angle) * m_pose.getRotation();
            q.normalize();
            m_pose.setRotation(q);
        }
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
    btScalar getLinearSleepingThreshold() const override { return btScalar(0.8); }
    btScalar getAngularSleepingThreshold() const override { return btScalar(1.0); }
    void applyCentralImpulses(const btVector3& linearImpulse, const btVector3& angularImpulse) override {
        m_v += linearImpulse * m_invMass;
        m_w += m_invInertiaWorld * angularImpulse;
        ++impulses;
    }
    void activate(bool) override {}
    void setSleepingThresholds(btScalar, btScalar) override {}
    void setMassProps(btScalar mass, const btVector3& inertia) override {
        m_invMass = btScalar(1) / mass;
        m_invInertia = btVector3(btScalar(1) / inertia.x(), btScalar(1) / inertia.y(), btScalar(1) / inertia.z());
        updateWorldInertia();
    }

    int impulses = 0;

private:
    void updateWorldInertia() {
        const btMatrix3x3& R = m_pose.getBasis();
        m_invInertiaWorld = R.scaled(m_invInertia) * R.transpose();
    }
    btTransform m_pose;
    btVector3 m_v{0, 0, 0}, m_w{0, 0, 0}, m_gravity{0, 0, 0};
    btScalar m_invMass = 0;
    btVector3 m_invInertia{0, 0, 0};
    btMatrix3x3 m_invInertiaWorld;
    const btVector3 m_one{1, 1, 1}, m_zero{0, 0, 0};
};

/// Every call forwarded to a btRigidBody, written here (not btBuoyancyRigidBody).
class ForwardingBody final : public btBuoyancyBody {
public:
    explicit ForwardingBody(btRigidBody* body) : m_body(body) {}
    const btTransform& getWorldTransform() const override { return m_body->getWorldTransform(); }
    const btVector3& getLinearVelocity() const override { return m_body->getLinearVelocity(); }
    const btVector3& getAngularVelocity() const override { return m_body->getAngularVelocity(); }
    btScalar getInvMass() const override { return m_body->getInvMass(); }
    const btVector3& getInvInertiaDiagLocal() const override { return m_body->getInvInertiaDiagLocal(); }
    const btMatrix3x3& getInvInertiaTensorWorld() const override { return m_body->getInvInertiaTensorWorld(); }
    const btVector3& getGravity() const override { return m_body->getGravity(); }
    const btVector3& getLinearFactor() const override { return m_body->getLinearFactor(); }
    const btVector3& getAngularFactor() const override { return m_body->getAngularFactor(); }
    const btVector3& getTotalForce() const override { return m_body->getTotalForce(); }
    const btVector3& getTotalTorque() const override { return m_body->getTotalTorque(); }
    bool isInWorld() const override { return m_body->getBroadphaseHandle() != nullptr; }
    bool isActive() const override { return m_body->isActive(); }
    btScalar getLinearSleepingThreshold() const override { return m_body->getLinearSleepingThreshold(); }
    btScalar getAngularSleepingThreshold() const override { return m_body->getAngularSleepingThreshold(); }
    void applyCentralImpulses(const btVector3& linearImpulse, const btVector3& angularImpulse) override {
        m_body->applyCentralImpulse(linearImpulse);
        m_body->applyTorqueImpulse(angularImpulse);
    }
    void activate(bool force) override { m_body->activate(force); }
    void setSleepingThresholds(btScalar linear, btScalar angular) override {
        m_body->setSleepingThresholds(linear, angular);
    }
    void setMassProps(btScalar mass, const btVector3& inertia) override {
        m_body->setMassProps(mass, inertia);
        m_body->updateInertiaTensor();
    }

private:
    btRigidBody* m_body;
};

struct BulletWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
};

struct EnterCounter : btBuoyancyEventListener {
    int enters = 0;
    const btBuoyancyAction* action = nullptr;
    const btRigidBody* body = reinterpret_cast<const btRigidBody*>(1);
    void onEnterWater(const btBuoyancyEvent& e) override {
        ++enters;
        action = e.action;
        body = e.body;
    }
};

struct OwnLoop {
    OwnBody* body = nullptr;
};

void beforeSubstep(btDynamicsWorld* world, btScalar dt) {
    // Bullet's pre-tick callback: the user's integrator moves its body where Bullet would integrate its own.
    static_cast<OwnLoop*>(world->getWorldUserInfo())->body->integrate(world->getGravity(), dt);
}

}  // namespace

TEST_CASE("body interface: a body of the user's own integrator floats at Archimedes' draft, Y-up and Z-up",
          "[bullet][body]") {
    // A plank 1 m × 1 m × 0.2 m of 600 kg/m³ in water of 1000 kg/m³ floats flat, 0.12 m deep: its centre of mass
    // 0.02 m below the water. At rest its stored velocity is the next gravity kick's opposite, g dt up (Bullet's order:
    // the integrator adds −g dt before it moves the body).
    const double rho = 1000.0, density = 600.0, g = 9.81, dt = 1.0 / 240.0;
    for (const bool zUp : {false, true}) {
        INFO((zUp ? "Z-up" : "Y-up"));
        BulletWorld w;
        const btVector3 up = zUp ? btVector3(0, 0, 1) : btVector3(0, 1, 0);
        w.world.setGravity(-btScalar(g) * up);
        btFlatWaterSurface water(0.0);
        btBuoyancyWorld buoyancy(&w.world, &water, rho);
        const btVector3 half = zUp ? btVector3(0.5f, 0.5f, 0.1f) : btVector3(0.5f, 0.1f, 0.5f);
        btBoxShape box(half);
        const double mass = density * 8.0 * double(half.x() * half.y() * half.z());
        const btVector3 size = 2 * half;
        const btVector3 inertia = btScalar(mass / 12.0) * btVector3(size.y() * size.y() + size.z() * size.z(),
                                                                     size.x() * size.x() + size.z() * size.z(),
                                                                     size.x() * size.x() + size.y() * size.y());
        btTransform start;
        start.setIdentity();
        start.setOrigin(up * btScalar(0.5));  // above the water: it falls in (one EnterWater event)
        start.setRotation(btQuaternion(btVector3(1, 0.4f, 0.2f).normalized(), btScalar(0.15)));
        OwnBody body(mass, inertia, start);
        OwnLoop loop{&body};
        w.world.setInternalTickCallback(beforeSubstep, &loop, true);
        btBuoyancyAction action(body, btBuoyancyShape::fromCollisionShape(box), &buoyancy);
        CHECK(action.getRigidBody() == nullptr);
        CHECK(&action.getBody() == &body);
        EnterCounter events;
        buoyancy.addEventListener(&events);
        w.world.addAction(&action);
        for (int i = 0; i < 60 * 30; ++i) w.world.stepSimulation(btScalar(1.0 / 60.0), 4, btScalar(dt));
        w.world.removeAction(&action);
        CHECK(body.impulses > 0);
        CHECK(events.enters == 1);
        CHECK(events.action == &action);
        CHECK(events.body == nullptr);  // not a btRigidBody: the event names the action (getBody)
        const double height = double(body.getCenterOfMassPosition().dot(up));
        CHECK(std::abs(height - (-0.02)) < 1e-3);
        CHECK(action.getLastResult().submergedVolume == Approx(mass / rho).epsilon(2e-3));
        CHECK(double((body.getLinearVelocity() - btScalar(g * dt) * up).length()) < 1e-3);
        CHECK(double(body.getAngularVelocity().length()) < 1e-3);
    }
}

TEST_CASE("body interface: a body forwarding to a btRigidBody moves bit for bit as the btRigidBody constructor's",
          "[bullet][body]") {
    btGerstnerWave wave;
    wave.amplitude = 0.25;
    wave.wavelength = 9.0;
    const btGerstnerWaterSurface waves({wave}, 0.0, 9.81);
    std::vector<btVector3> track[2];
    for (int run = 0; run < 2; ++run) {
        BulletWorld w;
        w.world.setGravity(btVector3(0, btScalar(-9.81), 0));
        btBuoyancyWorld buoyancy(&w.world, &waves, 1000.0);
        btBoxShape box(btVector3(0.6f, 0.25f, 0.4f));
        const btScalar mass = btScalar(0.5 * 1000 * 1.2 * 0.5 * 0.8);
        btVector3 inertia;
        box.calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &box, inertia);
        info.m_startWorldTransform.setOrigin(btVector3(0.3f, 0.5f, -0.2f));
        info.m_startWorldTransform.setRotation(btQuaternion(btVector3(0.2f, 1, 0.3f).normalized(), btScalar(0.5)));
        btRigidBody rigid(info);
        w.world.addRigidBody(&rigid);
        ForwardingBody forwarding(&rigid);
        std::unique_ptr<btBuoyancyAction> action =
            run == 0 ? std::make_unique<btBuoyancyAction>(&rigid, &buoyancy)
                     : std::make_unique<btBuoyancyAction>(forwarding, btBuoyancyShape::fromCollisionShape(box), &buoyancy);
        w.world.addAction(action.get());
        for (int i = 0; i < 240; ++i) {
            w.world.stepSimulation(btScalar(1.0 / 60.0), 4, btScalar(1.0 / 240.0));
            track[run].push_back(rigid.getCenterOfMassPosition());
            track[run].push_back(rigid.getAngularVelocity());
        }
        w.world.removeAction(action.get());
        w.world.removeRigidBody(&rigid);
    }
    REQUIRE(track[0].size() == track[1].size());
    bool same = true;
    for (std::size_t i = 0; i < track[0].size(); ++i) same = same && track[0][i] == track[1][i];
    CHECK(same);
    CHECK(track[0].back() != track[0].front());  // it moved
}
