// The records of the temporal level of detail (temporal/HydrostaticsHistory.h): the extrapolation is exact on
// cubics, refuses unevenly spaced records, clamps magnitudes extrapolated below zero; the pose and velocity
// deviations; the hydrostatic stiffness correction against exact evaluations at a nearby pose. The controller in
// Bullet worlds: tests/bullet/TemporalLodTest.cpp.
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/temporal/HydrostaticsHistory.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

using namespace buoyancy;

namespace {

/// A snapshot whose every number is the cubic q(t) = c0 + c1 t + c2 t² + c3 t³, with coefficients varied per field.
HydrostaticsSnapshot cubicSnapshot(double t) {
    auto q = [t](double k) {
        return (1.0 + k) + (0.5 - 0.1 * k) * t + (0.02 * k - 0.3) * t * t + (0.1 - 0.01 * k) * t * t * t;
    };
    HydrostaticsSnapshot s;
    s.hydrostatics.force = Eigen::Vector3d(q(1), q(2), q(3));
    s.hydrostatics.torque = Eigen::Vector3d(q(4), q(5), q(6));
    s.hydrostatics.centre_of_buoyancy = Eigen::Vector3d(q(7), q(8), q(9));
    s.hydrostatics.submerged_volume = 10 + q(10);
    s.hydrostatics.waterline_area = 10 + q(11);
    s.hydrostatics.wetted_area = 10 + q(12);
    s.com = Eigen::Vector3d(q(13), q(14), q(15));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s.rotation(i, j) = q(16 + 3 * i + j);
    s.dragForce = Eigen::Vector3d(q(25), q(26), q(27));
    s.dragTorque = Eigen::Vector3d(q(28), q(29), q(30));
    s.linearVelocity = Eigen::Vector3d(q(31), q(32), q(33));
    s.angularVelocity = Eigen::Vector3d(q(34), q(35), q(36));
    WaterplaneMoments& w = s.hydrostatics.waterplane;
    w.x = q(37);
    w.z = q(38);
    w.xx = 10 + q(39);
    w.xz = q(40);
    w.zz = 10 + q(41);
    w.valid = true;
    return s;
}

double largestDifference(const HydrostaticsSnapshot& a, const HydrostaticsSnapshot& b) {
    double d = 0;
    auto v = [&d](const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
        d = std::max(d, (x - y).cwiseAbs().maxCoeff());
    };
    v(a.hydrostatics.force, b.hydrostatics.force);
    v(a.hydrostatics.torque, b.hydrostatics.torque);
    v(a.hydrostatics.centre_of_buoyancy, b.hydrostatics.centre_of_buoyancy);
    d = std::max({d, std::abs(a.hydrostatics.submerged_volume - b.hydrostatics.submerged_volume),
                  std::abs(a.hydrostatics.waterline_area - b.hydrostatics.waterline_area),
                  std::abs(a.hydrostatics.wetted_area - b.hydrostatics.wetted_area),
                  (a.rotation - b.rotation).cwiseAbs().maxCoeff()});
    v(a.com, b.com);
    v(a.dragForce, b.dragForce);
    v(a.dragTorque, b.dragTorque);
    v(a.linearVelocity, b.linearVelocity);
    v(a.angularVelocity, b.angularVelocity);
    const WaterplaneMoments &p = a.hydrostatics.waterplane, &q = b.hydrostatics.waterplane;
    d = std::max({d, std::abs(p.x - q.x), std::abs(p.z - q.z), std::abs(p.xx - q.xx), std::abs(p.xz - q.xz),
                  std::abs(p.zz - q.zz)});
    return d;
}

}  // namespace

