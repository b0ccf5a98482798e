// btBuoyancyCheckBody: it must catch every broken invariant (each test below breaks one on
// purpose and expects the check to name it), and the bodies btBuoyantBody builds must pass it — mass > 0
// and positive-definite inertia — even for degenerate mass distributions (ballast on a line, a thin rod,
// a shell).

#include "reliability/ReliabilityHelpers.h"

#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <catch2/catch.hpp>

#include <limits>

using namespace reliability_test;
using Catch::Matchers::StartsWith;

namespace {

std::shared_ptr<const btBuoyancyShape> shape(const buoyancy::TriangleMesh& m) {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactMesh;
    return btBuoyancyShape::create(m, s);
}

}  // namespace

TEST_CASE("invariants: the check names each broken invariant", "[reliability][invariants]") {
    btBuoyantBody b(shape(buoyancy::makeBoxMesh(1, 2, 3)), btBuoyantBodySettings(), makePose(btVector3(1, 2, 3)));
    btRigidBody& r = *b.getRigidBody();
    REQUIRE(btBuoyancyCheckBody(r).empty());
    ScopedFpTrapsOff nanOnPurpose;
    const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
    const btScalar inf = std::numeric_limits<btScalar>::infinity();
    SECTION("position") {
        btTransform t = r.getWorldTransform();
        t.getOrigin().setZ(nan);
        r.setWorldTransform(t);
        CHECK_THAT(btBuoyancyCheckBody(r), StartsWith("position not finite"));
    }
    SECTION("rotation") {
        btTransform t = r.getWorldTransform();
        t.getBasis()[2][2] = btScalar(1.5);
        r.setWorldTransform(t);
        CHECK_THAT(btBuoyancyCheckBody(r), StartsWith("rotation not orthonormal"));
    }
    SECTION("velocities") {
        r.setLinearVelocity(btVector3(0, inf, 0));
        CHECK_THAT(btBuoyancyCheckBody(r), StartsWith("linear velocity not finite"));
        r.setLinearVelocity(btVector3(0, 0, 0));
        r.setAngularVelocity(btVector3(nan, 0, 0));
        CHECK_THAT(btBuoyancyCheckBody(r), StartsWith("angular velocity not finite"));
    }
    SECTION("inertia") {
        r.setMassProps(10, btVector3(1, 0, 1));  // Bullet turns a zero moment into a zero inverse moment
        r.updateInertiaTensor();
        CHECK_THAT(btBuoyancyCheckBody(r), StartsWith("local inverse inertia not > 0"));
        CHECK(btBuoyancyCheckBody(r, false).empty());  // allowed for users' rotation-locked bodies
        r.setMassProps(10, btVector3(1, -1, 1));
        r.updateInertiaTensor();
        CHECK_THAT(btBuoyancyCheckBody(r, false), StartsWith("local inverse inertia not finite and >= 0"));
    }
}

TEST_CASE("invariants: built bodies have mass > 0 and positive-definite inertia", "[reliability][invariants]") {
    const buoyancy::TriangleMesh rod = buoyancy::makeBoxMesh(0.01, 0.01, 10);
    const buoyancy::TriangleMesh disc = buoyancy::makeCylinderMesh(2, 0.002, 32);
    for (const buoyancy::TriangleMesh* m : {&rod, &disc}) {
        for (btBuoyantMassModel model : {btBuoyantMassModel::Solid, btBuoyantMassModel::Shell}) {
            btBuoyantBodySettings s;
            s.massModel = model;
            s.density = 7850;
            btBuoyantBody b(shape(*m), s, makePose(btVector3(0, 0, 0), btVector3(1, 1, 0), 33));
            CHECK(b.getMass() > 0);
            CHECK(btBuoyancyCheckBody(*b.getRigidBody()).empty());
        }
    }
    // Ballast far along one line dominates: nearly a dumbbell, one principal moment tiny.
    btBuoyantBodySettings s;
    s.density = 1;
    s.ballast = {{Eigen::Vector3d(0, 0, -50), 1e6}, {Eigen::Vector3d(0, 0, 50), 1e6}};
    btBuoyantBody b(shape(rod), s, makePose(btVector3(0, 0, 0)));
    CHECK(btBuoyancyCheckBody(*b.getRigidBody()).empty());
}
