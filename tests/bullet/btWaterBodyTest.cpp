// Several bounded water bodies in one world (btBuoyancyWorld::addWaterBody): each body floats in the water of the
// region it is in, at that water's level and density; a body outside every region gets no buoyancy and falls;
// overlapping or malformed regions are refused with a message naming them.
// Oracles: Archimedes (a box of density ρ_b and height H floats with draft ρ_b / ρ_w · H), free fall.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <memory>
#include <stdexcept>
#include <vector>

using Catch::Matchers::Contains;

namespace {

constexpr double kGravity = 9.81;  ///< m/s²

/// `world` with its gravity set to `gravity` (so the buoyancy context's water frame follows it).
btDynamicsWorld* withGravity(btDynamicsWorld* world, const btVector3& gravity) {
    world->setGravity(gravity);
    return world;
}

/// A Bullet world (y-up unless another gravity is given) without an unbounded water, and bodies with their actions.
struct WaterBodiesWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btBuoyancyWorld buoyancy;
    std::vector<std::unique_ptr<btBuoyantBody>> bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> actions;

    explicit WaterBodiesWorld(const btVector3& gravity = btVector3(0, btScalar(-kGravity), 0))
        : buoyancy(withGravity(&world, gravity), nullptr) {}
    ~WaterBodiesWorld() {
        for (auto& a : actions) world.removeAction(a.get());
        for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
    }
    /// A box of `size` (default a 1 × 0.5 × 1 m crate) and density `density`, kg/m³, centred at (x, y, z), m;
    /// returns its index.
    std::size_t addCrate(double density, double x, double y, double z,
                         const Eigen::Vector3d& size = Eigen::Vector3d(1.0, 0.5, 1.0)) {
        auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(size.x(), size.y(), size.z()));
        btBuoyantBodySettings settings;
        settings.density = density;
        const btTransform pose(btQuaternion::getIdentity(), btVector3(btScalar(x), btScalar(y), btScalar(z)));
        bodies.push_back(std::make_unique<btBuoyantBody>(shape, settings, pose));
        world.addRigidBody(bodies.back()->getRigidBody());
        actions.push_back(std::make_unique<btBuoyancyAction>(*bodies.back(), &buoyancy));
        world.addAction(actions.back().get());
        return bodies.size() - 1;
    }
    void run(double seconds) {
        for (int i = 0; i < int(seconds * 60 + 0.5); ++i) world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
    }
    double centreY(std::size_t i) const { return double(bodies[i]->getRigidBody()->getCenterOfMassPosition().y()); }
    double centreZ(std::size_t i) const { return double(bodies[i]->getRigidBody()->getCenterOfMassPosition().z()); }
};

btWaterBodyInfo boxWater(const char* name, const btWaterSurface* surface, double density, const btVector3& min,
                         const btVector3& max) {
    return btWaterBodyInfo{name, surface, density, min, max};  // the aggregate form docs/integration.md shows
}

}  // namespace

TEST_CASE("water bodies: a crate in each of two waters floats at its own water's level and density", "[bullet][waters]") {
    // A pool at y = 0 (fresh water) and a lake at y = 1 (denser water) side by side; a crate of density 500 kg/m³ in
    // each. Archimedes: draft d = ρ_b / ρ_w · H, so the crate's centre rests at level − d + H/2.
    WaterBodiesWorld w;
    const btFlatWaterSurface pool(0.0), lake(1.0);
    const double poolDensity = 1000.0, lakeDensity = 1250.0, crateDensity = 500.0, height = 0.5;
    w.buoyancy.addWaterBody(boxWater("pool", &pool, poolDensity, btVector3(-5, -3, -2), btVector3(-1, 0.5, 2)));
    w.buoyancy.addWaterBody(boxWater("lake", &lake, lakeDensity, btVector3(1, -2, -2), btVector3(5, 1.5, 2)));
    const std::size_t inPool = w.addCrate(crateDensity, -3, 0.5, 0);
    const std::size_t inLake = w.addCrate(crateDensity, 3, 1.5, 0);
    w.run(8.0);
    const double poolCentre = 0.0 - crateDensity / poolDensity * height + height / 2;  // 0
    const double lakeCentre = 1.0 - crateDensity / lakeDensity * height + height / 2;  // 1.05
    CHECK(w.centreY(inPool) == Approx(poolCentre).margin(0.01));
    CHECK(w.centreY(inLake) == Approx(lakeCentre).margin(0.01));
    // The submerged volume is the crate's mass over its own water's density (within the volume of a 1 cm draft
    // change, the waterplane being 1 m²: the position's tolerance).
    const double mass = crateDensity * 0.5;
    CHECK(w.actions[inPool]->getLastResult().submergedVolume == Approx(mass / poolDensity).margin(0.01));
    CHECK(w.actions[inLake]->getLastResult().submergedVolume == Approx(mass / lakeDensity).margin(0.01));
}

