// Several bounded water bodies in one world (btBuoyancyWorld::addWaterBody): each body floats in the water of the
// region it is in, at that water's level and density; a body outside every region gets no buoyancy and falls;
// overlapping or malformed regions are refused with a message naming them.
// Oracles: Archimedes (a box of density ρ_b and height H floats with draft ρ_b / ρ_w · H), free fall.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btWaterFrame.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
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

using Footprint = std::vector<std::array<double, 2>>;

btWaterBodyInfo polygonWater(const char* name, const btWaterSurface* surface, double density, const Footprint& footprint,
                             double bottom, double top) {
    btWaterBodyInfo info;
    info.name = name;
    info.surface = surface;
    info.fluidDensity = density;
    info.regionKind = btWaterRegionKind::Polygon;
    info.footprint = footprint;
    info.bottom = bottom;
    info.top = top;
    return info;
}

/// The L-shaped lake [0, 4] × [0, 2] ∪ [0, 2] × [0, 4] in (x, z): its notch is [2, 4] × [2, 4].
const Footprint kLake = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};

/// A convex prism tank: the convex footprint `ring` (x, z, either order) from y0 to y1, as outward triangles.
btWaterBodyInfo prismTank(const char* name, const btWaterSurface* surface, const Footprint& ring, double y0, double y1) {
    btWaterBodyInfo info;
    info.name = name;
    info.surface = surface;
    info.regionKind = btWaterRegionKind::Mesh;
    const int n = int(ring.size());
    for (const auto& p : ring) info.meshVertices.push_back(btVector3(btScalar(p[0]), btScalar(y0), btScalar(p[1])));
    for (const auto& p : ring) info.meshVertices.push_back(btVector3(btScalar(p[0]), btScalar(y1), btScalar(p[1])));
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const btVector3& v : info.meshVertices) centre += Eigen::Vector3d(v.x(), v.y(), v.z()) / double(2 * n);
    const auto add = [&](int a, int b, int c) {  // flipped to face away from the centre
        const btVector3 &A = info.meshVertices[std::size_t(a)], &B = info.meshVertices[std::size_t(b)],
                        &C = info.meshVertices[std::size_t(c)];
        const btVector3 normal = (B - A).cross(C - A);
        const btVector3 out = (A + B + C) / 3 - btVector3(btScalar(centre.x()), btScalar(centre.y()), btScalar(centre.z()));
        if (normal.dot(out) > 0) info.meshTriangles.insert(info.meshTriangles.end(), {a, b, c});
        else info.meshTriangles.insert(info.meshTriangles.end(), {a, c, b});
    };
    for (int k = 0; k < n; ++k) {
        const int j = (k + 1) % n;
        add(k, j, n + j);
        add(k, n + j, n + k);
        if (k > 0 && j > 0) {  // the floor and the lid, fanned from corner 0
            add(0, k, j);
            add(n, n + k, n + j);
        }
    }
    return info;
}

/// A closed mesh: the polygon `ring` (either winding) with its triangles `cut` (indices into ring), swept along the
/// world axis `along` (0 x, 1 y, 2 z) from w0 to w1; the ring's two coordinates are the other two axes in order (along y:
/// (x, z); along z: (x, y)). Oriented outward (the whole mesh is flipped when its volume comes out negative).
btWaterBodyInfo sweptMesh(const char* name, const btWaterSurface* surface, const Footprint& ring,
                          const std::vector<std::array<int, 3>>& cut, int along, double w0, double w1) {
    btWaterBodyInfo info;
    info.name = name;
    info.surface = surface;
    info.regionKind = btWaterRegionKind::Mesh;
    const int n = int(ring.size());
    const int u = along == 0 ? 1 : 0, v = along == 2 ? 1 : 2;
    for (const double w : {w0, w1})
        for (const auto& p : ring) {
            btVector3 q;
            q[along] = btScalar(w);
            q[u] = btScalar(p[0]);
            q[v] = btScalar(p[1]);
            info.meshVertices.push_back(q);
        }
    for (const auto& t : cut) {
        info.meshTriangles.insert(info.meshTriangles.end(), {t[0], t[2], t[1]});              // the cap at w0
        info.meshTriangles.insert(info.meshTriangles.end(), {n + t[0], n + t[1], n + t[2]});  // the cap at w1
    }
    for (int k = 0; k < n; ++k) {
        const int j = (k + 1) % n;
        info.meshTriangles.insert(info.meshTriangles.end(), {k, j, n + j, k, n + j, n + k});
    }
    // Flip everything when the caps' winding made the volume negative (the sides follow the same ring order).
    double volume6 = 0;
    for (std::size_t t = 0; t < info.meshTriangles.size(); t += 3) {
        const btVector3 &a = info.meshVertices[std::size_t(info.meshTriangles[t])],
                        &b = info.meshVertices[std::size_t(info.meshTriangles[t + 1])],
                        &c = info.meshVertices[std::size_t(info.meshTriangles[t + 2])];
        volume6 += double(a.dot(b.cross(c)));
    }
    if (volume6 < 0)
        for (std::size_t t = 0; t < info.meshTriangles.size(); t += 3) std::swap(info.meshTriangles[t + 1], info.meshTriangles[t + 2]);
    return info;
}

