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

TEST_CASE("btBuoyancyWorld: a water frame whose up is not antiparallel to gravity is refused with both vectors named",
          "[bullet][gravity]") {
    // A Z-up or oblique world is accepted (the default frame follows its gravity); an explicit frame against it is not.
    for (const btVector3 g : {btVector3(0, 0, -9.81f), btVector3(0, -9.81f, 0.5f)}) {
        UserWorld u(g);
        CHECK_NOTHROW(btBuoyancyWorld(&u.world, &u.water, 1000.0));
        try {
            btBuoyancyWorld context(&u.world, &u.water, btWaterFrame(), 1000.0);  // up +y
            FAIL("accepted gravity (" << g.x() << ", " << g.y() << ", " << g.z() << ") with up +y");
        } catch (const std::invalid_argument& e) {
            const std::string message = e.what();
            CHECK_THAT(message, Contains("water frame's up (0, 1, 0) is not antiparallel to the world's gravity"));
            CHECK_THAT(message, Contains(g.z() < -1 ? "(0, 0, -9.81)" : "(0, -9.81, 0.5)"));
        }
    }
    UserWorld u(btVector3(0, -9.81f, 0));
    CHECK_THROWS_WITH(btBuoyancyWorld(nullptr, &u.water, 1000.0), Contains("world: must not be null"));
}

TEST_CASE("btBuoyancyWorld without its world: a Z-up world takes its frame from the first gravity read, and floats",
          "[bullet][gravity]") {
    // The constructor without a world cannot check; the first substep reads the gravity of the world stepping it and
    // derives the default frame from it (up +z). Before the frame existed, the box was pushed 16 m along +y.
    UserWorld u(btVector3(0, 0, -9.81f));
    u.buoyancy = std::make_unique<btBuoyancyWorld>(&u.water, 1000.0, 9.81);
    CHECK_FALSE(u.buoyancy->isWaterFrameFixed());
    const auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.8, 0.4));  // 0.4 m tall along z
    btBuoyantBodySettings settings;
    settings.density = 400;
    u.body = std::make_unique<btBuoyantBody>(shape, settings,
                                             btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 0.1f)));
    u.world.addRigidBody(u.body->getRigidBody());
    u.action = std::make_unique<btBuoyancyAction>(*u.body, u.buoyancy.get());
    u.world.addAction(u.action.get());
    u.run(30.0);
    CHECK(u.buoyancy->isWaterFrameFixed());
    CHECK(u.buoyancy->getWaterFrame().up().isApprox(Eigen::Vector3d::UnitZ()));
    const btBuoyancyResult& r = u.action->getLastResult();
    CHECK(r.status == btBuoyancyStatus::Ok);
    CHECK(u.submergedFraction() == Approx(0.4).margin(0.004));  // Archimedes: s = 0.4
    const btVector3 p = u.body->getRigidBody()->getCenterOfMassPosition();
    CHECK(std::fabs(double(p.y())) < 1e-3);          // nothing along y
    CHECK(double(p.z()) == Approx(0.2 - 0.16).margin(2e-3));  // draft 0.16 of 0.4 m: centre 0.04 above the water
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
        CHECK_THAT(u.buoyancy->getGravityStatusMessage(),
                   Contains("gravity (0, 0, -9.81) m/s^2 does not point down the water frame's up axis (0, 1, 0)"));
        u.world.setGravity(btVector3(0, -9.81f, 0));
        u.run(1.0);
        CHECK(u.action->getLastResult().applied);
        CHECK(u.action->getLastResult().status == btBuoyancyStatus::Ok);
    }
}