TEST_CASE("water bodies: a body outside every region gets no buoyancy and no drag, and falls", "[bullet][waters]") {
    WaterBodiesWorld w;
    const btFlatWaterSurface pool(0.0);
    w.buoyancy.addWaterBody(boxWater("pool", &pool, 1000.0, btVector3(-5, -3, -2), btVector3(-1, 0.5, 2)));
    // Beside the pool, below its level: in unbounded water it would float up; here there is no water.
    const double startY = -1.0;
    const std::size_t crate = w.addCrate(500.0, 3, startY, 0);
    const double seconds = 0.5;
    w.run(seconds);
    const btBuoyancyResult& r = w.actions[crate]->getLastResult();
    CHECK(r.submergedVolume == 0.0);
    CHECK(r.buoyancyForce.length() == 0);
    CHECK(r.dragForce.length() == 0);
    // Free fall y = y0 − ½ g t² (semi-implicit Euler at 240 Hz is off by ½ g t dt ≈ 1 cm).
    CHECK(w.centreY(crate) == Approx(startY - 0.5 * kGravity * seconds * seconds).margin(0.02));
}

TEST_CASE("water bodies: overlapping or malformed regions are refused with a message naming them", "[bullet][waters]") {
    WaterBodiesWorld w;
    const btFlatWaterSurface pool(0.0), lake(1.0);
    REQUIRE(w.buoyancy.addWaterBody(boxWater("pool", &pool, 1000.0, btVector3(-5, -3, -2), btVector3(-1, 0, 2))) == 0);
    try {
        w.buoyancy.addWaterBody(boxWater("lake", &lake, 1000.0, btVector3(-2, -2, -2), btVector3(5, 1, 2)));
        FAIL("overlapping regions accepted");
    } catch (const std::invalid_argument& e) {
        CHECK_THAT(e.what(), Contains("\"lake\"") && Contains("\"pool\"") && Contains("overlap"));
    }
    CHECK(w.buoyancy.getWaterBodies().size() == 1);
    // Regions that only touch (a shared face at x = -1) are accepted.
    CHECK(w.buoyancy.addWaterBody(boxWater("lake", &lake, 1000.0, btVector3(-1, -2, -2), btVector3(5, 1, 2))) == 1);
    // min not below max, non-finite corners, bad density, null surface.
    CHECK_THROWS_WITH(w.buoyancy.addWaterBody(boxWater("flat", &lake, 1000.0, btVector3(10, 0, 0), btVector3(12, 0, 1))),
                      Contains("\"flat\"") && Contains("regionMax.y"));
    const btScalar inf = std::numeric_limits<btScalar>::infinity();
    CHECK_THROWS_WITH(w.buoyancy.addWaterBody(boxWater("far", &lake, 1000.0, btVector3(10, 0, 0), btVector3(inf, 1, 1))),
                      Contains("regionMax.x") && Contains("finite"));
    CHECK_THROWS_WITH(w.buoyancy.addWaterBody(boxWater("light", &lake, 0.0, btVector3(10, 0, 0), btVector3(11, 1, 1))),
                      Contains("fluidDensity"));
    CHECK_THROWS_WITH(w.buoyancy.addWaterBody(boxWater("none", nullptr, 1000.0, btVector3(10, 0, 0), btVector3(11, 1, 1))),
                      Contains("surface"));
    // An unbounded water and water bodies are one or the other.
    CHECK_THROWS_WITH(w.buoyancy.setWater(&pool), Contains("water bodies"));
    CHECK(w.buoyancy.getWater() == nullptr);
    w.buoyancy.removeAllWaterBodies();
    w.buoyancy.setWater(&pool);
    CHECK_THROWS_WITH(w.buoyancy.addWaterBody(boxWater("lake", &lake, 1000.0, btVector3(1, -2, -2), btVector3(5, 1, 2))),
                      Contains("unbounded water"));
}