/// A tank whose wall z = 2 runs from x = −2 to 2: the pentagon (−2, −2), (2, −2), (3, 0), (2, 2), (−2, 2).
const Footprint kTankRing = {{-2, -2}, {2, -2}, {3, 0}, {2, 2}, {-2, 2}};

/// regionHydrostatics of `mesh` at `pose` in the pieces of `body` (world = water frame).
buoyancy::HydrostaticsResult inRegion(const btWaterBody& body, const buoyancy::TriangleMesh& mesh,
                                      const Eigen::Isometry3d& pose) {
    std::vector<buoyancy::WaterRegion> regions;
    body.appendWaterRegions(btWaterFrame(), regions);
    return buoyancy::regionHydrostatics(mesh, pose, regions.data(), regions.size(), 0.0, kGravity,
                                        pose.translation());
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

TEST_CASE("water bodies: a box across the inner corner of an L-shaped lake gets the volume and force of its parts inside",
          "[bullet][waters]") {
    // The lake's footprint is non-convex (cut into triangles, the body clipped against each triangle's prism and the
    // parts summed). A 2 × 1 × 2 m box centred at (2.5, 0, 2.5) over the notch's corner (2, 2): by hand, the parts of
    // its footprint [1.5, 3.5]² inside the L are [1.5, 3.5] × [1.5, 2] (1 m², centroid (2.5, 1.75)) and
    // [1.5, 2] × [2, 3.5] (0.75 m², centroid (1.75, 2.75)); each a prism of depth D below the level 0.2 m.
    const double level = 0.2, rho = 1000.0, D = level + 0.5;
    const btFlatWaterSurface water(level);
    btBuoyancyWorld world(nullptr, rho, kGravity);
    REQUIRE(world.addWaterBody(polygonWater("lake", &water, rho, kLake, -3.0, 1.0)) == 0);
    const btWaterBody& lake = world.getWaterBodies()[0];
    CHECK(lake.footprintTriangles.size() == 4);
    const buoyancy::TriangleMesh box = buoyancy::makeBoxMesh(2.0, 1.0, 2.0);
    const Eigen::Isometry3d pose(Eigen::Translation3d(2.5, 0.0, 2.5));
    const auto h = inRegion(lake, box, pose);
    const double A1 = 1.0, A2 = 0.75, V = (A1 + A2) * D;
    CHECK(h.submerged_volume == Approx(V).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.x() == Approx((A1 * 2.5 + A2 * 1.75) / (A1 + A2)).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.z() == Approx((A1 * 1.75 + A2 * 2.75) / (A1 + A2)).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.y() == Approx(-0.5 + D / 2).epsilon(1e-12));
    // The bottom's parts inside pressed by ρ g D; horizontally ρ g D²/2 per metre of the end faces' parts inside:
    // x = 1.5 over z in [1.5, 3.5] (2 m, pushed to +x) against x = 3.5 over z in [1.5, 2] (0.5 m, pushed to −x), and
    // likewise along z.
    CHECK(h.force.y() == Approx(rho * kGravity * D * (A1 + A2)).epsilon(1e-12));
    CHECK(h.force.x() == Approx(rho * kGravity * D * D / 2 * (2.0 - 0.5)).epsilon(1e-12));
    CHECK(h.force.z() == Approx(rho * kGravity * D * D / 2 * (2.0 - 0.5)).epsilon(1e-12));

    // The same box through a world's step: the action sees it straddle the lake's shore and clips it likewise.
    WaterBodiesWorld w;
    w.buoyancy.addWaterBody(polygonWater("lake", &water, rho, kLake, -3.0, 1.0));
    const std::size_t i = w.addCrate(500.0, 2.5, 0.0, 2.5, Eigen::Vector3d(2.0, 1.0, 2.0));
    w.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    const btBuoyancyResult& r = w.actions[i]->getLastResult();
    // The 0.2 mm fall of the substep changes the volume by 1.75 m² × 0.2 mm (5e-4 of it).
    CHECK(double(r.submergedVolume) == Approx(V).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.y()) == Approx(rho * kGravity * V).epsilon(1e-3));
}

