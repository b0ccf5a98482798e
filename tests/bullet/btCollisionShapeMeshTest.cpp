// Bring your own body: the mesh of a Bullet collision shape (btCollisionShapeToMesh, btBuoyancyShape::fromCollisionShape)
// and the action that takes a user's btRigidBody as it is. Oracles: the closed-form volumes of the primitives, the
// extents Bullet documents for each shape and axis, Archimedes for the floating bodies (the submerged volume of a
// body at rest is its mass / ρ, whatever its shape).
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btCollisionShapeMesh.h>
#include <BulletBuoyancy/integrals/CapsuleHydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

using Catch::Matchers::Contains;

namespace {

constexpr double kPi = 3.14159265358979323846;

double volumeOf(const buoyancy::TriangleMesh& m) {
    double v = 0;
    for (const auto& t : m.triangles)
        v += m.vertices[std::size_t(t[0])].dot(m.vertices[std::size_t(t[1])].cross(m.vertices[std::size_t(t[2])]));
    return v / 6.0;
}

/// A user's Bullet world, y up, with flat water at 0 and its buoyancy context.
struct FlatWaterWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btFlatWaterSurface water{0.0};
    btBuoyancyWorld buoyancyWorld{&world, &water, 1000.0};
    FlatWaterWorld() { world.setGravity(btVector3(0, btScalar(-9.81), 0)); }
};

Eigen::Vector3d extent(const buoyancy::TriangleMesh& m, bool upper) {
    Eigen::Vector3d e = m.vertices.front();
    for (const auto& v : m.vertices) e = upper ? Eigen::Vector3d(e.cwiseMax(v)) : Eigen::Vector3d(e.cwiseMin(v));
    return e;
}

}  // namespace

