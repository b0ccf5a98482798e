// Equilibrium drafts and attitudes against the analytic / exact-polyhedral oracles (design.md 5).
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

using namespace buoyancy_test;

namespace {

/// Settle body i for `seconds` and average its mesh-frame height over the last `avgSeconds` (the mean of a
/// decaying oscillation is its equilibrium): Track::meanMeshY, and the final transform Track::last.
Track settle(BulletTestWorld& w, std::size_t i, double seconds, double avgSeconds, int substeps = 4) {
    return runTracked(w, seconds, substeps, 1.0 / 240.0, i, -1e300, -1e300, avgSeconds);
}

/// Error of the equilibrium: the oracle's water level for the settled pose (mesh displacing m/ρ_w at the
/// mean height) minus the real level 0, m.
double drafError(const buoyancy::TriangleMesh& mesh, const btTransform& last, double meanY, double mass) {
    btTransform pose = last;
    pose.getOrigin().setY(btScalar(meanY));
    return oracleEquilibriumLevel(mesh.vertices, mesh.triangles, pose, mass / 1000.0);
}

}  // namespace

TEST_CASE("plank settles at the analytic draft d = s c", "[bullet][equilibrium][slow]") {
    const double a = 2.0, c = 0.4, b = 1.0;
    const auto mesh = buoyancy::makeBoxMesh(a, c, b);
    btBuoyancySettings bs;
    bs.method = GENERATE(btBuoyancyMethod::ExactMesh, btBuoyancyMethod::ExactCoverage);
    auto shape = btBuoyancyShape::create(mesh, bs);
    for (double s : {0.05, 0.25, 0.5, 0.75, 0.95}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000.0 * s;
        // Released 5 cm above its analytic equilibrium.
        w.add(shape, body, makePose(btVector3(0, btScalar(c / 2 - s * c + 0.05), 0)), bs);
        const Track st = settle(w, 0, 10.0, 3.0);
        const double analyticY = c / 2 - s * c;  // box centre when the draft is s·c
        std::printf("plank %-14s s=%.2f  centre y %.6f  analytic %.6f  error %.3f%% of height  tilt %.3f deg\n",
                    btBuoyancyMethodName(shape->getMethod()), s, st.meanMeshY, analyticY,
                    100 * std::abs(st.meanMeshY - analyticY) / c, tiltDegrees(st.last));
        CHECK(std::abs(st.meanMeshY - analyticY) < 0.005 * c);
        CHECK(tiltDegrees(st.last) < 1.0);
    }
}

TEST_CASE("sphere settles at the draft of its own mesh volume", "[bullet][equilibrium][slow]") {
    const double R = 0.5;
    const auto mesh = buoyancy::makeSphereMesh(R, 64, 32);
    btBuoyancySettings bs;
    bs.method = GENERATE(btBuoyancyMethod::ExactMesh, btBuoyancyMethod::ExactCoverage);
    auto shape = btBuoyancyShape::create(mesh, bs);
    const double Vmesh = oracleDryMoments(mesh.vertices, mesh.triangles).volume;
    for (double s : {0.05, 0.3, 0.5, 0.7, 0.95}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000.0 * s;
        w.add(shape, body, makePose(btVector3(0, btScalar(R - 2 * R * s + 0.05), 0)), bs);
        const Track st = settle(w, 0, 10.0, 3.0);
        const double mass = w.body(0).getMass();
        const double err = drafError(mesh, st.last, st.meanMeshY, mass);
        // Analytic sphere of the same volume, for the report: cap volume π d²(3R − d)/3 = s V.
        const double Re = std::cbrt(3 * Vmesh / (4 * M_PI));
        double lo = 0, hi = 2 * Re;
        for (int it = 0; it < 80; ++it) {
            const double d = 0.5 * (lo + hi);
            (sphereCapVolume(Re, d) < s * Vmesh ? lo : hi) = d;
        }
        const double analyticY = Re - 0.5 * (lo + hi);
        std::printf("sphere %-14s s=%.2f  centre y %.6f  analytic(R_eq) %.6f  oracle level error %.3f%% of height\n",
                    btBuoyancyMethodName(shape->getMethod()), s, st.meanMeshY, analyticY, 100 * std::abs(err) / (2 * R));
        CHECK(std::abs(err) < 0.005 * 2 * R);
        CHECK(std::abs(st.meanMeshY - analyticY) < 0.005 * 2 * R);
    }
}