TEST_CASE("water bodies: a box half inside a convex mesh tank gets the pressure of its half inside", "[bullet][waters]") {
    // A 1 m cube centred on the tank's wall z = 2, level 0.25 m: the half z < 2 is inside, D = 0.75 m deep. By hand:
    // V = 0.5 × 1 × D, the bottom's half pressed by ρ g D, the face z = 1.5 pushed to +z by ρ g D²/2 × 1 m (the
    // wall's cut is not a face of the body: nothing pushes back).
    const double level = 0.25, rho = 1025.0, D = level + 0.5;
    const btFlatWaterSurface water(level);
    btBuoyancyWorld world(nullptr, rho, kGravity);
    btWaterBodyInfo info = prismTank("tank", &water, kTankRing, -3.0, 1.0);
    info.fluidDensity = rho;
    REQUIRE(world.addWaterBody(info) == 0);
    const btWaterBody& tank = world.getWaterBodies()[0];
    CHECK(tank.meshNormals.size() == 7);  // 5 walls, the floor and the lid
    const buoyancy::TriangleMesh cube = buoyancy::makeBoxMesh(1.0, 1.0, 1.0);
    const auto h = inRegion(tank, cube, Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 2.0)));
    CHECK(h.submerged_volume == Approx(0.5 * D).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.z() == Approx(1.75).epsilon(1e-12));
    CHECK(h.force.y() == Approx(rho * kGravity * D * 0.5).epsilon(1e-12));
    CHECK(h.force.z() == Approx(rho * kGravity * D * D / 2).epsilon(1e-12));
    CHECK(h.force.x() == Approx(0.0).margin(1e-9));
    // Fully inside (the tank's walls reach no part of it): the whole cube's ρ g D × 1 m², as unbounded water gives.
    const auto inside = inRegion(tank, cube, Eigen::Isometry3d(Eigen::Translation3d(0.0, 0.0, 0.0)));
    CHECK(inside.submerged_volume == Approx(D).epsilon(1e-12));
    CHECK(inside.force.y() == Approx(rho * kGravity * D).epsilon(1e-12));
    CHECK(inside.force.z() == Approx(0.0).margin(1e-9));
}

TEST_CASE("water bodies: a body inside a polygon lake or a mesh tank gets what unbounded water gives", "[bullet][waters]") {
    // One substep of a moving crate (pressure and drag) in unbounded water, in the L-shaped lake's arm (its bounding
    // sphere within the lake's sides, across the lake's triangles) and in the tank: the same result.
    const double level = 0.2;
    const btFlatWaterSurface water(level);
    const auto step = [](WaterBodiesWorld& w, double x, double z) {
        const std::size_t i = w.addCrate(500.0, x, 0, z);
        w.bodies[i]->getRigidBody()->setLinearVelocity(btVector3(0.3f, -0.2f, 0.7f));
        w.bodies[i]->getRigidBody()->setAngularVelocity(btVector3(0.1f, 0.4f, -0.2f));
        w.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
        return w.actions[i]->getLastResult();
    };
    WaterBodiesWorld unbounded;
    unbounded.buoyancy.setWater(&water);
    const btBuoyancyResult one = step(unbounded, 1.0, 1.0);
    REQUIRE(one.dragForce.length() > 1.0);
    WaterBodiesWorld lake;
    lake.buoyancy.addWaterBody(polygonWater("lake", &water, 1000.0, kLake, -3.0, 1.0));
    const btBuoyancyResult inLake = step(lake, 1.0, 1.0);
    WaterBodiesWorld tank;
    tank.buoyancy.addWaterBody(prismTank("tank", &water, kTankRing, -3.0, 1.0));
    const btBuoyancyResult inTank = step(tank, 1.0, 1.0);
    for (const btBuoyancyResult* r : {&inLake, &inTank}) {
        CHECK((r->buoyancyForce - one.buoyancyForce).length() <= 1e-6 * one.buoyancyForce.length());
        CHECK((r->buoyancyTorque - one.buoyancyTorque).length() <= 1e-6 * one.buoyancyForce.length());
        CHECK((r->dragForce - one.dragForce).length() <= 1e-6 * one.dragForce.length());
        CHECK(r->submergedVolume == Approx(one.submergedVolume).epsilon(1e-6));
    }
}

