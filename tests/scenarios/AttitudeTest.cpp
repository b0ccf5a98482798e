// Attitudes against metacentric theory (design.md 5): the long square log (flat / corner-down ranges),
// a ballasted ball that rights itself and a uniform ball that is neutral in roll (paper Fig. 14).
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace buoyancy_test;

namespace {

constexpr double kDeg = 180.0 / M_PI;

/// Roll of a log whose long axis is the body x axis: angle of the body y axis about world x, folded into
/// (−45°, 45°] (a square section repeats every 90°). 0 = a face is down, ±45 = a corner is down.
double foldedRoll(const btTransform& t) {
    const btMatrix3x3& R = t.getBasis();
    // Body y axis in world: column 1. Its angle from world y in the y-z plane.
    double phi = std::atan2(double(R[2][1]), double(R[1][1])) * kDeg;
    phi = std::fmod(phi, 90.0);
    if (phi < 0) phi += 90.0;
    return phi > 45.0 ? phi - 90.0 : phi;
}

/// Angle between the body y axis and world y, degrees.
double bodyYTilt(const btTransform& t) {
    return std::acos(std::clamp(double(t.getBasis()[1][1]), -1.0, 1.0)) * kDeg;
}

btBuoyancySettings exactMesh() {
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    return bs;
}

}  // namespace

TEST_CASE("long square log: flat at s = 0.1, corner-down at s = 0.5", "[bullet][attitude]") {
    // Oracle (design.md 5, metacentric height of a square prism): face-down stable for
    // s < (3 − √3)/6 ≈ 0.2113 or s > 0.7887; corner-down stable for 9/32 < s < 23/32.
    const double L = 4, c = 0.5;
    const auto mesh = buoyancy::makeBoxMesh(L, c, c);
    const btBuoyancySettings bs = exactMesh();
    auto shape = btBuoyancyShape::create(mesh, bs);
    struct Case {
        double s, startRoll, expectRoll;
    };
    for (const Case k : {Case{0.1, 20.0, 0.0}, Case{0.5, 8.0, 45.0}, Case{0.9, 20.0, 0.0}}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000 * k.s;
        w.add(shape, body, makePose(btVector3(0, btScalar(c / 2 - k.s * c), 0), btVector3(1, 0, 0), k.startRoll), bs);
        w.run(30.0);
        const btTransform t = w.body(0).getMeshWorldTransform();
        const double roll = foldedRoll(t);
        // Distance to the expected attitude on the 90° circle.
        const double err = std::abs(std::abs(roll) - k.expectRoll);
        // The long axis stays horizontal.
        const double axisTilt = std::asin(std::min(1.0, std::abs(double(t.getBasis()[1][0])))) * kDeg;
        // Height oracle: flat at draft s c (centre at c/2 − s c); corner-down at s = 0.5 the centre is at the
        // water line by symmetry of the square about its diagonal.
        const double y = double(t.getOrigin().y());
        const double yTheory = k.expectRoll == 0.0 ? c / 2 - k.s * c : 0.0;
        std::printf("log s=%.2f: start roll %.1f deg, final roll %.2f deg (theory %.0f), axis tilt %.3f deg, "
                    "centre y %.5f (theory %.5f)\n",
                    k.s, k.startRoll, roll, k.expectRoll, axisTilt, y, yTheory);
        CHECK(err < 2.0);
        CHECK(axisTilt < 1.0);
        CHECK(std::abs(y - yTheory) < 0.005 * c);
    }
}