TEST_CASE("collision shape mesh: primitives have their closed-form volume and Bullet's extents", "[bullet][shapes]") {
    const double tol = 1e-3;
    SECTION("box: exact, the margin inside the extents") {
        btBoxShape box(btVector3(0.5f, 0.2f, 0.4f));
        const auto m = btCollisionShapeToMesh(box, tol);
        CHECK(volumeOf(m) == Approx(1.0 * 0.4 * 0.8).epsilon(1e-6));
        CHECK(extent(m, true).x() == Approx(0.5).epsilon(1e-6));
    }
    SECTION("sphere: within the tolerance, inscribed") {
        btSphereShape sphere(0.5f);
        const double exact = 4.0 / 3.0 * kPi * 0.125;
        const auto sm = btCollisionShapeToMesh(sphere, tol);
        std::printf("curved shapes at tolerance %g: sphere %zu triangles\n", tol, sm.triangleCount());
        const double v = volumeOf(sm);
        CHECK(v <= exact);
        CHECK(v >= exact * (1 - tol));
        // A tighter tolerance gets closer.
        CHECK(volumeOf(btCollisionShapeToMesh(sphere, 1e-4)) >= exact * (1 - 1e-4));
    }
    SECTION("capsule, cylinder and cone along x, y and z") {
        const double r = 0.3, h = 1.2;  // cylinder/cone height; capsule: cylinder part h, radius r
        for (int axis = 0; axis < 3; ++axis) {
            INFO("axis " << axis);
            std::unique_ptr<btCollisionShape> capsule, cylinder, cone;
            const btVector3 cylHalf = axis == 0 ? btVector3(btScalar(h / 2), btScalar(r), btScalar(r))
                                    : axis == 1 ? btVector3(btScalar(r), btScalar(h / 2), btScalar(r))
                                                : btVector3(btScalar(r), btScalar(r), btScalar(h / 2));
            if (axis == 0) {
                capsule = std::make_unique<btCapsuleShapeX>(btScalar(r), btScalar(h));
                cylinder = std::make_unique<btCylinderShapeX>(cylHalf);
                cone = std::make_unique<btConeShapeX>(btScalar(r), btScalar(h));
            } else if (axis == 1) {
                capsule = std::make_unique<btCapsuleShape>(btScalar(r), btScalar(h));
                cylinder = std::make_unique<btCylinderShape>(cylHalf);
                cone = std::make_unique<btConeShape>(btScalar(r), btScalar(h));
            } else {
                capsule = std::make_unique<btCapsuleShapeZ>(btScalar(r), btScalar(h));
                cylinder = std::make_unique<btCylinderShapeZ>(cylHalf);
                cone = std::make_unique<btConeShapeZ>(btScalar(r), btScalar(h));
            }
            const double capsuleV = kPi * r * r * (h + 4.0 / 3.0 * r), cylinderV = kPi * r * r * h,
                         coneV = kPi * r * r * h / 3.0;
            const auto mc = btCollisionShapeToMesh(*capsule, tol), my = btCollisionShapeToMesh(*cylinder, tol),
                       mk = btCollisionShapeToMesh(*cone, tol);
            if (axis == 1)
                std::printf("curved shapes at tolerance %g: capsule %zu, cylinder %zu, cone %zu triangles\n", tol,
                            mc.triangleCount(), my.triangleCount(), mk.triangleCount());
            CHECK(volumeOf(mc) == Approx(capsuleV).epsilon(tol * 1.01));
            CHECK(volumeOf(my) == Approx(cylinderV).epsilon(tol * 1.01));
            CHECK(volumeOf(mk) == Approx(coneV).epsilon(tol * 1.01));
            // Along the axis: the capsule reaches h/2 + r, the cylinder h/2, the cone's apex +h/2 and base −h/2.
            CHECK(extent(mc, true)[axis] == Approx(h / 2 + r).epsilon(1e-6));
            CHECK(extent(my, true)[axis] == Approx(h / 2).epsilon(1e-6));
            CHECK(extent(mk, true)[axis] == Approx(h / 2).epsilon(1e-6));
            CHECK(extent(mk, false)[axis] == Approx(-h / 2).epsilon(1e-6));
            // Across it: the radius.
            const int across = (axis + 1) % 3;
            CHECK(extent(my, true)[across] == Approx(r).epsilon(1e-6));
        }
    }
    SECTION("convex hull: its points, without Bullet's 0.04 m margin") {
        btConvexHullShape hull;
        for (int i = 0; i < 8; ++i) hull.addPoint(btVector3(i & 1 ? 0.5f : -0.5f, i & 2 ? 0.5f : -0.5f, i & 4 ? 0.5f : -0.5f));
        CHECK(volumeOf(btCollisionShapeToMesh(hull, tol)) == Approx(1.0).epsilon(1e-6));
        hull.setLocalScaling(btVector3(2, 1, 1));
        CHECK(volumeOf(btCollisionShapeToMesh(hull, tol)) == Approx(2.0).epsilon(1e-6));
    }
    SECTION("compound: children with their transforms; overlapping children refused") {
        btBoxShape a(btVector3(0.5f, 0.5f, 0.5f)), b(btVector3(0.25f, 0.25f, 0.25f));
        btCompoundShape compound;
        btTransform t;
        t.setIdentity();
        t.setOrigin(btVector3(-1, 0, 0));
        compound.addChildShape(t, &a);
        t.setOrigin(btVector3(1, 0, 0));
        compound.addChildShape(t, &b);
        const auto m = btCollisionShapeToMesh(compound, tol);
        CHECK(volumeOf(m) == Approx(1.0 + 0.125).epsilon(1e-6));
        CHECK(extent(m, false).x() == Approx(-1.5).epsilon(1e-6));
        btCompoundShape overlapping;
        t.setOrigin(btVector3(0, 0, 0));
        overlapping.addChildShape(t, &a);
        t.setOrigin(btVector3(0.6f, 0, 0));
        overlapping.addChildShape(t, &b);
        CHECK_THROWS_WITH(btCollisionShapeToMesh(overlapping, tol), Contains("do not overlap"));
    }
}

