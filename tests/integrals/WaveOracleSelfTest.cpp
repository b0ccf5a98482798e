// Tests of the curved-water reference itself (tests/oracles/WaveOracle.h) against closed forms and the flat-water
// polyhedral oracle (design.md 5).
#include "oracles/OracleMeshes.h"
#include "oracles/PolyhedralOracle.h"
#include "oracles/WaveOracle.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace buoyancy_test;

namespace {
constexpr double kPi = 3.14159265358979323846;

std::vector<Eigen::Vector3d> shifted(const OracleMesh& m, const Eigen::Vector3d& t) {
    std::vector<Eigen::Vector3d> v = m.verts;
    for (auto& p : v) p += t;
    return v;
}
}  // namespace

TEST_CASE("wave oracle: box under one Airy wave against the closed form", "[oracle][waves]") {
    // Box 4 × 1.5 × 1 (x, y, z) centred at (cx, 0, 0.3): bottom at −0.75 always under η ∈ [−0.5, 0.5], top at 0.75
    // always above, so V = L_z ∫ (η − y_b) dx and F_x / (ρg) = L_z ∫ −η_x (η − y_b) dx = −L_z [η²/2 − y_b η].
    const double a = 0.5, lambda = 20.0, k = 2 * kPi / lambda;
    const OracleMesh box = oracleBox(4.0, 1.5, 1.0);
    for (double phase : {0.0, 0.7, 2.1}) {
        for (double cx : {0.0, 3.3}) {
            const auto eta = [&](double x, double) { return a * std::cos(k * x + phase); };
            const std::vector<Eigen::Vector3d> v = shifted(box, Eigen::Vector3d(cx, 0.0, 0.3));
            WaveOracleOptions o;
            o.maxEdge = lambda / 40;
            const WaveOracleResult r = waveOracle(v, box.tris, eta, Eigen::Vector3d(cx, 0, 0.3), o);
            const double x0 = cx - 2, x1 = cx + 2, yb = -0.75;
            const double V = airyBoxVolume(a, k, phase, x0, x1, yb, 1.0);
            CHECK(std::abs(r.volume - V) <= 1e-9 * 6.0);
            const auto e = [&](double x) { return a * std::cos(k * x + phase); };
            const double Fx = -1.0 * ((0.5 * e(x1) * e(x1) - yb * e(x1)) - (0.5 * e(x0) * e(x0) - yb * e(x0)));
            CHECK(std::abs(r.force.x() - Fx) <= 1e-6 * 6.0);
            CHECK(std::abs(r.force.y() - V) <= 1e-9 * 6.0);
            CHECK(std::abs(r.force.z()) <= 1e-9 * 6.0);
            // First moment along x: L_z ∫ x (η − y_b) dx, by parts: (a/k)[x sin] + (a/k²)[cos] − y_b [x²/2].
            const auto F1 = [&](double x) {
                return (a / k) * x * std::sin(k * x + phase) + (a / (k * k)) * std::cos(k * x + phase) - yb * 0.5 * x * x;
            };
            CHECK(std::abs(r.firstMoment.x() - (F1(x1) - F1(x0))) <= 1e-8 * 6.0 * 4.0);
        }
    }
}

TEST_CASE("wave oracle: flat water matches the polyhedral oracle, torque included", "[oracle][waves]") {
    const OracleMesh cyl = oracleCylinder(0.8, 2.0, 14);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, 0.2, 1).normalized()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.2, 0.1, -0.4);
    const std::vector<Eigen::Vector3d> v = oraclePose(cyl.verts, pose);
    const double h = 0.25;
    const OracleMoments s = oracleSubmergedMoments(v, cyl.tris, h);
    WaveOracleOptions o;
    o.maxEdge = 0.5;
    const Eigen::Vector3d ref(0.1, -0.3, 0.2);
    const WaveOracleResult r = waveOracle(v, cyl.tris, [&](double, double) { return h; }, ref, o);
    // The waterline's pieces are refined, not cut exactly: an error of a few 1e-9 of V remains there.
    CHECK(r.volume == Approx(s.volume).epsilon(1e-7));
    CHECK((r.centreOfBuoyancy() - s.centroid).norm() <= 1e-7);
    // Flat water: force (0, V, 0), torque (C_B − ref) × (0, V, 0).
    CHECK((r.force - Eigen::Vector3d(0, s.volume, 0)).norm() <= 1e-7 * s.volume);
    CHECK((r.torque - (s.centroid - ref).cross(Eigen::Vector3d(0, s.volume, 0))).norm() <= 1e-7 * s.volume * 2.0);
}

TEST_CASE("wave oracle: its own error on a tilted cylinder in two crossing waves is below 1e-5 of V", "[oracle][waves]") {
    // Halving the sub-triangle edge changes the result by less than 1e-5 V (the rule is O(h⁴) away from the
    // waterline and the waterline pieces are refined 5 more times).
    const OracleMesh cyl = oracleCylinder(1.0, 3.0, 16);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(1.2, Eigen::Vector3d(1, 0.1, 0.2).normalized()).toRotationMatrix();
    const std::vector<Eigen::Vector3d> v = oraclePose(cyl.verts, pose);
    const auto eta = [](double x, double z) {
        return 0.4 * std::cos(2 * kPi / 9.0 * x + 0.3) + 0.3 * std::cos(2 * kPi / 6.0 * (0.6 * x + 0.8 * z));
    };
    const double Vbody = kPi * 1.0 * 3.0;
    WaveOracleOptions o;
    o.maxEdge = 6.0 / 40;
    const WaveOracleResult coarse = waveOracle(v, cyl.tris, eta, Eigen::Vector3d::Zero(), o);
    o.maxEdge /= 2;
    const WaveOracleResult fine = waveOracle(v, cyl.tris, eta, Eigen::Vector3d::Zero(), o);
    CHECK(coarse.volume > 0.1 * Vbody);
    CHECK(std::abs(coarse.volume - fine.volume) <= 1e-5 * Vbody);
    CHECK((coarse.firstMoment - fine.firstMoment).norm() <= 1e-5 * Vbody * 3.0);
    CHECK((coarse.force - fine.force).norm() <= 1e-5 * Vbody);
}