TEST_CASE("water bodies: a body straddling two waters takes each part of its surface from its own water",
          "[bullet][waters]") {
    // A lock: the upper chamber (x < 0) at 0.2 m of fresh water, the lower (x > 0) at −0.1 m of sea water. A 2 × 1 × 1 m
    // box centred on the gate at x = 0. By hand (prisms): the bottom's left half pressed by ρ₁ g D₁, its right half by
    // ρ₂ g D₂ (D the depth of the bottom, y = −0.5, in each water); the ends by ρ g D²/2 per metre of width.
    WaterBodiesWorld w;
    const double h1 = 0.2, rho1 = 1000.0, h2 = -0.1, rho2 = 1025.0;
    const btFlatWaterSurface upper(h1), lower(h2);
    w.buoyancy.addWaterBody(boxWater("upper", &upper, rho1, btVector3(-10, -5, -5), btVector3(0, 1, 5)));
    w.buoyancy.addWaterBody(boxWater("lower", &lower, rho2, btVector3(0, -5, -5), btVector3(10, 1, 5)));
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 1.0, 1.0));
    btBuoyantBodySettings settings;
    settings.density = 500;
    w.bodies.push_back(std::make_unique<btBuoyantBody>(shape, settings, btTransform::getIdentity()));
    w.world.addRigidBody(w.bodies.back()->getRigidBody());
    w.actions.push_back(std::make_unique<btBuoyancyAction>(*w.bodies.back(), &w.buoyancy));
    w.world.addAction(w.actions.back().get());
    CHECK_FALSE(w.buoyancy.getWaterBodies().empty());
    w.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));  // one substep (the box moves g dt² ≈ 0.2 mm)
    const btBuoyancyResult& r = w.actions.back()->getLastResult();
    const double D1 = h1 + 0.5, D2 = h2 + 0.5;
    // Tolerance: the 0.2 mm the box fell in the substep changes the force by ρ g × 2 m² × 0.2 mm ≈ 4 N (4e-4 of it).
    CHECK(double(r.submergedVolume) == Approx(D1 + D2).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.y()) == Approx(kGravity * (rho1 * D1 + rho2 * D2)).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.x()) == Approx(kGravity * (rho1 * D1 * D1 - rho2 * D2 * D2) / 2).margin(5.0));
    CHECK(std::abs(double(r.buoyancyForce.z())) < 1.0);
}

TEST_CASE("water bodies in a Z-up world: heights along +z, regions in world coordinates", "[bullet][waters]") {
    // Gravity −z: the water frame's up is +z and each surface's height is measured along it. The boxes are the world's.
    WaterBodiesWorld w(btVector3(0, 0, btScalar(-kGravity)));
    const btFlatWaterSurface pool(0.0), lake(1.0);
    w.buoyancy.addWaterBody(boxWater("pool", &pool, 1000.0, btVector3(-5, -2, -3), btVector3(-1, 2, 0.5)));
    w.buoyancy.addWaterBody(boxWater("lake", &lake, 1000.0, btVector3(1, -2, -2), btVector3(5, 2, 1.5)));
    const Eigen::Vector3d crate(1.0, 1.0, 0.5);  // 0.5 m tall along z
    const std::size_t inPool = w.addCrate(500.0, -3, 0, 0.5, crate);
    const std::size_t inLake = w.addCrate(500.0, 3, 0, 1.5, crate);
    w.run(8.0);
    // Archimedes along z: draft 500/1000 · 0.5, centre at level − draft + 0.25.
    CHECK(w.centreZ(inPool) == Approx(0.0 - 0.25 + 0.25).margin(0.01));
    CHECK(w.centreZ(inLake) == Approx(1.0 - 0.25 + 0.25).margin(0.01));

    // A 2 × 1 × 1 m box (1 m tall along z) across x = 0 between two more waters, as in the Y-up lock above.
    WaterBodiesWorld lock(btVector3(0, 0, btScalar(-kGravity)));
    const double h1 = 0.2, h2 = -0.1;
    const btFlatWaterSurface upper(h1), lower(h2);
    lock.buoyancy.addWaterBody(boxWater("upper", &upper, 1000.0, btVector3(-10, -5, -5), btVector3(0, 5, 1)));
    lock.buoyancy.addWaterBody(boxWater("lower", &lower, 1000.0, btVector3(0, -5, -5), btVector3(10, 5, 1)));
    const std::size_t box = lock.addCrate(500.0, 0, 0, 0, Eigen::Vector3d(2.0, 1.0, 1.0));
    lock.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    const btBuoyancyResult& r = lock.actions[box]->getLastResult();
    const double D1 = h1 + 0.5, D2 = h2 + 0.5;
    CHECK(double(r.submergedVolume) == Approx(D1 + D2).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.z()) == Approx(kGravity * 1000.0 * (D1 + D2)).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.x()) == Approx(kGravity * 1000.0 * (D1 * D1 - D2 * D2) / 2).margin(5.0));
    CHECK(std::abs(double(r.buoyancyForce.y())) < 1.0);
}