TEST_CASE("collision shape mesh: multi-sphere, convex triangle mesh and GImpact mesh shapes", "[bullet][shapes]") {
    const double kPi = 3.14159265358979323846;
    const double tol = 1e-3;
    SECTION("two equal spheres are a capsule (their hull), as Bullet collides them") {
        const btVector3 centres[2] = {btVector3(0, -0.5, 0), btVector3(0, 0.5, 0)};
        const btScalar radii[2] = {btScalar(0.3), btScalar(0.3)};
        btMultiSphereShape shape(centres, radii, 2);
        const double r = 0.3, length = 1.0;
        const double capsule = kPi * r * r * length + 4.0 / 3.0 * kPi * r * r * r;
        const double v = volumeOf(btCollisionShapeToMesh(shape, tol));
        CHECK(v <= capsule);                  // inscribed
        CHECK(v >= capsule * (1 - 2 * tol));  // each sphere within the tolerance, the hull about as close
        // Scaled by 2 on every axis: eight times the volume.
        shape.setLocalScaling(btVector3(2, 2, 2));
        CHECK(volumeOf(btCollisionShapeToMesh(shape, tol)) == Approx(8 * v).epsilon(2 * tol));
    }
    // A closed 2 x 1 x 1 box as a striding mesh (12 triangles, outward).
    btTriangleMesh boxTriangles;
    {
        const btVector3 c[8] = {{-1, -0.5, -0.5}, {1, -0.5, -0.5}, {-1, 0.5, -0.5}, {1, 0.5, -0.5},
                                {-1, -0.5, 0.5},  {1, -0.5, 0.5},  {-1, 0.5, 0.5},  {1, 0.5, 0.5}};
        const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& q : quads) {
            boxTriangles.addTriangle(c[q[0]], c[q[1]], c[q[2]]);
            boxTriangles.addTriangle(c[q[0]], c[q[2]], c[q[3]]);
        }
    }
    SECTION("btConvexTriangleMeshShape: the mesh itself, scaled") {
        btConvexTriangleMeshShape shape(&boxTriangles);
        CHECK(volumeOf(btCollisionShapeToMesh(shape, tol)) == Approx(2.0).epsilon(1e-6));
        shape.setLocalScaling(btVector3(1, 3, 1));
        CHECK(volumeOf(btCollisionShapeToMesh(shape, tol)) == Approx(6.0).epsilon(1e-6));
    }
    SECTION("btGImpactMeshShape: the mesh itself; an open one is refused by name") {
        btGImpactMeshShape shape(&boxTriangles);
        CHECK(volumeOf(btCollisionShapeToMesh(shape, tol)) == Approx(2.0).epsilon(1e-6));
        btTriangleMesh open;
        open.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
        open.addTriangle(btVector3(0, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1));
        btGImpactMeshShape openShape(&open);
        CHECK_THROWS_WITH(btCollisionShapeToMesh(openShape, tol),
                          Contains("btGImpactMeshShape") && Contains("open surface") && Contains("must be closed"));
    }
    SECTION("btBvhTriangleMeshShape is refused with the reason") {
        btBvhTriangleMeshShape shape(&boxTriangles, true);
        CHECK_THROWS_WITH(btCollisionShapeToMesh(shape, tol), Contains("static bodies only"));
    }
}

TEST_CASE("collision shape mesh: unsupported shapes and bad scaling are refused by name", "[bullet][shapes]") {
    btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
    CHECK_THROWS_WITH(btCollisionShapeToMesh(plane, 1e-3), Contains("STATICPLANE") && Contains("not supported"));
    btBoxShape box(btVector3(1, 1, 1));
    box.setLocalScaling(btVector3(1, 0, 1));  // Bullet keeps |scale|: a zero is the scale it cannot use
    CHECK_THROWS_WITH(btCollisionShapeToMesh(box, 1e-3), Contains("local scaling") && Contains("must be positive"));
    btSphereShape sphere(1);
    CHECK_THROWS_WITH(btCollisionShapeToMesh(sphere, 0.0), Contains("curvedShapeTolerance"));
    CHECK_THROWS_WITH(btBuoyancyShape::fromCollisionShape(plane), Contains("not supported"));
}