TEST_CASE("hydrostatics history: the extrapolation reproduces cubics in time", "[temporal]") {
    const int k = 4;
    HydrostaticsHistory history;
    const double dt = 0.01;  // substep, s
    CHECK_FALSE(history.canPredict(17, 17 * dt, k));
    for (std::uint64_t n : {4u, 8u, 12u}) history.push(n, double(n) * dt, cubicSnapshot(double(n) * dt));
    CHECK_FALSE(history.canPredict(13, 13 * dt, k));  // three records: not yet
    history.push(16, 16 * dt, cubicSnapshot(16 * dt));
    REQUIRE(history.size() == HydrostaticsHistory::kRecords);
    for (std::uint64_t n = 17; n <= 20; ++n) {
        CHECK(history.canPredict(n, double(n) * dt, k) == (n < 20));
        CHECK(history.canCheck(n, double(n) * dt, k) == (n == 20));
        const HydrostaticsSnapshot p = history.extrapolate(n, k);
        const double d = largestDifference(p, cubicSnapshot(double(n) * dt));
        CHECK(d < 1e-12);
        CHECK(p.hydrostatics.waterplane.valid);
    }
    CHECK(history.volume(0, k) == Approx(cubicSnapshot(16 * dt).hydrostatics.submerged_volume));
    CHECK(history.volume(1, k) == Approx(cubicSnapshot(12 * dt).hydrostatics.submerged_volume));
    CHECK(history.volume(1, 2 * k) == 0.0);  // not spaced by 8
    CHECK_FALSE(history.canPredict(16, 16 * dt, k));   // at the newest record itself
    CHECK_FALSE(history.canPredict(17, 17 * dt, 3));   // records not 3 apart
    CHECK_FALSE(history.canPredict(17, 16.5 * dt, k)); // the substep length changed since the records
    // One record without waterplane moments (a sampled evaluation): the extrapolation has none either.
    HydrostaticsSnapshot plain = cubicSnapshot(20 * dt);
    plain.hydrostatics.waterplane.valid = false;
    history.push(20, 20 * dt, plain);
    CHECK_FALSE(history.extrapolate(21, k).hydrostatics.waterplane.valid);
    // A missed evaluation (records 4, 8, 12, 20) breaks the equal spacing: no prediction.
    HydrostaticsHistory gap;
    for (std::uint64_t n : {4u, 8u, 12u, 20u}) gap.push(n, double(n) * dt, cubicSnapshot(double(n)));
    CHECK_FALSE(gap.canPredict(21, 21 * dt, k));
    CHECK_FALSE(gap.canCheck(24, 24 * dt, k));
    // Records 4 substeps apart but not equally in time (the substep length changed between them).
    HydrostaticsHistory uneven;
    uneven.push(4, 0.04, cubicSnapshot(0.04));
    uneven.push(8, 0.08, cubicSnapshot(0.08));
    uneven.push(12, 0.12, cubicSnapshot(0.12));
    uneven.push(16, 0.18, cubicSnapshot(0.18));
    CHECK_FALSE(uneven.canPredict(17, 0.195, k));
    gap.clear();
    CHECK(gap.size() == 0);
}

TEST_CASE("hydrostatics history: volumes and areas extrapolated below zero are clamped, deviations", "[temporal]") {
    HydrostaticsHistory history;
    for (int n = 0; n < 4; ++n) {
        HydrostaticsSnapshot s;
        s.hydrostatics.submerged_volume = 0.3 - 0.1 * n;  // 0.3, 0.2, 0.1, 0.0 → −0.1 next
        s.hydrostatics.waterline_area = 0.3 - 0.1 * n;
        s.hydrostatics.wetted_area = 0.3 - 0.1 * n;
        s.hydrostatics.waterplane.xx = 0.3 - 0.1 * n;
        s.hydrostatics.waterplane.zz = 0.3 - 0.1 * n;
        history.push(std::uint64_t(2 * n), double(2 * n), s);
    }
    const HydrostaticsSnapshot p = history.extrapolate(8, 2);
    CHECK(p.hydrostatics.submerged_volume == 0.0);
    CHECK(p.hydrostatics.waterline_area == 0.0);
    CHECK(p.hydrostatics.wetted_area == 0.0);
    CHECK(p.hydrostatics.waterplane.xx == 0.0);
    CHECK(p.hydrostatics.waterplane.zz == 0.0);
    // A rotation by a small angle θ about z, radius r: deviation ≈ r θ (|ΔR|_F = 2 sin(θ/2)·√2).
    HydrostaticsSnapshot still;
    const double theta = 1e-3, r = 2.0;
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    CHECK(HydrostaticsHistory::poseDeviation(Eigen::Vector3d(0, 0.01, 0), rot, still, r) ==
          Approx(0.01 + r * 2 * std::sin(theta / 2)).epsilon(1e-9));
    // A horizontal drift counts through the water's slope: 0 in flat water, 0.5 × 5 mm here.
    const Eigen::Vector3d drift(0.003, 0.002, 0.004);
    CHECK(HydrostaticsHistory::poseDeviation(drift, Eigen::Matrix3d::Identity(), still, r, 0.0) == Approx(0.002));
    CHECK(HydrostaticsHistory::poseDeviation(drift, Eigen::Matrix3d::Identity(), still, r, 0.5) ==
          Approx(0.002 + 0.5 * 0.005));
    // With the stiffness correction: slope × (drift + r θ) + 8 (rise + r θ)² / r.
    const double rt = r * 2 * std::sin(theta / 2);
    CHECK(HydrostaticsHistory::correctedPoseDeviation(drift, rot, still, r, 0.5) ==
          Approx(0.5 * (0.005 + rt) + 8 * (0.002 + rt) * (0.002 + rt) / r).epsilon(1e-9));
    CHECK(HydrostaticsHistory::velocityDeviation(Eigen::Vector3d(0.3, 0, 0.4), Eigen::Vector3d(0, 0.1, 0), still, r) ==
          Approx(0.5 + r * 0.1));
}