TEST_CASE("water bodies: polygon and mesh regions that overlap are refused and ones that only touch are accepted",
          "[bullet][waters]") {
    const btFlatWaterSurface water(0.0);
    btBuoyancyWorld world(nullptr, 1000.0, kGravity);
    REQUIRE(world.addWaterBody(polygonWater("lake", &water, 1000.0, kLake, -3.0, 1.0)) == 0);
    // The notch's square shares two edges with the lake; a triangle in the notch touches nothing (its bounding box
    // meets the lake's: a bounding-box test would refuse it).
    CHECK(world.addWaterBody(polygonWater("notch", &water, 1000.0, {{2, 2}, {4, 2}, {4, 3}}, -3.0, 1.0)) == 1);
    CHECK(world.addWaterBody(polygonWater("corner", &water, 1000.0, {{3, 4}, {2, 4}, {4, 3}, {4, 4}}, -3.0, 1.0)) == 2);
    // A box beside the lake sharing the face x = 4, and one below its bottom sharing the plane y = -3.
    CHECK(world.addWaterBody(boxWater("pool", &water, 1000.0, btVector3(4, -3, 0), btVector3(6, 1, 2))) == 3);
    CHECK(world.addWaterBody(boxWater("cellar", &water, 1000.0, btVector3(0, -5, 0), btVector3(4, -3, 2))) == 4);
    // A tank sharing the face x = 0 with the lake.
    Footprint west = {{-2, 0}, {0, 0}, {0, 4}, {-2, 4}};
    CHECK(world.addWaterBody(prismTank("west tank", &water, west, -3.0, 1.0)) == 5);
    // Overlaps: a square reaching 0.1 m into the lake's arm, a box into its corner, a tank into it.
    try {
        world.addWaterBody(polygonWater("pond", &water, 1000.0, {{1.9, 2.5}, {1.95, 3.5}, {1.99, 3.5}}, -3.0, 1.0));
        FAIL("overlapping polygon accepted");
    } catch (const std::invalid_argument& e) {
        CHECK_THAT(e.what(), Contains("\"pond\"") && Contains("\"lake\"") && Contains("overlap") && Contains("polygon"));
    }
    CHECK_THROWS_WITH(world.addWaterBody(boxWater("box", &water, 1000.0, btVector3(3.5, -1, 1.5), btVector3(5, 0, 2.5))),
                      Contains("\"box\"") && Contains("\"lake\"") && Contains("overlap"));
    Footprint east = {{-1, 1}, {0.5, 1}, {0.5, 2}, {-1, 2}};
    CHECK_THROWS_WITH(world.addWaterBody(prismTank("east tank", &water, east, -1.0, 0.0)),
                      Contains("\"east tank\"") && Contains("overlap"));
    CHECK(world.getWaterBodies().size() == 6);
}

TEST_CASE("water bodies: bad footprints and meshes are refused with a message naming the problem", "[bullet][waters]") {
    const btFlatWaterSurface water(0.0);
    btBuoyancyWorld world(nullptr, 1000.0, kGravity);
    CHECK_THROWS_WITH(world.addWaterBody(polygonWater("bow", &water, 1000.0, {{0, 0}, {2, 2}, {2, 0}, {0, 2}}, -1, 1)),
                      Contains("\"bow\"") && Contains("footprint: not a simple polygon: edge 0") && Contains("meets edge 2"));
    CHECK_THROWS_WITH(world.addWaterBody(polygonWater("two", &water, 1000.0, {{0, 0}, {2, 2}}, -1, 1)),
                      Contains("footprint: a polygon needs at least 3 corners (got 2)"));
    CHECK_THROWS_WITH(world.addWaterBody(polygonWater("line", &water, 1000.0, {{0, 0}, {1, 1}, {3, 3}}, -1, 1)),
                      Contains("footprint: not a simple polygon"));  // collinear: the closing edge folds back
    CHECK_THROWS_WITH(world.addWaterBody(polygonWater("twice", &water, 1000.0, {{0, 0}, {1, 0}, {1, 1}, {1, 0}}, -1, 1)),
                      Contains("corners 1 and 3 are the same point"));
    CHECK_THROWS_WITH(world.addWaterBody(polygonWater("back", &water, 1000.0, {{0, 0}, {2, 0}, {1, 0}, {1, 1}}, -1, 1)),
                      Contains("fold back"));
    CHECK_THROWS_WITH(world.addWaterBody(polygonWater("flat", &water, 1000.0, kLake, 1, 1)),
                      Contains("\"flat\"") && Contains("top: must be greater than bottom"));
    // A C-shaped tank (its section in x, y swept along z): the lower arm's top lies under the upper arm's.
    const Footprint cSection = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {3, 2}, {3, 3}, {0, 3}};
    CHECK_THROWS_WITH(world.addWaterBody(sweptMesh("cee", &water, cSection,
                                                   {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 7}, {4, 5, 6}, {4, 6, 7}}, 2,
                                                   0.0, 1.0)),
                      Contains("\"cee\"") && Contains("the region mesh of water body 'cee' overhangs: triangles") &&
                          Contains("m^2 in common seen from above"));
    btWaterBodyInfo open = prismTank("open", &water, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0.0, 1.0);
    open.meshTriangles.resize(open.meshTriangles.size() - 3);
    CHECK_THROWS_WITH(world.addWaterBody(open), Contains("\"open\"") && Contains("not closed"));
    btWaterBodyInfo inward = prismTank("inward", &water, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0.0, 1.0);
    for (std::size_t t = 0; t < inward.meshTriangles.size(); t += 3) std::swap(inward.meshTriangles[t + 1], inward.meshTriangles[t + 2]);
    CHECK_THROWS_WITH(world.addWaterBody(inward), Contains("face inward"));
    CHECK(world.getWaterBodies().empty());
}