TEST_CASE("your own btRigidBody: a btBoxShape, btSphereShape or btCapsuleShape body floats at its Archimedes draft",
          "[bullet][shapes]") {
    // A user's world and body, Bullet's defaults everywhere (sleeping thresholds included); the action takes the
    // geometry from the body's collision shape, and the body's own mass and inertia.
    struct Case {
        const char* name;
        double density, volume;
    };
    const int which = GENERATE(0, 1, 2);
    btBoxShape box(btVector3(0.5f, 0.2f, 0.4f));   // s = 0.4: stable flat
    btSphereShape sphere(0.5f);                      // s = 0.3
    btCapsuleShapeZ capsule(0.25f, 1.0f);            // lying along z, s = 0.5
    btCollisionShape* shapes[] = {&box, &sphere, &capsule};
    const Case cases[] = {{"box", 400, 0.32},
                          {"sphere", 300, 4.0 / 3.0 * kPi * 0.125},
                          {"capsule", 500, kPi * 0.0625 * (1.0 + 4.0 / 3.0 * 0.25)}};
    const Case& c = cases[which];
    btCollisionShape* shape = shapes[which];

    FlatWaterWorld scene;
    btDiscreteDynamicsWorld& world = scene.world;
    btBuoyancyWorld& buoyancyWorld = scene.buoyancyWorld;

    const btScalar mass = btScalar(c.density * c.volume);
    btVector3 inertia;
    shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform.setOrigin(btVector3(0, 1, 0));
    btRigidBody body(info);
    world.addRigidBody(&body);
    btBuoyancyAction action(&body, &buoyancyWorld);
    world.addAction(&action);
    // The mean over the last 10 s of 40 (a sphere's heave is damped by drag alone and still rings a little).
    double sum = 0, lo = 1e300, hi = -1e300;
    int count = 0;
    for (int frame = 0; frame < 60 * 40; ++frame) {
        world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        if (frame >= 60 * 30) {
            const double v = action.getLastResult().submergedVolume;
            sum += v;
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            ++count;
        }
    }
    const double submerged = sum / count;
    INFO(c.name << ": mean submerged " << submerged << " m3 (" << lo << " .. " << hi << "), mass / rho "
                << double(mass) / 1000.0 << ", velocity " << body.getLinearVelocity().length() << " m/s, spin "
                << body.getAngularVelocity().length() << " rad/s, axis " << body.getWorldTransform().getBasis().getColumn(2).y());
    CHECK(submerged == Approx(double(mass) / 1000.0).epsilon(3e-3));
    CHECK(action.getLastResult().status == btBuoyancyStatus::Ok);
    world.removeAction(&action);
    world.removeRigidBody(&body);
}

TEST_CASE("your own btRigidBody: a btSphereShape in flat water gets the sphere's cap, not its tessellation",
          "[bullet][shapes]") {
    // The cap height h of a sphere of radius R and density ratio s: π h² (3R − h) / 3 = s · 4/3 π R³, solved here by
    // bisection. At that draft the submerged volume must be s V to float rounding (the tessellated sphere of the
    // default tolerance holds 0.1 % less).
    const double R = 0.5, s = 0.3, V = 4.0 / 3.0 * kPi * R * R * R;
    double lo = 0, hi = 2 * R;
    for (int i = 0; i < 200; ++i) {
        const double h = 0.5 * (lo + hi);
        (kPi * h * h * (3 * R - h) / 3 < s * V ? lo : hi) = h;
    }
    const double h = 0.5 * (lo + hi);
    FlatWaterWorld scene;
    btDiscreteDynamicsWorld& world = scene.world;
    btBuoyancyWorld& buoyancyWorld = scene.buoyancyWorld;
    btSphereShape sphere{btScalar(R)};
    const btScalar mass = btScalar(1000.0 * s * V);
    btVector3 inertia;
    sphere.calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &sphere, inertia);
    info.m_startWorldTransform.setOrigin(btVector3(0.3f, btScalar(R - h), -0.2f));  // bottom at −h: draft h
    btRigidBody body(info);
    world.addRigidBody(&body);
    btBuoyancyAction action(&body, &buoyancyWorld);
    world.addAction(&action);
    REQUIRE(action.getShape()->getSphereRadius() == Approx(R));
    world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    // Bullet runs actions after it has moved the body by this substep's gravity kick (g dt², 0.17 mm): the action saw
    // the pose the body has now. The cap there, by the same formula:
    const double hNow = R - double(body.getCenterOfMassPosition().y());
    const double vNow = kPi * hNow * hNow * (3 * R - hNow) / 3;
    CHECK(std::abs(hNow - h) < 1e-3);
    const btBuoyancyResult& r = action.getLastResult();
    CHECK(r.submergedVolume == Approx(vNow).epsilon(1e-5));
    CHECK(double(r.buoyancyForce.y()) == Approx(1000.0 * 9.81 * vNow).epsilon(1e-5));
    CHECK(double(r.buoyancyTorque.length()) < 1e-6 * double(r.buoyancyForce.length()));  // through the centre
    world.removeAction(&action);
    world.removeRigidBody(&body);
}