TEST_CASE("a ball with a low centre of mass rights itself", "[bullet][attitude]") {
    // A floating sphere's buoyancy always acts through its centre O (its metacentre), so the righting
    // moment is W·OG·sin θ: stable upright iff the COM G lies below O. Oracle for the small-roll period
    // (drag off; buoyancy is vertical so G does not move sideways): T = 2π sqrt(I_G / (W·OG)).
    const double R = 0.5, rhoB = 300, mb = 60, yb = -0.35;
    const auto mesh = buoyancy::makeSphereMesh(R, 48, 24);
    const OracleMoments dry = oracleDryMoments(mesh.vertices, mesh.triangles);
    const double M = rhoB * dry.volume, W = (M + mb) * 9.81;
    const double OG = mb * -yb / (M + mb);
    // I_G about a horizontal axis: the mesh's own (oracle) inertia + parallel-axis terms of both masses.
    const double IG = rhoB * dry.inertiaAboutCentroid()(2, 2) + M * OG * OG + mb * (-yb - OG) * (-yb - OG);
    const double Ttheory = 2 * M_PI * std::sqrt(IG / (W * OG));
    btBuoyantBodySettings body;
    body.density = rhoB;
    body.ballast.push_back({Eigen::Vector3d(0, yb, 0), mb});

    SECTION("small-roll period without drag") {
        btBuoyancySettings bs = exactMesh();
        bs.dragCoefficient = 0;
        bs.linearDamping = 0;
        bs.radiationDamping = 0;
        bs.addedMass = false;
        auto shape = btBuoyancyShape::create(mesh, bs);
        BulletTestWorld w;
        // Start at its draft (oracle level for the upright pose) with a 5° roll.
        const double yEq = -oracleEquilibriumLevel(mesh.vertices, mesh.triangles, makePose(btVector3(0, 0, 0)),
                                                   (M + mb) / 1000.0);
        w.add(shape, body, makePose(btVector3(0, btScalar(yEq), 0), btVector3(0, 0, 1), 5), bs);
        const double dt = 1.0 / 240.0;
        std::vector<double> crossings;
        double prev = 0, tPrev = 0, maxRoll = 0;
        for (int k = 1; k <= 240 * 12; ++k) {
            w.step(1, 1, dt);
            const btMatrix3x3 B = w.body(0).getMeshWorldTransform().getBasis();
            const double roll = std::atan2(-double(B[0][1]), double(B[1][1])) * kDeg;  // about z
            maxRoll = std::max(maxRoll, std::abs(roll));
            if (k > 1 && prev > 0 && roll <= 0) crossings.push_back(tPrev + dt * prev / (prev - roll));
            prev = roll;
            tPrev = k * dt;
        }
        REQUIRE(crossings.size() >= 3);
        const double T = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
        std::printf("ballasted ball: roll period %.4f s, theory 2 pi sqrt(I_G/(W OG)) = %.4f s (%.2f%%), max roll %.2f deg\n",
                    T, Ttheory, 100 * (T / Ttheory - 1), maxRoll);
        CHECK(std::abs(T / Ttheory - 1) < 0.03);
        CHECK(maxRoll < 5.2);  // no energy gain
    }
    SECTION("rights itself from 60 deg with the default drag") {
        const btBuoyancySettings bs = exactMesh();
        auto shape = btBuoyancyShape::create(mesh, bs);
        BulletTestWorld w;
        w.add(shape, body, makePose(btVector3(0, 0, 0), btVector3(0, 0, 1), 60), bs);
        const double start = bodyYTilt(w.body(0).getMeshWorldTransform());
        w.run(28.0);
        // Amplitude over the last 2 s (one roll period) and the mean signed roll (the attitude it oscillates about).
        double amp = 0, mean = 0;
        const int frames = 120;
        for (int f = 0; f < frames; ++f) {
            w.step(1, 4, 1.0 / 240);
            const btMatrix3x3 B = w.body(0).getMeshWorldTransform().getBasis();
            const double roll = std::atan2(-double(B[0][1]), double(B[1][1])) * kDeg;
            amp = std::max(amp, std::abs(roll));
            mean += roll / frames;
        }
        std::printf("ballasted ball: tilt %.1f deg -> roll amplitude %.2f deg, mean roll %.2f deg over 28-30 s\n",
                    start, amp, mean);
        CHECK(start == Approx(60.0).margin(1e-3));
        CHECK(amp < 15.0);
        CHECK(std::abs(mean) < 3.0);
    }
}

TEST_CASE("a uniform ball is neutral in roll (paper Fig. 14): no righting moment", "[bullet][attitude]") {
    // Uniform sphere: COM at the centre, buoyancy through the centre: zero pressure torque at any tilt. A
    // wrong centre of buoyancy (e.g. the mesh sliced unrotated, design.md 6 item 4) would right it like
    // the ballasted ball. Rotation of a sphere is (almost) undamped, so the faceted mesh's tiny torques let
    // it wander; what must not happen is a systematic return to its starting ("upright") attitude.
    const double R = 0.5;
    const btBuoyancySettings bs = exactMesh();
    auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(R, 48, 24), bs);
    for (double start : {60.0, 120.0}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 500;
        w.add(shape, body, makePose(btVector3(0, 0.02, 0), btVector3(0, 0, 1), start), bs);
        const double WR = w.body(0).getMass() * 9.81 * R;
        double minTilt = start, maxTorque = 0;
        for (int k = 0; k < 20 * 60; ++k) {
            w.step(1, 4, 1.0 / 240);
            minTilt = std::min(minTilt, bodyYTilt(w.body(0).getMeshWorldTransform()));
            maxTorque = std::max(maxTorque, double(w.action(0).getLastResult().buoyancyTorque.length()));
        }
        const double tilt = bodyYTilt(w.body(0).getMeshWorldTransform());
        std::printf("uniform ball: tilt %.1f deg -> %.2f deg after 20 s (min %.2f), max pressure torque %.3g W R\n",
                    start, tilt, minTilt, maxTorque / WR);
        CHECK(maxTorque < 0.01 * WR);
        CHECK(minTilt > 20.0);
    }
}
