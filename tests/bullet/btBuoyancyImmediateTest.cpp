// Immediate mode (btBuoyancyImmediate) against the action it shares its evaluation with (the same body in waves,
// stepped by Bullet with an action and with one call per substep from Bullet's tick callback), and a user's own loop
// against Archimedes (a sphere's cap at its density ratio, Y-up and Z-up).
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyImmediate.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

namespace {

constexpr double kPi = 3.14159265358979323846;

struct TickContext {
    btBuoyancyImmediate* buoyancy = nullptr;
    const btWaterSurface* water = nullptr;
    double time = 0;
};

void afterSubstep(btDynamicsWorld* world, btScalar dt) {
    auto* c = static_cast<TickContext*>(world->getWorldUserInfo());
    c->time += double(dt);
    c->buoyancy->applyBuoyancyImpulse(*c->water, world->getGravity(), 1000.0, c->time, double(dt));
}

struct World {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btBoxShape box{btVector3(0.5f, 0.2f, 0.4f)};
    std::unique_ptr<btRigidBody> body;
    World() {
        world.setGravity(btVector3(0, btScalar(-9.81), 0));
        const btScalar mass = btScalar(0.4 * 1000 * 0.32);
        btVector3 inertia;
        box.calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &box, inertia);
        info.m_startWorldTransform.setOrigin(btVector3(0.2f, 0.4f, -0.1f));
        info.m_startWorldTransform.setRotation(btQuaternion(btVector3(0.3f, 0.2f, 1).normalized(), btScalar(0.4)));
        body = std::make_unique<btRigidBody>(info);
        body->setActivationState(DISABLE_DEACTIVATION);
        world.addRigidBody(body.get());
    }
    ~World() { world.removeRigidBody(body.get()); }
};

}  // namespace

TEST_CASE("immediate mode: one call per substep moves a body in waves as the action does", "[bullet][immediate]") {
    btGerstnerWave wave;
    wave.amplitude = 0.2;
    wave.wavelength = 8.0;
    wave.directionX = 0.6;
    wave.directionZ = 0.8;
    wave.steepness = 0.5;
    const btGerstnerWaterSurface water({wave}, 0.0, 9.81);
    World withAction, immediate;
    btBuoyancyWorld buoyancyWorld(&withAction.world, &water, 1000.0);
    btBuoyancyAction action(withAction.body.get(), &buoyancyWorld);
    withAction.world.addAction(&action);
    btBuoyancyImmediate buoyancy(immediate.body.get());
    TickContext tick{&buoyancy, &water, 0.0};
    immediate.world.setInternalTickCallback(afterSubstep, &tick);
    double worst = 0, worstAngle = 0;
    for (int frame = 0; frame < 60 * 3; ++frame) {
        withAction.world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        immediate.world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        worst = std::max(worst, double((withAction.body->getCenterOfMassPosition() -
                                        immediate.body->getCenterOfMassPosition()).length()));
        worstAngle = std::max(worstAngle, double(withAction.body->getOrientation().angleShortestPath(
                                              immediate.body->getOrientation())));
    }
    const btBuoyancyResult& a = action.getLastResult();
    const btBuoyancyResult& b = buoyancy.getAction().getLastResult();
    INFO("largest difference " << worst << " m, " << worstAngle << " rad; submerged " << a.submergedVolume << " and "
                               << b.submergedVolume << " m3");
    // The same evaluation at the same poses and water times (the clocks add the same substeps): rounding apart only.
    CHECK(worst < 1e-5);
    CHECK(worstAngle < 1e-5);
    CHECK(b.applied);
    CHECK(b.submergedVolume > 0.05);
    CHECK(b.time == Approx(a.time).epsilon(1e-12));
    // The impulses returned are the ones applied: for this substep, J = F_total dt scaled by the added mass.
    CHECK(b.linearImpulse.length() > 0);
    withAction.world.removeAction(&action);
}