TEST_CASE("your own btRigidBody: a btCapsuleShape in flat water gets the capsule's exact hydrostatics along its own axis",
          "[bullet][shapes]") {
    // Capsules along x, y and z, tilted, crossing the water: after one substep the action's result is the capsule's
    // (buoyancy::capsuleHydrostatics, exact; tests/integrals) at the body's pose along the axis Bullet's shape
    // names, and not its tessellation's (0.1 % short at the default tolerance).
    const double r = 0.3, halfHeight = 0.5;
    btCapsuleShapeX alongX{btScalar(r), btScalar(2 * halfHeight)};
    btCapsuleShape alongY{btScalar(r), btScalar(2 * halfHeight)};
    btCapsuleShapeZ alongZ{btScalar(r), btScalar(2 * halfHeight)};
    btCapsuleShape* shapes[] = {&alongX, &alongY, &alongZ};
    for (int axis = 0; axis < 3; ++axis) {
        FlatWaterWorld scene;
        btDiscreteDynamicsWorld& world = scene.world;
        btBuoyancyWorld& buoyancyWorld = scene.buoyancyWorld;
        btRigidBody::btRigidBodyConstructionInfo info(100, nullptr, shapes[axis], btVector3(10, 10, 10));
        info.m_startWorldTransform.setOrigin(btVector3(0.2f, -0.1f, 0.3f));
        info.m_startWorldTransform.setRotation(btQuaternion(btVector3(0.3f, 0.2f, 1.0f).normalized(), btScalar(0.6)));
        btRigidBody body(info);
        body.setActivationState(DISABLE_DEACTIVATION);
        world.addRigidBody(&body);
        btBuoyancyAction action(&body, &buoyancyWorld);
        world.addAction(&action);
        REQUIRE(action.getShape()->getCapsuleRadius() == Approx(r).epsilon(1e-6));
        REQUIRE(action.getShape()->getCapsuleAxis() == axis);
        world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
        const btTransform& pose = body.getWorldTransform();
        const btVector3 o = pose.getOrigin(), a = pose.getBasis().getColumn(axis);
        const Eigen::Vector3d centre(o.x(), o.y(), o.z());
        const buoyancy::HydrostaticsResult expected = buoyancy::capsuleHydrostatics(
            centre, Eigen::Vector3d(a.x(), a.y(), a.z()), halfHeight, r, 0.0, 1000.0, 9.81, centre);
        const btBuoyancyResult& got = action.getLastResult();
        INFO("capsule along axis " << axis << ": " << got.submergedVolume << " m3 against " << expected.submerged_volume);
        CHECK(got.submergedVolume == Approx(expected.submerged_volume).epsilon(1e-6));
        const double tessellated = action.getShape()->getVolume() / (kPi * r * r * (2 * halfHeight + 4.0 / 3.0 * r));
        CHECK(tessellated < 1 - 1e-4);  // the mesh is short: the result above did not come from it
        world.removeAction(&action);
        world.removeRigidBody(&body);
    }
}