TEST_CASE("water bodies: straddling two equal waters is the one water, and half over the edge is half the buoyancy",
          "[bullet][waters]") {
    // Two regions side by side holding the same water (level 0.2 m, 1000 kg/m³): a body across them must get what one
    // unbounded water gives, pressure and drag (each drag cluster wet in the region its centre is in). And a body half
    // out of its region (over the pool's edge, no water beyond) gets the pressure of its half inside: ρ g × 1 m² × D.
    const double level = 0.2, depth = level + 0.5;
    const btFlatWaterSurface water(level);
    auto boxAcross = [](WaterBodiesWorld& w) {
        const std::size_t i = w.addCrate(500.0, 0, 0, 0, Eigen::Vector3d(2.0, 1.0, 1.0));
        w.bodies[i]->getRigidBody()->setLinearVelocity(btVector3(0.3f, -0.2f, 0.7f));
        w.bodies[i]->getRigidBody()->setAngularVelocity(btVector3(0.1f, 0.4f, -0.2f));
        w.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
        return w.actions[i]->getLastResult();
    };
    WaterBodiesWorld unbounded;
    unbounded.buoyancy.setWater(&water);
    const btBuoyancyResult one = boxAcross(unbounded);
    WaterBodiesWorld split;
    split.buoyancy.addWaterBody(boxWater("left", &water, 1000.0, btVector3(-10, -5, -5), btVector3(0, 1, 5)));
    split.buoyancy.addWaterBody(boxWater("right", &water, 1000.0, btVector3(0, -5, -5), btVector3(10, 1, 5)));
    const btBuoyancyResult two = boxAcross(split);
    REQUIRE(one.dragForce.length() > 1.0);  // the drag is exercised
    CHECK((two.buoyancyForce - one.buoyancyForce).length() <= 1e-5 * one.buoyancyForce.length());
    CHECK((two.buoyancyTorque - one.buoyancyTorque).length() <= 1e-5 * one.buoyancyForce.length());
    CHECK((two.dragForce - one.dragForce).length() <= 1e-5 * one.dragForce.length());
    CHECK((two.dragTorque - one.dragTorque).length() <= 1e-5 * one.dragForce.length());

    WaterBodiesWorld edge;
    edge.buoyancy.addWaterBody(boxWater("pool", &water, 1000.0, btVector3(-10, -5, -5), btVector3(0, 1, 5)));
    const std::size_t i = edge.addCrate(500.0, 0, 0, 0, Eigen::Vector3d(2.0, 1.0, 1.0));
    edge.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    const btBuoyancyResult& half = edge.actions[i]->getLastResult();
    // The 0.2 mm fall of the substep: ρ g × 1 m² × 0.2 mm ≈ 2 N of 6,900 N.
    CHECK(double(half.buoyancyForce.y()) == Approx(1000.0 * kGravity * 1.0 * depth).epsilon(1e-3));
    CHECK(double(half.submergedVolume) == Approx(1.0 * depth).epsilon(1e-3));
}

TEST_CASE("water bodies: a stone resting on a region's bottom keeps its buoyancy", "[bullet][waters]") {
    // The bed is collision geometry at the region's bottom; the stone (2500 kg/m³) sinks onto it and rests there,
    // fully under 2.5 m of water. Archimedes: V_sub = V and an upward pressure force ρ g V, resting or not (with the
    // bottom as a wall for the pressure the stone read V_sub = −0.656 m³ and was pressed down).
    WaterBodiesWorld w;
    const btFlatWaterSurface pool(0.0);
    w.buoyancy.addWaterBody(boxWater("pool", &pool, 1000.0, btVector3(-5, -3, -5), btVector3(5, 0.5, 5)));
    btStaticPlaneShape bedShape(btVector3(0, 1, 0), btScalar(-3.0));
    btRigidBody bed(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &bedShape));
    w.world.addRigidBody(&bed);
    const Eigen::Vector3d size(1.0, 0.5, 1.0);
    const std::size_t stone = w.addCrate(2500.0, 0, -2.0, 0, size);
    w.run(4.0);
    const btBuoyancyResult& r = w.actions[stone]->getLastResult();
    INFO("stone centre at y = " << w.centreY(stone) << " m, submerged " << r.submergedVolume << " m3");
    CHECK(w.centreY(stone) == Approx(-3.0 + 0.25).margin(0.02));  // on the bed
    CHECK(r.submergedVolume == Approx(size.prod()).epsilon(1e-6));
    CHECK(double(r.buoyancyForce.y()) == Approx(1000.0 * kGravity * size.prod()).epsilon(1e-4));
    CHECK(w.actions[stone]->getSubmergedFraction() == Approx(1.0).epsilon(1e-6));
    w.world.removeRigidBody(&bed);
}