TEST_CASE("hydrostatic stiffness correction: exact evaluations at a nearby pose, to first order", "[temporal]") {
    // Oracle: clipping the mesh at the moved pose. The correction must remove the first-order change, leaving a
    // second-order remainder (here ≤ 3 % of the change for a 2 mm / 2 mrad move).
    const btFlatWaterSurface flat(0.0);
    const double rg = 1000.0 * 9.81;
    struct Case {
        const char* name;
        TriangleMesh mesh;
        Eigen::Vector3d com;  // mesh frame
    };
    const Case cases[] = {{"box", makeBoxMesh(2.0, 0.5, 1.0), Eigen::Vector3d(0.1, 0.05, -0.05)},
                          {"sphere", makeSphereMesh(0.5, 48, 24), Eigen::Vector3d(0.0, -0.1, 0.02)}};
    for (const Case& c : cases) {
        for (int k = 0; k < 4; ++k) {
            INFO(c.name << " pose " << k);
            Eigen::Isometry3d p0 = Eigen::Isometry3d::Identity();
            p0.linear() = (Eigen::AngleAxisd(0.7 * k, Eigen::Vector3d::UnitY()) *
                           Eigen::AngleAxisd(0.15 * (k - 1.5), Eigen::Vector3d::UnitX()))
                              .toRotationMatrix();
            p0.translation() = Eigen::Vector3d(0.3, -0.05 * k, -0.2);
            const Eigen::Vector3d c0 = p0 * c.com;
            HydrostaticsSnapshot s;
            s.hydrostatics = clippedHydrostatics(c.mesh, p0, flat, 0.0, 1000.0, 9.81, c0);
            REQUIRE(s.hydrostatics.waterplane.valid);
            s.com = c0;
            s.rotation = p0.linear();
            // The move: a small rotation about the COM, a rise and a horizontal shift (no change in flat water).
            const Eigen::Matrix3d turn =
                Eigen::AngleAxisd(2e-3, Eigen::Vector3d(0.6, 0.3 * k - 0.5, -0.8).normalized()).toRotationMatrix();
            const Eigen::Vector3d shift(0.003, 0.002, -0.001);
            Eigen::Isometry3d p1 = Eigen::Isometry3d::Identity();
            p1.linear() = turn * p0.linear();
            p1.translation() = turn * (p0.translation() - c0) + c0 + shift;
            const Eigen::Vector3d c1 = c0 + shift;
            const HydrostaticsResult exact = clippedHydrostatics(c.mesh, p1, flat, 0.0, 1000.0, 9.81, c1);
            HydrostaticsSnapshot moved = s;
            hydrostaticStiffnessCorrection(moved, c1, p1.linear(), rg);
            const double changeF = (exact.force - s.hydrostatics.force).norm();
            const double changeT = (exact.torque - s.hydrostatics.torque).norm();
            const double errF = (exact.force - moved.hydrostatics.force).norm();
            const double errT = (exact.torque - moved.hydrostatics.torque).norm();
            const double errV = std::abs(exact.submerged_volume - moved.hydrostatics.submerged_volume);
            std::printf("%s pose %d: force change %.3e N, left %.1e; torque change %.3e N m, left %.1e\n", c.name, k,
                        changeF, errF, changeT, errT);
            CHECK(errF <= 0.03 * changeF);
            CHECK(errT <= 0.03 * changeT);
            CHECK(errV * rg <= 0.03 * changeF);
        }
    }
}