TEST_CASE("your own btRigidBody: a btBoxShape in flat water takes the exact box clip and moves as its mesh does",
          "[bullet][shapes]") {
    // The same tilted box dropped twice: once as a btBoxShape body (the action's constant-time box clip) and once
    // through an explicit 12-triangle mesh of the same box (the general exact-mesh path). Both are exact, so the two
    // trajectories may differ by rounding only.
    const btVector3 half(0.5f, 0.2f, 0.4f);
    btBoxShape box(half);
    using Run = FlatWaterWorld;
    auto start = [&](Run& run, btRigidBody*& body) {
        run.world.setGravity(btVector3(0, btScalar(-9.81), 0));
        const btScalar mass = btScalar(0.45 * 1000 * 8 * 0.5 * 0.2 * 0.4);
        btVector3 inertia;
        box.calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &box, inertia);
        info.m_startWorldTransform.setOrigin(btVector3(0.1f, 0.3f, -0.2f));
        info.m_startWorldTransform.setRotation(btQuaternion(btVector3(1, 0.3f, 0.5f).normalized(), btScalar(0.7)));
        body = new btRigidBody(info);
        body->setActivationState(DISABLE_DEACTIVATION);
        run.world.addRigidBody(body);
    };
    Run fast, general;
    btRigidBody* fastBody = nullptr;
    btRigidBody* generalBody = nullptr;
    start(fast, fastBody);
    start(general, generalBody);
    btBuoyancyAction fastAction(fastBody, &fast.buoyancyWorld);
    REQUIRE(fastAction.getShape()->isBox());
    CHECK(fastAction.getShape()->getBoxHalfExtents().isApprox(Eigen::Vector3d(0.5, 0.2, 0.4), 1e-6));
    btBuoyancyAction generalAction(generalBody, btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.8)),
                                   &general.buoyancyWorld);
    REQUIRE_FALSE(generalAction.getShape()->isBox());
    fast.world.addAction(&fastAction);
    general.world.addAction(&generalAction);
    double worst = 0, worstVolume = 0;
    for (int frame = 0; frame < 60 * 2; ++frame) {
        fast.world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        general.world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        worst = std::max(worst, double((fastBody->getCenterOfMassPosition() - generalBody->getCenterOfMassPosition()).length()));
        worstVolume = std::max(worstVolume, std::abs(fastAction.getLastResult().submergedVolume -
                                                     generalAction.getLastResult().submergedVolume));
    }
    INFO("largest position difference " << worst << " m, submerged volume difference " << worstVolume << " m3");
    // Float Bullet keeps 7 digits: 2 s of rounding apart stays far below a millimetre; a wrong clip would be metres or
    // centimetres off within the first second.
    CHECK(worst < 1e-4);
    CHECK(worstVolume < 1e-5);
    CHECK(fastAction.getLastResult().submergedVolume > 0.1);
    fast.world.removeAction(&fastAction);
    general.world.removeAction(&generalAction);
    fast.world.removeRigidBody(fastBody);
    general.world.removeRigidBody(generalBody);
    delete fastBody;
    delete generalBody;
}

