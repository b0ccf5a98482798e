// The buoyancy context takes gravity from the Bullet world it serves: a world whose gravity does not point down the
// water's up axis is refused (constructor) or gets no buoyancy with a status saying why (at run time), never a
// silent wrong answer; Moon or changed gravity is followed; zero gravity gives no buoyancy and no NaN.
// Oracles: Archimedes (the submerged volume of a floating body is its mass / ρ whatever g is), free fall.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <stdexcept>

using Catch::Matchers::Contains;

namespace {

/// A Bullet world as a user makes one, with the given gravity, and a 1 × 0.4 × 0.8 m board of density 400 kg/m³
/// (s = 0.4: stable flat, draft 0.16 m) whose mesh centre starts at `startY`.
struct UserWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btFlatWaterSurface water{0.0};
    std::unique_ptr<btBuoyancyWorld> buoyancy;
    std::unique_ptr<btBuoyantBody> body;
    std::unique_ptr<btBuoyancyAction> action;

    explicit UserWorld(const btVector3& gravity) { world.setGravity(gravity); }

    void addBoard(double startY) {
        auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.8));
        btBuoyantBodySettings settings;
        settings.density = 400;
        body = std::make_unique<btBuoyantBody>(shape, settings,
                                               btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(startY), 0)));
        world.addRigidBody(body->getRigidBody());
        action = std::make_unique<btBuoyancyAction>(*body, buoyancy.get());
        world.addAction(action.get());
    }
    ~UserWorld() {
        if (action) world.removeAction(action.get());
        if (body) world.removeRigidBody(body->getRigidBody());
    }
    void run(double seconds) {
        for (int i = 0; i < int(seconds * 60); ++i) world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
    }
    double submergedFraction() const { return action->getLastResult().submergedVolume / 0.32; }
};

}  // namespace

TEST_CASE("btBuoyancyWorld: a Z-up or oblique world is refused with both vectors named", "[bullet][gravity]") {
    for (const btVector3 g : {btVector3(0, 0, -9.81f), btVector3(0, -9.81f, 0.5f)}) {
        UserWorld u(g);
        try {
            btBuoyancyWorld context(&u.world, &u.water, 1000.0);
            FAIL("accepted gravity (" << g.x() << ", " << g.y() << ", " << g.z() << ")");
        } catch (const std::invalid_argument& e) {
            const std::string message = e.what();
            CHECK_THAT(message, Contains("does not point down the water's up axis (0, 1, 0)"));
            CHECK_THAT(message, Contains(g.z() < -1 ? "(0, 0, -9.81)" : "(0, -9.81, 0.5)"));
        }
    }
    UserWorld u(btVector3(0, -9.81f, 0));
    CHECK_THROWS_WITH(btBuoyancyWorld(nullptr, &u.water, 1000.0), Contains("world: must not be null"));
}

TEST_CASE("btBuoyancyWorld without its world: a Z-up world gets no buoyancy and a status, not a push along y",
          "[bullet][gravity]") {
    // The constructor without a world cannot refuse; the first substep reads the gravity of the world stepping it.
    UserWorld u(btVector3(0, 0, -9.81f));
    u.buoyancy = std::make_unique<btBuoyancyWorld>(&u.water, 1000.0, 9.81);
    u.addBoard(-0.1);  // half in the water as y-up water sees it
    u.run(1.0);
    const btBuoyancyResult& r = u.action->getLastResult();
    CHECK(r.status == btBuoyancyStatus::GravityNotAlongWaterUp);
    CHECK_FALSE(r.applied);
    CHECK(u.buoyancy->getGravityStatus() == btBuoyancyStatus::GravityNotAlongWaterUp);
    CHECK_THAT(std::string(btBuoyancyStatusMessage(r.status)), Contains("does not point down"));
    // Free fall along −z, nothing along y (before: pushed up 16 m along +y).
    const btVector3 v = u.body->getRigidBody()->getLinearVelocity();
    CHECK(double(v.z()) == Approx(-9.81).epsilon(0.01));
    CHECK(std::fabs(double(v.y())) < 1e-6);
}