TEST_CASE("horizontal cylinder settles at the draft of its own mesh volume", "[bullet][equilibrium]") {
    const double R = 0.3, L = 2.0;
    const auto mesh = buoyancy::makeCylinderMesh(R, L, 64);
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    auto shape = btBuoyancyShape::create(mesh, bs);
    for (double s : {0.1, 0.5, 0.9}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000.0 * s;
        w.add(shape, body, makePose(btVector3(0, btScalar(R - 2 * R * s + 0.05), 0), btVector3(0, 0, 1), 90), bs);
        const Track st = settle(w, 0, 10.0, 3.0);
        const double err = drafError(mesh, st.last, st.meanMeshY, w.body(0).getMass());
        std::printf("cylinder s=%.2f  centre y %.6f  oracle level error %.3f%% of height\n", s, st.meanMeshY,
                    100 * std::abs(err) / (2 * R));
        CHECK(std::abs(err) < 0.005 * 2 * R);
        // The axis stays horizontal.
        CHECK(std::abs(double(st.last.getBasis()[1][1])) < 0.02);
    }
}

TEST_CASE("draft does not depend on the substeps per frame", "[bullet][equilibrium]") {
    const auto mesh = buoyancy::makeBoxMesh(2.0, 0.4, 1.0);
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    auto shape = btBuoyancyShape::create(mesh, bs);
    std::vector<double> ys, finals;
    for (int n : {1, 4, 8}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 600;
        w.add(shape, body, makePose(btVector3(0, 0.3, 0), btVector3(1, 0, 1), 10), bs);
        // 8 s in frames of n substeps of 1/240 s (a multiple of 8 substeps), then the mean over 2 s.
        w.step(1920 / n, n, 1.0 / 240.0);
        double mean = 0;
        for (int f = 0; f < 480 / n; ++f) {
            w.step(1, n, 1.0 / 240.0);
            mean += double(w.body(0).getMeshWorldTransform().getOrigin().y());
        }
        ys.push_back(mean / (480 / n));
        finals.push_back(double(w.body(0).getMeshWorldTransform().getOrigin().y()));
        std::printf("substeps %d: final centre y %.9f, mean of the last 2 s %.9f (analytic %.9f)\n", n,
                    double(w.body(0).getMeshWorldTransform().getOrigin().y()), ys.back(), 0.2 - 0.6 * 0.4);
    }
    // Impulses per substep: the same substeps give the same motion whatever the frame split.
    CHECK(finals[1] == finals[0]);
    CHECK(finals[2] == finals[0]);
    CHECK(std::abs(ys[0] - (0.2 - 0.6 * 0.4)) < 0.005 * 0.4);
}

TEST_CASE("cube face-down is stable at s = 0.1 and 0.9, unstable at 0.5", "[bullet][attitude]") {
    const auto mesh = buoyancy::makeBoxMesh(1, 1, 1);
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    auto shape = btBuoyancyShape::create(mesh, bs);
    for (double s : {0.1, 0.5, 0.9}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000 * s;
        // Start at the analytic draft with a 5° heel about a horizontal axis.
        w.add(shape, body, makePose(btVector3(0, btScalar(0.5 - s), 0), btVector3(1, 0, 0.3), 5), bs);
        w.run(25.0);
        const double tilt = tiltDegrees(w.body(0).getMeshWorldTransform());
        std::printf("cube s=%.2f: tilt after 25 s %.2f deg (theory: %s)\n", s, tilt,
                    (s < 0.2113 || s > 0.7887) ? "face-down stable" : "face-down unstable");
        if (s == 0.5) CHECK(tilt > 20.0);
        else CHECK(tilt < 1.0);
    }
}