TEST_CASE("setBodyMassFromShape: mass and inertia of boxes, spheres and capsules in closed form", "[bullet][shapes]") {
    FlatWaterWorld scene;
    btDiscreteDynamicsWorld& world = scene.world;
    btBuoyancyWorld& buoyancyWorld = scene.buoyancyWorld;
    const double rho = 600;
    auto bodyOf = [&](btCollisionShape& shape) {
        btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, &shape, btVector3(1, 1, 1));
        return std::make_unique<btRigidBody>(info);
    };
    SECTION("box") {
        btBoxShape box(btVector3(0.5f, 0.2f, 0.4f));
        auto body = bodyOf(box);
        btBuoyancyAction action(body.get(), &buoyancyWorld);
        const btBuoyancyMassResult r = action.setBodyMassFromShape(rho);
        const double a = 1.0, b = 0.4, c = 0.8, m = rho * a * b * c;
        CHECK(r.mass == Approx(m).epsilon(1e-6));
        CHECK(1.0 / double(body->getInvMass()) == Approx(m).epsilon(1e-6));
        CHECK(double(body->getLocalInertia().x()) == Approx(m * (b * b + c * c) / 12).epsilon(1e-5));
        CHECK(double(body->getLocalInertia().y()) == Approx(m * (a * a + c * c) / 12).epsilon(1e-5));
        CHECK(double(body->getLocalInertia().z()) == Approx(m * (a * a + b * b) / 12).epsilon(1e-5));
        CHECK(r.centroidOffset.length() < 1e-6);
        CHECK(r.productOfInertiaRatio < 1e-6);
    }
    SECTION("sphere") {
        btSphereShape sphere{btScalar(0.5)};
        auto body = bodyOf(sphere);
        btBuoyancyAction action(body.get(), &buoyancyWorld);
        action.setBodyMassFromShape(rho);
        const double m = rho * 4.0 / 3.0 * kPi * 0.125;
        CHECK(1.0 / double(body->getInvMass()) == Approx(m).epsilon(1e-6));
        for (int k = 0; k < 3; ++k) CHECK(double(body->getLocalInertia()[k]) == Approx(0.4 * m * 0.25).epsilon(1e-6));
    }
    SECTION("capsule along z") {
        const double r = 0.25, h = 1.0;  // radius, cylinder length
        btCapsuleShapeZ capsule{btScalar(r), btScalar(h)};
        auto body = bodyOf(capsule);
        btBuoyancyAction action(body.get(), &buoyancyWorld);
        action.setBodyMassFromShape(rho);
        // Cylinder plus two hemispheres, each hemisphere about its own centroid 3r/8 from its flat face:
        // (83/320) m_h r² across, then moved to the capsule's centre (parallel-axis theorem).
        const double mc = rho * kPi * r * r * h, ms = rho * 4.0 / 3.0 * kPi * r * r * r;
        const double axial = mc * r * r / 2 + 0.4 * ms * r * r;
        const double across = mc * (3 * r * r + h * h) / 12 +
                              2 * (83.0 / 320.0 * (ms / 2) * r * r + (ms / 2) * std::pow(h / 2 + 3 * r / 8, 2));
        // The capsule's solid in closed form, as its hydrostatics (not its tessellation, 0.1 % short by default).
        CHECK(1.0 / double(body->getInvMass()) == Approx(mc + ms).epsilon(1e-6));
        CHECK(double(body->getLocalInertia().z()) == Approx(axial).epsilon(1e-6));
        CHECK(double(body->getLocalInertia().x()) == Approx(across).epsilon(1e-6));
        CHECK(double(body->getLocalInertia().y()) == Approx(across).epsilon(1e-6));
    }
    SECTION("cone: the centroid off Bullet's origin is reported") {
        const double r = 0.4, h = 1.2;
        btConeShape cone{btScalar(r), btScalar(h)};  // along y, origin half-way up
        auto body = bodyOf(cone);
        btBuoyancyAction action(body.get(), &buoyancyWorld);
        const btBuoyancyMassResult res = action.setBodyMassFromShape(rho);
        CHECK(res.mass == Approx(rho * kPi * r * r * h / 3).epsilon(1e-3));
        // A cone's centroid lies a quarter of its height above its base, the base h/2 below Bullet's origin.
        CHECK(double(res.centroidOffset.y()) == Approx(-h / 4).epsilon(3e-3));
    }
    SECTION("bad density") {
        btBoxShape box(btVector3(0.5f, 0.2f, 0.4f));
        auto body = bodyOf(box);
        btBuoyancyAction action(body.get(), &buoyancyWorld);
        CHECK_THROWS_WITH(action.setBodyMassFromShape(0.0), Contains("density"));
        CHECK_THROWS_WITH(action.setBodyMassFromShape(std::nan("")), Contains("density"));
        CHECK(1.0 / double(body->getInvMass()) == Approx(1.0));  // unchanged
    }
}
