// Tests of the independent oracle itself against closed-form values (design.md 5).
#include "oracles/OracleMeshes.h"
#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace buoyancy_test;

namespace {
constexpr double kPi = 3.14159265358979323846;

/// Mirror y → −y (winding reversed so it stays outward).
OracleMesh mirrorY(const OracleMesh& m) {
    OracleMesh r = m;
    for (auto& v : r.verts) v.y() = -v.y();
    for (auto& t : r.tris) std::swap(t[1], t[2]);
    return r;
}
}  // namespace

TEST_CASE("oracle: unit cube and box", "[oracle]") {
    const OracleMesh cube = oracleBox(1, 1, 1);
    const OracleMoments m = oracleDryMoments(cube.verts, cube.tris);
    CHECK(m.volume == Approx(1.0).epsilon(1e-14));
    CHECK(m.centroid.norm() < 1e-14);
    CHECK((m.inertiaAboutCentroid() - Eigen::Matrix3d::Identity() / 6.0).norm() < 1e-14);
    CHECK(oracleSurfaceArea(cube.verts, cube.tris) == Approx(6.0));

    const OracleMesh box = oracleBox(2, 3, 5);
    const OracleMoments b = oracleDryMoments(box.verts, box.tris);
    CHECK(b.volume == Approx(30.0).epsilon(1e-14));
    CHECK((b.inertiaAboutCentroid() - boxInertia(2, 3, 5)).norm() < 1e-12);
    // Submerged part below y = h: a·c·(h + b/2), centre at the middle of the draft.
    for (double h : {-1.4, -0.5, 0.0, 0.7, 1.49}) {
        const OracleMoments s = oracleSubmergedMoments(box.verts, box.tris, h);
        CHECK(s.volume == Approx(boxSubmergedVolume(2, 3, 5, h)).epsilon(1e-13));
        CHECK(s.centroid.y() == Approx(boxCentreOfBuoyancyY(2, 3, 5, h)).epsilon(1e-13));
        CHECK(std::abs(s.centroid.x()) < 1e-13);
        CHECK(std::abs(s.centroid.z()) < 1e-13);
        CHECK(oracleCapArea(box.verts, box.tris, h) == Approx(10.0).epsilon(1e-13));
    }
    CHECK(oracleSubmergedMoments(box.verts, box.tris, -2.0).volume == 0.0);
    CHECK(oracleSubmergedMoments(box.verts, box.tris, 2.0).volume == Approx(30.0).epsilon(1e-14));
}

TEST_CASE("oracle: tetrahedron closed forms", "[oracle]") {
    const double s = 1.7;
    const OracleMesh t = oracleTetrahedron(s);
    const OracleMoments m = oracleDryMoments(t.verts, t.tris);
    CHECK(m.volume == Approx(s * s * s / 6.0).epsilon(1e-14));
    CHECK((m.centroid - Eigen::Vector3d::Constant(s / 4.0)).norm() < 1e-14);
    // ∫x² = s⁵/60, ∫xy = s⁵/120 over the corner tetrahedron.
    const double s5 = std::pow(s, 5);
    CHECK(m.second(0, 0) == Approx(s5 / 60.0).epsilon(1e-13));
    CHECK(m.second(1, 1) == Approx(s5 / 60.0).epsilon(1e-13));
    CHECK(m.second(0, 1) == Approx(s5 / 120.0).epsilon(1e-13));
    CHECK(m.second(1, 2) == Approx(s5 / 120.0).epsilon(1e-13));
    // Below y = h: the similar tetrahedron of height s − h is cut off above → V = s³/6 − (s − h)³/6.
    const double h = 0.6;
    CHECK(oracleSubmergedMoments(t.verts, t.tris, h).volume ==
          Approx(s * s * s / 6.0 - std::pow(s - h, 3) / 6.0).epsilon(1e-13));
    // Cap: the triangle x, z ≥ 0, x + z ≤ s − h.
    CHECK(oracleCapArea(t.verts, t.tris, h) == Approx(0.5 * (s - h) * (s - h)).epsilon(1e-13));
}

TEST_CASE("oracle: sphere mesh converges to the ball", "[oracle]") {
    const double R = 0.8;
    double prev = 1.0;
    for (int n : {16, 32, 64, 128}) {
        const OracleMesh s = oracleSphere(R, 2 * n, n);
        const OracleMoments m = oracleDryMoments(s.verts, s.tris);
        const double err = std::abs(m.volume / sphereVolume(R) - 1.0);
        CHECK(err < prev / 3.0);  // O(1/n²)
        prev = err;
        CHECK(m.centroid.norm() < 1e-12);
        CHECK((m.inertiaAboutCentroid() - sphereInertia(R)).norm() / sphereInertia(R).norm() < 3 * err + 1e-12);
    }
    CHECK(prev < 1e-3);
    // Caps: volume and centroid against π h²(3R − h)/3 and 3(2R − h)²/(4(3R − h)).
    const OracleMesh s = oracleSphere(R, 256, 128);
    for (double hc : {0.1, 0.5, 0.8, 1.3, 1.55}) {
        const double level = -R + hc;
        const OracleMoments c = oracleSubmergedMoments(s.verts, s.tris, level);
        CHECK(c.volume == Approx(sphereCapVolume(R, hc)).epsilon(2e-3));
        CHECK(-c.centroid.y() == Approx(sphereCapCentroidDistance(R, hc)).epsilon(2e-3));
        CHECK(oracleCapArea(s.verts, s.tris, level) == Approx(kPi * (R * R - level * level)).epsilon(2e-3));
    }
}

TEST_CASE("oracle: split at any plane conserves volume and first moment (posed meshes)", "[oracle]") {
    const OracleMesh shapes[] = {oracleBox(1.0, 0.6, 0.8), oracleSphere(0.5, 24, 12), oracleTorus(0.6, 0.2, 24, 12),
                                 oracleCylinder(0.3, 1.2, 20)};
    const Eigen::Isometry3d pose =
        Eigen::Translation3d(0.3, 0.1, -0.2) * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
    for (const auto& shape : shapes) {
        OracleMesh posed{oraclePose(shape.verts, pose), shape.tris};
        const OracleMoments dry = oracleDryMoments(posed.verts, posed.tris);
        const OracleMesh flipped = mirrorY(posed);
        for (double h : {-0.31, -0.05, 0.12, 0.37}) {
            const OracleMoments below = oracleSubmergedMoments(posed.verts, posed.tris, h);
            const OracleMoments above = oracleSubmergedMoments(flipped.verts, flipped.tris, -h);
            CHECK(below.volume + above.volume == Approx(dry.volume).epsilon(1e-12));
            Eigen::Vector3d aboveFirst = above.volume * above.centroid;
            aboveFirst.y() = -aboveFirst.y();
            CHECK((below.volume * below.centroid + aboveFirst - dry.volume * dry.centroid).norm() < 1e-12);
            // The cap seen from below and from above is the same area.
            CHECK(oracleCapArea(posed.verts, posed.tris, h) ==
                  Approx(oracleCapArea(flipped.verts, flipped.tris, -h)).epsilon(1e-12));
        }
    }
}