TEST_CASE("immediate mode: your own loop floats a sphere at its Archimedes draft in a Y-up and a Z-up world",
          "[bullet][immediate]") {
    const bool zUp = GENERATE(false, true);
    const btVector3 gravity = zUp ? btVector3(0, 0, btScalar(-9.81)) : btVector3(0, btScalar(-9.81), 0);
    const btVector3 up = -gravity.normalized();
    const double R = 0.5, s = 0.3, V = 4.0 / 3.0 * kPi * R * R * R;
    // The cap height h with π h² (3R − h) / 3 = s V, by bisection.
    double lo = 0, hi = 2 * R;
    for (int i = 0; i < 200; ++i) {
        const double h = 0.5 * (lo + hi);
        (kPi * h * h * (3 * R - h) / 3 < s * V ? lo : hi) = h;
    }
    const double h = 0.5 * (lo + hi);
    btSphereShape sphere{btScalar(R)};
    const btScalar mass = btScalar(1000 * s * V);
    btVector3 inertia;
    sphere.calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &sphere, inertia);
    info.m_startWorldTransform.setOrigin(up * btScalar(0.6));
    btRigidBody body(info);
    const btFlatWaterSurface water(0.0);
    btBuoyancyImmediate buoyancy(&body);
    const double dt = 1.0 / 240;
    double t = 0;
    for (int step = 0; step < 240 * 30; ++step) {
        // The user's loop: gravity kick, move, then buoyancy at the new pose (Bullet's order).
        body.setLinearVelocity(body.getLinearVelocity() + gravity * btScalar(dt));
        btTransform next;
        body.predictIntegratedTransform(btScalar(dt), next);
        body.proceedToTransform(next);
        t += dt;
        buoyancy.applyBuoyancyImpulse(water, gravity, 1000.0, t, dt);
    }
    const double height = double(body.getCenterOfMassPosition().dot(up));
    INFO((zUp ? "Z-up" : "Y-up") << ": centre " << height << " m above the water, expected " << R - h);
    CHECK(height == Approx(R - h).margin(2e-3));
    // At rest the velocity after the buoyancy impulse is g dt upward: the next gravity kick brings it to 0 (as in
    // Bullet, where the body at rest holds +g dt between substeps).
    CHECK(double((body.getLinearVelocity() + gravity * btScalar(dt)).length()) < 1e-3);
    CHECK(buoyancy.getContext().getWaterFrame().up().isApprox(Eigen::Vector3d(double(up.x()), double(up.y()), double(up.z())), 1e-6));
}

TEST_CASE("immediate mode: zero gravity gives no buoyancy and bad input is refused", "[bullet][immediate]") {
    btBoxShape box(btVector3(0.5f, 0.5f, 0.5f));
    btRigidBody::btRigidBodyConstructionInfo info(100, nullptr, &box, btVector3(10, 10, 10));
    btRigidBody body(info);
    const btFlatWaterSurface water(1.0);  // the box's centre 1 m under
    btBuoyancyImmediate buoyancy(&body);
    const btBuoyancyResult& r = buoyancy.applyBuoyancyImpulse(water, btVector3(0, 0, 0), 1000.0, 0.1, 0.01);
    CHECK(r.status == btBuoyancyStatus::NoGravity);
    CHECK(body.getLinearVelocity().length() == 0);
    CHECK_THROWS_WITH(buoyancy.applyBuoyancyImpulse(water, btVector3(0, -9.81f, 0), -5.0, 0.1, 0.01),
                      Catch::Contains("fluidDensity"));
    CHECK_THROWS_WITH(buoyancy.applyBuoyancyImpulse(water, btVector3(0, btScalar(NAN), 0), 1000.0, 0.1, 0.01),
                      Catch::Contains("gravity"));
    // A whole box under water in Y-up gravity: ρ V g dt upward (its own weight is the loop's to apply).
    const btBuoyancyResult& under = buoyancy.applyBuoyancyImpulse(water, btVector3(0, btScalar(-9.81), 0), 1000.0, 0.2, 0.01);
    CHECK(under.status == btBuoyancyStatus::Ok);
    CHECK(under.submergedVolume == Approx(1.0).epsilon(1e-6));
    CHECK(double(under.buoyancyForce.y()) == Approx(1000 * 9.81).epsilon(1e-5));
}
