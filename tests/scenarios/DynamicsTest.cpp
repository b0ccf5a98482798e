// Dynamics against physical laws (design.md 5, 6): heave period, terminal velocity, energy,
// neutral buoyancy, symmetry, and the in-place mass change.
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

using namespace buoyancy_test;

namespace {
/// Velocity at the current pose for symplectic Euler: Bullet's stored velocity already holds this
/// substep's buoyancy kick J_b but not the next gravity kick; the mean of v_{n−1/2} = v − J_b/m and
/// v_{n+1/2} = v + g dt estimates v(x_n) to O(dt²).
btVector3 midVelocity(BulletTestWorld& w, double dt) {
    const btRigidBody* rb = w.rigid(0);
    const btBuoyancyResult& r = w.action(0).getLastResult();
    return rb->getLinearVelocity() +
           btScalar(0.5 * dt) * (rb->getGravity() - r.buoyancyForce * rb->getInvMass() - r.dragForce * rb->getInvMass());
}

btBuoyancySettings undamped() {
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    bs.dragCoefficient = 0;
    bs.linearDamping = 0;
    bs.radiationDamping = 0;
    bs.skinFriction = 0;
    bs.addedMass = false;
    return bs;
}
}  // namespace

TEST_CASE("heave period of a wall-sided box is 2 pi sqrt(m / (rho g A_wp))", "[bullet][dynamics]") {
    const double a = 2, c = 0.5, b = 2, s = 0.5;
    const btBuoyancySettings bs = undamped();
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(a, c, b), bs);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 1000 * s;
    const double yEq = c / 2 - s * c;
    w.add(shape, body, makePose(btVector3(0, btScalar(yEq - 0.05), 0)), bs);
    const double dt = 1.0 / 240.0;
    double prev = -0.05, tPrev = 0;
    std::vector<double> crossings;
    for (int k = 1; k <= 2400; ++k) {
        w.step(1, 1, dt);
        const double y = double(w.body(0).getMeshWorldTransform().getOrigin().y()) - yEq;
        if (prev < 0 && y >= 0) crossings.push_back(tPrev + dt * (-prev) / (y - prev));  // upward zero crossing
        prev = y;
        tPrev = k * dt;
    }
    REQUIRE(crossings.size() >= 5);
    const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
    const double m = w.body(0).getMass();
    const double theory = 2 * M_PI * std::sqrt(m / (1000.0 * 9.81 * a * b));
    std::printf("heave period %.5f s, theory %.5f s (%.3f%%)\n", period, theory, 100 * (period / theory - 1));
    CHECK(std::abs(period / theory - 1) < 0.03);
}

TEST_CASE("sinking sphere reaches the quadratic-drag terminal velocity", "[bullet][dynamics]") {
    const double R = 0.1, rhoB = 2000;
    const auto mesh = buoyancy::makeSphereMesh(R, 64, 32);
    btBuoyancySettings bs = undamped();
    bs.dragCoefficient = 1.0;
    bs.addedMass = true;  // does not change the terminal velocity
    auto shape = btBuoyancyShape::create(mesh, bs);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = rhoB;
    w.add(shape, body, makePose(btVector3(0, -50, 0)), bs);
    w.run(3.0);
    const double v = -double(midVelocity(w, 1.0 / 240.0).y());
    // Oracle: v_t = sqrt(2 |m − ρV| g / (ρ C_d A_proj)), V the mesh's exact volume, A_proj its silhouette
    // seen along the pole axis: the 64-gon equator of radius R.
    const double V = oracleDryMoments(mesh.vertices, mesh.triangles).volume;
    const double Aproj = 0.5 * 64 * R * R * std::sin(2 * M_PI / 64);
    const double m = w.body(0).getMass();
    const double vt = std::sqrt(2 * std::abs(m - 1000 * V) * 9.81 / (1000 * 1.0 * Aproj));
    std::printf("terminal velocity %.5f m/s, theory %.5f m/s (%.3f%%)\n", v, vt, 100 * (v / vt - 1));
    CHECK(std::abs(v / vt - 1) < 0.03);
}

TEST_CASE("energy is conserved with drag off", "[bullet][dynamics]") {
    const double a = 2, c = 1, b = 2, s = 0.5, rho = 1000, g = 9.81;
    const btBuoyancySettings bs = undamped();
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(a, c, b), bs);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = rho * s;
    const double yEq = c / 2 - s * c;
    w.add(shape, body, makePose(btVector3(0, btScalar(yEq - 0.1), 0)), bs);
    const double m = w.body(0).getMass();
    // Mechanical energy: kinetic + gravity + buoyancy potential ρ g A d²/2 (wall-sided, 0 < d < c).
    auto energy = [&]() {
        const btRigidBody* rb = w.rigid(0);
        const double y = double(rb->getCenterOfMassPosition().y());
        const double d = c / 2 - y;
        const double v2 = double(midVelocity(w, 1.0 / 1000.0).length2());
        const btVector3 om = rb->getAngularVelocity();
        const btVector3 Iw = rb->getInvInertiaTensorWorld().inverse() * om;
        return 0.5 * m * v2 + 0.5 * double(om.dot(Iw)) + m * g * y + 0.5 * rho * g * a * b * d * d;
    };
    const double dRest = s * c;
    const double eRest = m * g * (c / 2 - dRest) + 0.5 * rho * g * a * b * dRest * dRest;
    const double e0 = energy() - eRest;
    double worst = 0;
    for (int k = 0; k < 60000; ++k) {
        w.step(1, 1, 1.0 / 1000.0);
        worst = std::max(worst, std::abs(energy() - eRest - e0));
    }
    std::printf("energy above rest %.6f J, worst drift over 60 s %.4f%%\n", e0, 100 * worst / e0);
    CHECK(worst < 0.01 * e0);
}