TEST_CASE("water bodies: a mesh of more than 32 face planes is taken as columns under its footprint", "[bullet][waters]") {
    // A 40-sided tank (42 distinct planes, more than a convex region clips by) of circumradius 2 m: its inscribed
    // radius is 2 cos(π/40) = 1.99383 m.
    const btFlatWaterSurface water(0.5);
    btBuoyancyWorld world(nullptr, 1000.0, kGravity);
    Footprint round;
    for (int k = 0; k < 40; ++k) round.push_back({2.0 * std::cos(0.05 * M_PI * k), 2.0 * std::sin(0.05 * M_PI * k)});
    REQUIRE(world.addWaterBody(prismTank("round", &water, round, 0.0, 1.0)) == 0);
    const btWaterBody& tank = world.getWaterBodies()[0];
    CHECK(tank.meshColumns);
    const double inscribed = 2.0 * std::cos(M_PI / 40);
    CHECK(tank.sphereWithinSides(btWaterFrame(), Eigen::Vector3d(0, 0.5, 0), inscribed - 1e-4));
    CHECK_FALSE(tank.sphereWithinSides(btWaterFrame(), Eigen::Vector3d(0, 0.5, 0), inscribed + 1e-4));
    CHECK(world.queryWater(btVector3(1.9f, 0.25f, 0)).waterBody == 0);
    CHECK(world.queryWater(btVector3(1.9f, 0.25f, 0.7f)).waterBody == -1);  // 1.9² + 0.7² > 2²: outside
    CHECK(world.queryWater(btVector3(0, -0.25f, 0)).waterBody == -1);       // below its floor
    CHECK(tank.distanceTo(btWaterFrame(), Eigen::Vector3d(0, -0.25, 0)) == Approx(0.25));
    // A box's prism pieces tile the footprint: a 1 m cube wholly inside gets unbounded water's volume.
    std::vector<buoyancy::WaterRegion> pieces;
    tank.appendWaterRegions(btWaterFrame(), pieces);
    CHECK(pieces.size() == 38);  // the lid's fan of 40 corners
    const auto h = inRegion(tank, buoyancy::makeBoxMesh(1.0, 1.0, 1.0), Eigen::Isometry3d(Eigen::Translation3d(0.3, 0.3, 0.2)));
    CHECK(h.submerged_volume == Approx(0.7).epsilon(1e-12));
}

/// The L-shaped lake's footprint cut into triangles (same winding as kLake).
const std::vector<std::array<int, 3>> kLakeCut = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};

