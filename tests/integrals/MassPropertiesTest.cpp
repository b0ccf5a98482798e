// Mass properties: exact polyhedral integrals and sample sums against the independent oracle and
// closed-form values (design.md 2.1, 5).
#include <BulletBuoyancy/integrals/MassProperties.h>
#include "oracles/OracleMeshes.h"
#include "oracles/PolyhedralOracle.h"
#include "TestSamples.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

using namespace buoyancy;
using namespace buoyancy_test;

namespace {
constexpr double kPi = 3.14159265358979323846;

double relFrobenius(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a - b).norm() / b.norm(); }

double diagonalOf(const OracleMesh& m) {
    Eigen::Vector3d lo = m.verts[0], hi = m.verts[0];
    for (const auto& v : m.verts) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    return (hi - lo).norm();
}

OracleMesh posedShape(const OracleMesh& m, const Eigen::Isometry3d& pose) { return {oraclePose(m.verts, pose), m.tris}; }
}  // namespace

TEST_CASE("polyhedronMassProperties: box is exact", "[integrals][mass]") {
    const double rho = 700;
    const MassProperties m = polyhedronMassProperties(toTriangleMesh(oracleBox(2, 3, 5)), rho);
    CHECK(m.volume == Approx(30).epsilon(1e-14));
    CHECK(m.mass == Approx(rho * 30).epsilon(1e-14));
    CHECK(m.area == Approx(2 * (6 + 15 + 10)).epsilon(1e-14));
    CHECK(m.centre.norm() < 1e-13);
    CHECK(relFrobenius(m.inertia, rho * boxInertia(2, 3, 5)) < 1e-13);
}

TEST_CASE("polyhedronMassProperties matches the tetrahedra oracle on posed shapes", "[integrals][mass]") {
    const OracleMesh shapes[] = {oracleBox(1.0, 0.6, 0.8), oracleTetrahedron(1.3), oracleSphere(0.5, 32, 16),
                                 oracleTorus(0.6, 0.2, 32, 16), oracleCylinder(0.3, 1.2, 24)};
    const Eigen::Isometry3d pose =
        Eigen::Translation3d(3.0, -1.5, 7.0) * Eigen::AngleAxisd(0.9, Eigen::Vector3d(-1, 2, 0.5).normalized());
    for (const auto& s : shapes) {
        const OracleMesh p = posedShape(s, pose);
        const OracleMoments o = oracleDryMoments(p.verts, p.tris);
        const MassProperties m = polyhedronMassProperties(toTriangleMesh(p), 1.0);
        CHECK(m.volume == Approx(o.volume).epsilon(1e-12));
        CHECK((m.centre - o.centroid).norm() < 1e-12 * diagonalOf(p));
        CHECK(relFrobenius(m.inertia, o.inertiaAboutCentroid()) < 1e-10);
        CHECK(m.area == Approx(oracleSurfaceArea(p.verts, p.tris)).epsilon(1e-12));
    }
}

TEST_CASE("polyhedronMassProperties: analytic primitives within tessellation tolerance", "[integrals][mass]") {
    const double R = 0.5;
    const MassProperties sphere = polyhedronMassProperties(toTriangleMesh(oracleSphere(R, 128, 64)), 1.0);
    CHECK(sphere.volume == Approx(sphereVolume(R)).epsilon(2e-3));
    CHECK(relFrobenius(sphere.inertia, sphereInertia(R)) < 4e-3);
    // Cylinder r, h: V = π r² h, I_yy = M r²/2, I_xx = I_zz = M(3r² + h²)/12.
    const double r = 0.3, h = 1.2;
    const MassProperties cyl = polyhedronMassProperties(toTriangleMesh(oracleCylinder(r, h, 128)), 1.0);
    const double Vc = kPi * r * r * h;
    CHECK(cyl.volume == Approx(Vc).epsilon(1e-3));
    const Eigen::Matrix3d Ic = Eigen::Vector3d(Vc * (3 * r * r + h * h) / 12, Vc * r * r / 2, Vc * (3 * r * r + h * h) / 12)
                                   .asDiagonal();
    CHECK(relFrobenius(cyl.inertia, Ic) < 2e-3);
    // Torus R, a (axis y): V = 2π² R a², I_yy = M(R² + 3a²/4), I_xx = I_zz = M(R²/2 + 5a²/8).
    const double Rt = 0.6, a = 0.2;
    const MassProperties tor = polyhedronMassProperties(toTriangleMesh(oracleTorus(Rt, a, 128, 64)), 1.0);
    const double Vt = 2 * kPi * kPi * Rt * a * a;
    CHECK(tor.volume == Approx(Vt).epsilon(3e-3));  // inscribed polygons: ≈ (2π/64)²/6 + (2π/128)²/6
    const Eigen::Matrix3d It = Eigen::Vector3d(Vt * (Rt * Rt / 2 + 5 * a * a / 8), Vt * (Rt * Rt + 3 * a * a / 4),
                                               Vt * (Rt * Rt / 2 + 5 * a * a / 8))
                                   .asDiagonal();
    CHECK(relFrobenius(tor.inertia, It) < 3e-3);
}