TEST_CASE("a neutrally buoyant body stays at its depth", "[bullet][dynamics]") {
    btBuoyancySettings bs;
    bs.method = GENERATE(btBuoyancyMethod::ExactMesh, btBuoyancyMethod::ExactCoverage);
    auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.3, 48, 24), bs);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 1000;
    w.add(shape, body, makePose(btVector3(0, -2, 0)), bs);
    w.run(20.0);
    const btVector3 p = w.body(0).getMeshWorldTransform().getOrigin();
    std::printf("neutral %s: displacement after 20 s %.3g m\n", btBuoyancyMethodName(shape->getMethod()),
                double((p - btVector3(0, -2, 0)).length()));
    CHECK(double((p - btVector3(0, -2, 0)).length()) < 0.01);
}

TEST_CASE("a symmetric body in calm water neither drifts nor spins", "[bullet][dynamics][slow]") {
    btBuoyancySettings bs;
    bs.method = GENERATE(btBuoyancyMethod::ExactMesh, btBuoyancyMethod::ExactCoverage);
    auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.5, 48, 24), bs);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 500;
    w.add(shape, body, makePose(btVector3(0, 0.3, 0)), bs);
    w.run(20.0);
    const btVector3 p = w.body(0).getMeshWorldTransform().getOrigin();
    const double drift = std::hypot(double(p.x()), double(p.z()));
    const double spin = double(w.rigid(0)->getAngularVelocity().length());
    std::printf("symmetric %s: drift %.3g m, spin %.3g rad/s\n", btBuoyancyMethodName(shape->getMethod()), drift, spin);
    // The texture samples of a UV sphere are not exactly symmetric: exact-coverage drifts 0.83 mm in these 20 s with
    // an exact evaluation every substep, 1.03 mm at the default temporal level of detail (measured); exact-mesh
    // clips the symmetric mesh itself (1e-14 m). The sphere still heaves after 20 s (only drag damps it, and it
    // is kept awake until it is at rest), and exact-coverage's sample asymmetry leaves a torque of about 4e-5 W R
    // that turns it at up to 1.4e-3 rad/s meanwhile (measured); exact-mesh stays below 1e-5 rad/s.
    CHECK(drift < (bs.method == btBuoyancyMethod::ExactMesh ? 1e-6 : 2e-3));
    CHECK(spin < (bs.method == btBuoyancyMethod::ExactMesh ? 1e-5 : 3e-3));
}

TEST_CASE("updateMassProperties moves the COM without moving the mesh", "[bullet][massprops]") {
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(2, 1, 1), btBuoyancySettings());
    btBuoyantBodySettings settings;
    settings.density = 500;
    btBuoyantBody body(shape, settings, makePose(btVector3(1, 2, 3), btVector3(1, 1, 0), 30));
    btRigidBody* rb = body.getRigidBody();
    rb->setLinearVelocity(btVector3(0.5, -1, 2));
    rb->setAngularVelocity(btVector3(0.3, 0.7, -0.2));
    const btTransform before = body.getMeshWorldTransform();
    const double m = body.getMass();
    // Velocity of a mesh point (its corner) before: v + ω × (p − c).
    const btVector3 corner = before * btVector3(1, 0.5, 0.5);
    const btVector3 vCornerBefore =
        rb->getLinearVelocity() + rb->getAngularVelocity().cross(corner - rb->getCenterOfMassPosition());

    // Same mass, COM moved to (0.5, -0.2, 0.1) in the mesh frame, some new (non-diagonal) inertia.
    Eigen::Matrix3d I;
    I << 60, 5, 0, 5, 120, -3, 0, -3, 110;
    body.updateMassProperties(m, Eigen::Vector3d(0.5, -0.2, 0.1), I);
    const btTransform after = body.getMeshWorldTransform();
    const btVector3 vCornerAfter =
        rb->getLinearVelocity() + rb->getAngularVelocity().cross(corner - rb->getCenterOfMassPosition());
    // The mesh does not jump.
    CHECK(double((after.getOrigin() - before.getOrigin()).length()) < 1e-5);
    CHECK(double((after * btVector3(1, 0.5, 0.5) - corner).length()) < 1e-5);
    // The rigid velocity field is unchanged, so with ω = 0 linear momentum is conserved exactly.
    CHECK(double((vCornerAfter - vCornerBefore).length()) < 1e-5);
    // The COM is where we put it.
    CHECK(double((rb->getCenterOfMassPosition() - before * btVector3(0.5, -0.2, 0.1)).length()) < 1e-5);
    CHECK(1.0 / double(rb->getInvMass()) == Approx(m).epsilon(1e-6));

    rb->setAngularVelocity(btVector3(0, 0, 0));
    const btVector3 p0 = rb->getLinearVelocity() * btScalar(m);
    body.updateMassProperties(m, Eigen::Vector3d(-0.3, 0.1, 0), I);
    CHECK(double((rb->getLinearVelocity() * btScalar(m) - p0).length()) < 1e-4);
    // Bad input changes nothing.
    CHECK_THROWS_AS(body.updateMassProperties(0.0, Eigen::Vector3d::Zero(), I), std::invalid_argument);
}