TEST_CASE("water bodies: an L-shaped lock given as a mesh gets what the same L as a polygon lake gives",
          "[bullet][waters]") {
    // The L-shaped lake of the polygon test as a closed mesh (non-convex: taken as columns). The 2 × 1 × 2 m box over
    // the notch's corner: by hand, 1 m² + 0.75 m² of its footprint inside, D = 0.7 m deep (see the polygon test).
    const double level = 0.2, rho = 1000.0, D = level + 0.5;
    const btFlatWaterSurface water(level);
    btBuoyancyWorld world(nullptr, rho, kGravity);
    REQUIRE(world.addWaterBody(sweptMesh("lock", &water, kLake, kLakeCut, 1, -3.0, 1.0)) == 0);
    const btWaterBody& lock = world.getWaterBodies()[0];
    CHECK(lock.meshColumns);
    const auto h = inRegion(lock, buoyancy::makeBoxMesh(2.0, 1.0, 2.0), Eigen::Isometry3d(Eigen::Translation3d(2.5, 0.0, 2.5)));
    const double A1 = 1.0, A2 = 0.75, V = (A1 + A2) * D;
    CHECK(h.submerged_volume == Approx(V).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.x() == Approx((A1 * 2.5 + A2 * 1.75) / (A1 + A2)).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.z() == Approx((A1 * 1.75 + A2 * 2.75) / (A1 + A2)).epsilon(1e-12));
    CHECK(h.force.y() == Approx(rho * kGravity * D * (A1 + A2)).epsilon(1e-12));
    CHECK(h.force.x() == Approx(rho * kGravity * D * D / 2 * (2.0 - 0.5)).epsilon(1e-12));
    CHECK(h.force.z() == Approx(rho * kGravity * D * D / 2 * (2.0 - 0.5)).epsilon(1e-12));
    // Point queries: the arm, the notch, below the floor, above the lid (the column).
    CHECK(world.queryWater(btVector3(3, -1, 1)).waterBody == 0);
    CHECK(world.queryWater(btVector3(3, -1, 3)).waterBody == -1);
    CHECK(world.queryWater(btVector3(1, -4, 1)).waterBody == -1);
    CHECK(world.queryWater(btVector3(1, 5, 3)).waterBody == 0);
    CHECK(lock.distanceTo(btWaterFrame(), Eigen::Vector3d(3.0, 0.0, 3.0)) == Approx(1.0));
    CHECK(lock.sphereWithinSides(btWaterFrame(), Eigen::Vector3d(1.0, 0.0, 1.0), 0.9));
    CHECK_FALSE(lock.sphereWithinSides(btWaterFrame(), Eigen::Vector3d(1.5, 0.0, 1.5), 0.8));  // the notch's corner
    // A polygon lake in the notch touches the lock (accepted); one reaching into its arm overlaps (refused).
    CHECK(world.addWaterBody(polygonWater("notch", &water, rho, {{2, 2}, {4, 2}, {4, 4}, {2, 4}}, -3.0, 1.0)) == 1);
    CHECK_THROWS_WITH(world.addWaterBody(polygonWater("pond", &water, rho, {{3, -1}, {5, -1}, {5, 1}, {3, 1}}, -3.0, 1.0)),
                      Contains("\"pond\"") && Contains("\"lock\"") && Contains("overlap"));

    // Through a world's step: the action sees the box straddle the lock's shore and clips it likewise.
    WaterBodiesWorld w;
    w.buoyancy.addWaterBody(sweptMesh("lock", &water, kLake, kLakeCut, 1, -3.0, 1.0));
    const std::size_t i = w.addCrate(500.0, 2.5, 0.0, 2.5, Eigen::Vector3d(2.0, 1.0, 2.0));
    w.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    CHECK(double(w.actions[i]->getLastResult().submergedVolume) == Approx(V).epsilon(1e-3));
}

/// A stepped pool's section in (x, y): the deep end x in [0, 4] down to y = −3, the shallow end x in [4, 8] down to
/// y = −1, the lid at y = 1; swept along z from 0 to 4.
const Footprint kStepSection = {{0, -3}, {4, -3}, {4, -1}, {8, -1}, {8, 1}, {0, 1}};
const std::vector<std::array<int, 3>> kStepCut = {{0, 1, 2}, {0, 2, 5}, {2, 3, 4}, {2, 4, 5}};

TEST_CASE("water bodies in a Z-up world: a stepped pool mesh is columns along +z", "[bullet][waters]") {
    // The stepped pool's section given in the world's (x, z), swept along y: with gravity −z its floors are at
    // z = −3 (x < 4) and z = −1 (x > 4), its lid at z = 1.
    const btFlatWaterSurface water(0.0);
    WaterBodiesWorld w(btVector3(0, 0, btScalar(-kGravity)));
    REQUIRE(w.buoyancy.addWaterBody(sweptMesh("pool", &water, kStepSection, kStepCut, 1, 0.0, 4.0)) == 0);
    CHECK(w.buoyancy.getWaterBodies()[0].meshColumns);
    const auto at = [&](double x, double y, double z) {
        return w.buoyancy.queryWater(btVector3(btScalar(x), btScalar(y), btScalar(z)));
    };
    CHECK(at(2, 2, -2.5).waterBody == 0);
    CHECK(double(at(2, 2, -2.5).depth) == Approx(2.5));
    CHECK(at(6, 2, -0.5).waterBody == 0);
    CHECK(at(6, 2, -2.0).waterBody == -1);
    CHECK(at(9, 2, -0.5).waterBody == -1);
    // A crate of density 600 kg/m³ (0.5 m along z) in the shallow end floats with draft 0.3 m (Archimedes).
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 1.0, 0.5));
    btBuoyantBodySettings settings;
    settings.density = 600.0;
    w.bodies.push_back(std::make_unique<btBuoyantBody>(shape, settings,
                                                       btTransform(btQuaternion::getIdentity(), btVector3(6, 2, 0.25f))));
    w.world.addRigidBody(w.bodies.back()->getRigidBody());
    w.actions.push_back(std::make_unique<btBuoyancyAction>(*w.bodies.back(), &w.buoyancy));
    w.world.addAction(w.actions.back().get());
    w.run(8.0);
    CHECK(-(double(w.bodies.back()->getRigidBody()->getCenterOfMassPosition().z()) - 0.25) == Approx(0.3).margin(2e-3));
}