TEST_CASE("btBuoyancyWorld follows the world's gravity: Moon, a change at run time, zero", "[bullet][gravity]") {
    SECTION("Moon gravity: the board floats at its Archimedes draft (s = 0.4 of its volume under water)") {
        UserWorld u(btVector3(0, -1.62f, 0));
        u.buoyancy = std::make_unique<btBuoyancyWorld>(&u.world, &u.water, 1000.0);
        CHECK(u.buoyancy->getGravity() == Approx(1.62).epsilon(1e-6));
        u.addBoard(0.3);
        u.run(60.0);
        CHECK(u.submergedFraction() == Approx(0.4).margin(0.004));
    }
    SECTION("the constructor without a world, g = 9.81, in a Moon world: the world's gravity is used") {
        UserWorld u(btVector3(0, -1.62f, 0));
        u.buoyancy = std::make_unique<btBuoyancyWorld>(&u.water, 1000.0, 9.81);
        u.addBoard(0.3);
        u.run(60.0);
        CHECK(u.buoyancy->getGravity() == Approx(1.62).epsilon(1e-6));
        CHECK(u.submergedFraction() == Approx(0.4).margin(0.004));  // before: 0.066 (draft 0.081 of 0.5 m in a box)
    }
    SECTION("gravity changed at run time is followed, and the board stays at its draft") {
        UserWorld u(btVector3(0, -9.81f, 0));
        u.buoyancy = std::make_unique<btBuoyancyWorld>(&u.world, &u.water, 1000.0);
        u.addBoard(0.3);
        u.run(20.0);
        CHECK(u.submergedFraction() == Approx(0.4).margin(0.004));
        u.world.setGravity(btVector3(0, -3.71f, 0));  // Mars
        u.run(20.0);
        CHECK(u.buoyancy->getGravity() == Approx(3.71).epsilon(1e-6));
        CHECK(u.submergedFraction() == Approx(0.4).margin(0.004));
        CHECK(u.action->getLastResult().status == btBuoyancyStatus::Ok);
    }
    SECTION("zero gravity: no buoyancy, no NaN; the board keeps its velocity") {
        UserWorld u(btVector3(0, 0, 0));
        u.buoyancy = std::make_unique<btBuoyancyWorld>(&u.world, &u.water, 1000.0);
        u.addBoard(-0.1);
        u.body->getRigidBody()->setLinearVelocity(btVector3(0.5f, 0, 0));
        u.run(2.0);
        const btBuoyancyResult& r = u.action->getLastResult();
        CHECK(r.status == btBuoyancyStatus::NoGravity);
        CHECK_FALSE(r.applied);
        const btVector3 v = u.body->getRigidBody()->getLinearVelocity();
        const btVector3 p = u.body->getRigidBody()->getCenterOfMassPosition();
        CHECK(std::isfinite(double(p.x())));
        CHECK(double(v.x()) == Approx(0.5).epsilon(1e-4));
        CHECK(std::fabs(double(v.y())) < 1e-6);
    }
    SECTION("gravity turned to z at run time: the status says why, no exception through stepSimulation") {
        UserWorld u(btVector3(0, -9.81f, 0));
        u.buoyancy = std::make_unique<btBuoyancyWorld>(&u.world, &u.water, 1000.0);
        u.addBoard(0.3);
        u.run(2.0);
        CHECK(u.action->getLastResult().status == btBuoyancyStatus::Ok);
        u.world.setGravity(btVector3(0, 0, -9.81f));
        CHECK_NOTHROW(u.run(1.0));
        CHECK(u.action->getLastResult().status == btBuoyancyStatus::GravityNotAlongWaterUp);
        u.world.setGravity(btVector3(0, -9.81f, 0));
        u.run(1.0);
        CHECK(u.action->getLastResult().applied);
        CHECK(u.action->getLastResult().status == btBuoyancyStatus::Ok);
    }
}