TEST_CASE("polyhedronMassProperties rejects bad input", "[integrals][mass]") {
    TriangleMesh box = toTriangleMesh(oracleBox(1, 1, 1));
    CHECK_THROWS_AS(polyhedronMassProperties(box, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(polyhedronMassProperties(box, std::nan("")), std::invalid_argument);
    TriangleMesh inverted = box;
    for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
    CHECK_THROWS_WITH(polyhedronMassProperties(inverted, 1.0), Catch::Contains("not positive"));
    TriangleMesh bad = box;
    bad.triangles[3][1] = 99;
    CHECK_THROWS_WITH(polyhedronMassProperties(bad, 1.0), Catch::Contains("out of range"));
    CHECK_THROWS_AS(polyhedronMassProperties(TriangleMesh{}, 1.0), std::invalid_argument);
}

TEST_CASE("solidMassProperties: one sample per box triangle is exact", "[integrals][mass]") {
    // On axis-aligned faces every field of design.md 2.1 is at most linear over the face, so a sample at
    // each triangle's centroid integrates it exactly.
    const OracleMesh box = posedShape(oracleBox(2, 3, 5), Eigen::Isometry3d(Eigen::Translation3d(0.5, -1, 2)));
    const SurfaceSamples s = subdividedSamples(box, 1);
    const MassProperties m = solidMassProperties(s, 2.0);
    CHECK(m.volume == Approx(30).epsilon(1e-13));
    CHECK(m.mass == Approx(60).epsilon(1e-13));
    CHECK(m.area == Approx(62).epsilon(1e-13));
    CHECK((m.centre - Eigen::Vector3d(0.5, -1, 2)).norm() < 1e-12);
    CHECK(relFrobenius(m.inertia, 2.0 * boxInertia(2, 3, 5)) < 1e-12);
}

TEST_CASE("solidMassProperties from samples converges to the oracle (O(h²))", "[integrals][mass]") {
    const Eigen::Isometry3d pose =
        Eigen::Translation3d(0.2, 0.1, -0.3) * Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized());
    const OracleMesh shapes[] = {posedShape(oracleSphere(0.5, 32, 16), pose), posedShape(oracleTorus(0.6, 0.2, 32, 16), pose)};
    for (const auto& p : shapes) {
        const OracleMoments o = oracleDryMoments(p.verts, p.tris);
        double prevC = 1, prevI = 1;
        for (int k : {1, 2, 4}) {
            const MassProperties m = solidMassProperties(subdividedSamples(p, k), 1.0);
            CHECK(m.volume == Approx(o.volume).epsilon(1e-12));  // linear field: exact
            const double ec = (m.centre - o.centroid).norm() / diagonalOf(p);
            const double ei = relFrobenius(m.inertia, o.inertiaAboutCentroid());
            INFO("k=" << k << " centre err/diag=" << ec << " inertia err=" << ei);
            CHECK(ec < 5e-3);
            CHECK(ei < 2e-2);
            if (k > 1) {
                CHECK(ec < prevC / 3 + 1e-12);
                CHECK(ei < prevI / 3 + 1e-12);
            }
            prevC = ec;
            prevI = ei;
        }
    }
}

TEST_CASE("shellMassProperties: thin cube shell", "[integrals][mass]") {
    const double L = 2.0, rho = 800, t = 0.01;
    const SurfaceSamples s = subdividedSamples(oracleBox(L, L, L), 16);
    const MassProperties m = shellMassProperties(s, rho, t);
    const double M = rho * t * 6 * L * L;  // ρ Σ|A_i| t, not ρ Σ A^y t (which is 0)
    CHECK(m.mass == Approx(M).epsilon(1e-12));
    CHECK(m.centre.norm() < 1e-12);
    // Thin cube shell: I = 5/18 M L² about every axis through the centre.
    CHECK(relFrobenius(m.inertia, (5.0 / 18.0) * M * L * L * Eigen::Matrix3d::Identity()) < 1e-2);

    // Per-sample areal density: top face massless → the 5 other faces put the COM at y = −L/10.
    std::vector<double> sigma(s.size(), rho * t);
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.py[i] > 0.5 * L - 1e-9) sigma[i] = 0;
    const MassProperties open = shellMassProperties(s, sigma);
    CHECK(open.mass == Approx(M * 5 / 6).epsilon(1e-12));
    CHECK(open.centre.y() == Approx(-L / 10).epsilon(1e-12));
    CHECK(std::abs(open.centre.x()) < 1e-12);

    CHECK_THROWS_AS(shellMassProperties(s, rho, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(shellMassProperties(s, std::vector<double>(3, 1.0)), std::invalid_argument);
    sigma[5] = -1;
    CHECK_THROWS_AS(shellMassProperties(s, sigma), std::invalid_argument);
}

TEST_CASE("shellMassProperties: sphere shell 2/3 M R²", "[integrals][mass]") {
    const double R = 0.5;
    const MassProperties m = shellMassProperties(subdividedSamples(oracleSphere(R, 64, 32), 2), 1.0, 1.0);
    CHECK(m.mass == Approx(4 * kPi * R * R).epsilon(3e-3));
    CHECK(relFrobenius(m.inertia, (2.0 / 3.0) * m.mass * R * R * Eigen::Matrix3d::Identity()) < 3e-3);
}

TEST_CASE("solidMassProperties rejects bad input", "[integrals][mass]") {
    SurfaceSamples s = subdividedSamples(oracleBox(1, 1, 1), 1);
    CHECK_THROWS_AS(solidMassProperties(s, -1.0), std::invalid_argument);
    CHECK_THROWS_AS(solidMassProperties(SurfaceSamples{}, 1.0), std::invalid_argument);
    SurfaceSamples inv = s;
    for (auto* v : {&inv.ax, &inv.ay, &inv.az})
        for (double& a : *v) a = -a;
    CHECK_THROWS_WITH(solidMassProperties(inv, 1.0), Catch::Contains("not positive"));
    s.ay.pop_back();
    CHECK_THROWS_WITH(solidMassProperties(s, 1.0), Catch::Contains("different lengths"));
}

TEST_CASE("principalFrame diagonalises with a proper rotation", "[integrals][mass]") {
    const Eigen::Matrix3d R0 = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
    for (const Eigen::Vector3d d : {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(5, 5, 2), Eigen::Vector3d(4, 4, 4)}) {
        const Eigen::Matrix3d I = R0 * d.asDiagonal() * R0.transpose();
        const PrincipalFrame f = principalFrame(I);
        CHECK(f.rotation.determinant() == Approx(1.0).epsilon(1e-12));
        CHECK((f.rotation.transpose() * f.rotation - Eigen::Matrix3d::Identity()).norm() < 1e-12);
        CHECK((f.rotation * f.moments.asDiagonal() * f.rotation.transpose() - I).norm() < 1e-12 * I.norm());
        Eigen::Vector3d sorted = d;
        std::sort(sorted.data(), sorted.data() + 3);
        CHECK((f.moments - sorted).norm() < 1e-12 * d.norm());
    }
    Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
    nan(0, 1) = std::nan("");
    CHECK_THROWS_AS(principalFrame(nan), std::invalid_argument);
    Eigen::Matrix3d asym = Eigen::Matrix3d::Identity();
    asym(0, 1) = 0.5;
    CHECK_THROWS_AS(principalFrame(asym), std::invalid_argument);
}