TEST_CASE("water bodies: a stepped pool mesh holds water down to each end's floor and a crate floats at its draft",
          "[bullet][waters]") {
    const btFlatWaterSurface water(0.0);
    WaterBodiesWorld w;
    REQUIRE(w.buoyancy.addWaterBody(sweptMesh("pool", &water, kStepSection, kStepCut, 2, 0.0, 4.0)) == 0);
    CHECK(w.buoyancy.getWaterBodies()[0].meshColumns);
    const auto at = [&](double x, double y, double z) {
        return w.buoyancy.queryWater(btVector3(btScalar(x), btScalar(y), btScalar(z)));
    };
    CHECK(at(2, -2.5, 2).waterBody == 0);   // deep end, above its floor
    CHECK(at(6, -0.5, 2).waterBody == 0);   // shallow end
    CHECK(at(6, -2.0, 2).waterBody == -1);  // under the shallow end's floor
    CHECK(at(2, -3.5, 2).waterBody == -1);  // under the deep end's floor
    CHECK(double(at(2, -2.5, 2).depth) == Approx(2.5));
    // Regions under the shallow end: one sharing its floor and the step's riser is accepted, one reaching 0.5 m up
    // into the pool across the step is refused, one under the deep end's floor accepted.
    CHECK(w.buoyancy.addWaterBody(boxWater("cellar", &water, 1000.0, btVector3(4, -3, 0), btVector3(8, -1, 4))) == 1);
    CHECK(w.buoyancy.addWaterBody(boxWater("sump", &water, 1000.0, btVector3(0, -5, 0), btVector3(4, -3, 4))) == 2);
    CHECK_THROWS_WITH(w.buoyancy.addWaterBody(boxWater("riser", &water, 1000.0, btVector3(3.5, -2, 1), btVector3(4.5, -1.5, 2))),
                      Contains("\"riser\"") && Contains("\"pool\"") && Contains("overlap"));
    // A crate of density 600 kg/m³ in each end floats with draft 0.6 × 0.5 m (Archimedes).
    const std::size_t deep = w.addCrate(600.0, 2.0, 0.5, 2.0), shallow = w.addCrate(600.0, 6.0, 0.5, 2.0);
    w.run(8.0);
    for (const std::size_t i : {deep, shallow}) {
        const double bottom = w.centreY(i) - 0.25;
        CHECK(-bottom == Approx(0.6 * 0.5).margin(2e-3));
    }
}

TEST_CASE("water bodies: point queries answer with the polygon lake or the mesh tank the point is in", "[bullet][waters]") {
    const btFlatWaterSurface lakeWater(0.0), tankWater(0.5);
    btBuoyancyWorld world(nullptr, 1000.0, kGravity);
    world.addWaterBody(polygonWater("lake", &lakeWater, 1000.0, kLake, -3.0, 1.0));
    world.addWaterBody(prismTank("tank", &tankWater, {{5, 0}, {7, 0}, {6, 2}}, -1.0, 1.0));
    const auto at = [&](double x, double y, double z) { return world.queryWater(btVector3(btScalar(x), btScalar(y), btScalar(z))); };
    const btWaterQueryResult arm = at(3.0, -1.0, 1.0);  // in the lake's x arm
    CHECK(arm.waterBody == 0);
    CHECK(arm.inWater);
    CHECK(double(arm.depth) == Approx(1.0));
    CHECK(at(1.0, 5.0, 3.0).waterBody == 0);   // above its top, within its sides: the lake's column
    CHECK(at(3.0, -1.0, 3.0).waterBody == -1);  // in the notch: no water
    CHECK_FALSE(at(3.0, -1.0, 3.0).hasWater);
    CHECK(at(1.0, -4.0, 1.0).waterBody == -1);  // below the lake's bottom
    const btWaterQueryResult inTank = at(6.0, 0.0, 0.5);
    CHECK(inTank.waterBody == 1);
    CHECK(double(inTank.depth) == Approx(0.5));
    CHECK(at(5.2, 0.0, 1.5).waterBody == -1);  // beside the tank's slanted wall
    // The sphere tests the action uses: within the lake's sides, reaching the notch or not.
    const btWaterBody& lake = world.getWaterBodies()[0];
    CHECK(lake.sphereWithinSides(btWaterFrame(), Eigen::Vector3d(1.0, 0.0, 1.0), 0.9));
    CHECK_FALSE(lake.sphereWithinSides(btWaterFrame(), Eigen::Vector3d(1.5, 0.0, 1.5), 0.8));  // the notch's corner 0.71 m away
    CHECK(lake.distanceTo(btWaterFrame(), Eigen::Vector3d(3.0, 0.0, 3.0)) == Approx(1.0));
    CHECK(lake.distanceTo(btWaterFrame(), Eigen::Vector3d(1.0, 4.0, 1.0)) == Approx(3.0));
}

TEST_CASE("water bodies in a Z-up world: a footprint is in the water frame's horizontal axes", "[bullet][waters]") {
    // Gravity −z: the water frame's x is the world's +x and its z the world's −y (btWaterFrame), heights along +z. The
    // L-shaped lake's footprint is given in those axes, so its notch [2, 4] × [2, 4] (water x, z) is the world's
    // x in [2, 4], y in [−4, −2]. The box of the Y-up test, 2 m along x and y and 1 m tall along z, over the notch's
    // corner: the same 1.75 m² of its footprint inside, D = 0.7 m deep.
    WaterBodiesWorld w(btVector3(0, 0, btScalar(-kGravity)));
    const double level = 0.2, D = level + 0.5;
    const btFlatWaterSurface water(level);
    w.buoyancy.addWaterBody(polygonWater("lake", &water, 1000.0, kLake, -3.0, 1.0));
    const auto at = [&](double x, double y, double z) {
        return w.buoyancy.queryWater(btVector3(btScalar(x), btScalar(y), btScalar(z))).waterBody;
    };
    CHECK(at(3.0, -1.0, -0.5) == 0);   // water (3, −0.5, 1): the x arm
    CHECK(at(3.0, -3.0, -0.5) == -1);  // water (3, −0.5, 3): the notch
    CHECK(at(3.0, 1.0, -0.5) == -1);   // water z = −1: outside
    const std::size_t i = w.addCrate(500.0, 2.5, -2.5, 0.0, Eigen::Vector3d(2.0, 2.0, 1.0));
    w.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    const btBuoyancyResult& r = w.actions[i]->getLastResult();
    CHECK(double(r.submergedVolume) == Approx(1.75 * D).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.z()) == Approx(1000.0 * kGravity * 1.75 * D).epsilon(1e-3));
}

TEST_CASE("water bodies: a box over the edge of a lake of many footprint triangles gets its half inside",
          "[bullet][waters]") {
    // The rectangle [0, 10] × [0, 4] with 19 more corners along its edge z = 0 (cut into about 20 thin triangles, of
    // which the action keeps only those its bounding sphere reaches). A 1 m cube centred on the edge x = 10: half of
    // it inside, V = 0.5 × D, ρ g D²/2 on its face x = 9.5.
    Footprint shore;
    for (int k = 0; k <= 20; ++k) shore.push_back({0.5 * k, 0.0});
    shore.push_back({10.0, 4.0});
    shore.push_back({0.0, 4.0});
    const double level = 0.2, D = level + 0.5;
    const btFlatWaterSurface water(level);
    WaterBodiesWorld w;
    w.buoyancy.addWaterBody(polygonWater("lake", &water, 1000.0, shore, -3.0, 1.0));
    CHECK(w.buoyancy.getWaterBodies()[0].footprintTriangles.size() >= 20);
    const std::size_t i = w.addCrate(500.0, 10.0, 0.0, 2.0, Eigen::Vector3d(1.0, 1.0, 1.0));
    w.world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    const btBuoyancyResult& r = w.actions[i]->getLastResult();
    CHECK(double(r.submergedVolume) == Approx(0.5 * D).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.y()) == Approx(1000.0 * kGravity * 0.5 * D).epsilon(1e-3));
    CHECK(double(r.buoyancyForce.x()) == Approx(1000.0 * kGravity * D * D / 2).epsilon(2e-3));
}
