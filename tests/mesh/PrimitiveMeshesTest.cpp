// Primitive meshes: closed, welded, outward (prepareMesh leaves them unchanged), volumes against exact
// polyhedral formulas derived by hand, and UVs forming a valid layout (inside [0,1]², counter-clockwise,
// no two triangles covering the same UV point — checked by point sampling).

#include <BulletBuoyancy/mesh/MeshRepair.h>
#include "mesh/MeshTestUtil.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

using namespace buoyancy;
using namespace mesh_test;

namespace {

constexpr double kPi = 3.14159265358979323846;

double uvCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const Eigen::Vector2d u = b - a, v = c - a;
    return u.x() * v.y() - u.y() * v.x();
}

/// Checks the UV layout: every corner in [0,1]², every UV triangle counter-clockwise with positive area,
/// and no sample point of a G × G grid strictly inside two triangles.
void checkUvLayout(const TriangleMesh& m, int G = 1024) {
    REQUIRE(m.hasUvs());
    for (const Eigen::Vector2d& t : m.corner_uvs) {
        REQUIRE(t.x() >= 0.0);
        REQUIRE(t.x() <= 1.0);
        REQUIRE(t.y() >= 0.0);
        REQUIRE(t.y() <= 1.0);
    }
    std::vector<unsigned char> hits(static_cast<std::size_t>(G) * G, 0);
    std::size_t overlaps = 0, nonPositive = 0;
    for (std::size_t t = 0; t < m.triangleCount(); ++t) {
        const Eigen::Vector2d a = m.corner_uvs[3 * t], b = m.corner_uvs[3 * t + 1], c = m.corner_uvs[3 * t + 2];
        if (!(uvCross(a, b, c) > 0)) { ++nonPositive; continue; }
        const Eigen::Vector2d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
        for (int i = std::max(0, int(lo.x() * G - 1)); i <= std::min(G - 1, int(hi.x() * G + 1)); ++i)
            for (int j = std::max(0, int(lo.y() * G - 1)); j <= std::min(G - 1, int(hi.y() * G + 1)); ++j) {
                const Eigen::Vector2d p((i + 0.5) / G, (j + 0.5) / G);
                if (uvCross(a, b, p) > 0 && uvCross(b, c, p) > 0 && uvCross(c, a, p) > 0)
                    if (++hits[std::size_t(i) * G + j] > 1) ++overlaps;
            }
    }
    CHECK(nonPositive == 0);
    CHECK(overlaps == 0);
}

/// prepareMesh must find nothing to do.
void checkClean(const TriangleMesh& original) {
    TriangleMesh m = original;
    const MeshReport r = prepareMesh(m, "primitive");
    CHECK(r.welded_vertices == 0);
    CHECK(r.degenerate_removed == 0);
    CHECK(r.components == 1);
    CHECK(r.flipped_components == 0);
    CHECK(r.warnings.empty());
    const bool sameTriangles = m.triangles == original.triangles;  // same indices: nothing renumbered
    const bool sameVertices = m.vertices == original.vertices;
    const bool sameUvs = m.corner_uvs == original.corner_uvs;
    CHECK(sameTriangles);
    CHECK(sameVertices);
    CHECK(sameUvs);
}

}  // namespace

TEST_CASE("primitives: box", "[mesh][primitives]") {
    const TriangleMesh m = makeBoxMesh(1.0, 2.0, 3.0);
    CHECK(m.vertices.size() == 8);
    CHECK(m.triangleCount() == 12);
    checkClean(m);
    CHECK(tetraVolume(m) == Approx(6.0).epsilon(1e-14));
    CHECK(bbox(m).min().isApprox(Eigen::Vector3d(-0.5, -1, -1.5)));
    checkUvLayout(m);
}

TEST_CASE("primitives: UV sphere", "[mesh][primitives]") {
    const int S = 64, R = 32;
    const double r = 1.5;
    const TriangleMesh m = makeSphereMesh(r, S, R);
    CHECK(m.vertices.size() == static_cast<std::size_t>(2 + S * (R - 1)));
    CHECK(m.triangleCount() == static_cast<std::size_t>(2 * S * (R - 1)));
    checkClean(m);
    // Exact volume of this polyhedron, written independently: by rotational symmetry every one of the S
    // sectors of band i (between polar angles θ_i and θ_{i+1}) has the same two tetrahedra (O,A,B,C) and
    // (O,A,C,D), A, D on ring i and B, C on ring i+1 at azimuths 0 and 2π/S (at the poles two coincide and
    // one tetrahedron is flat, which the formula handles).
    double v = 0;
    const double d = 2 * kPi / S;
    for (int i = 0; i < R; ++i) {
        const double t0 = kPi * i / R, t1 = kPi * (i + 1) / R;
        const double r0 = r * std::sin(t0), y0 = r * std::cos(t0), r1 = r * std::sin(t1), y1 = r * std::cos(t1);
        const Eigen::Vector3d A(r0, y0, 0), B(r1, y1, 0), C(r1 * std::cos(d), y1, -r1 * std::sin(d)),
            D(r0 * std::cos(d), y0, -r0 * std::sin(d));
        v += S * (A.dot(B.cross(C)) + A.dot(C.cross(D))) / 6.0;
    }
    CHECK(tetraVolume(m) == Approx(v).epsilon(1e-12));
    // And close to the ball: the inscribed polyhedron is smaller, within 1 % at 64 × 32.
    CHECK(tetraVolume(m) < 4.0 / 3.0 * kPi * r * r * r);
    CHECK(tetraVolume(m) == Approx(4.0 / 3.0 * kPi * r * r * r).epsilon(0.01));
    checkUvLayout(m);
    checkUvLayout(makeSphereMesh(1.0, 7, 3), 512);
}

TEST_CASE("primitives: cylinder", "[mesh][primitives]") {
    const int S = 48;
    const double r = 0.7, h = 2.5;
    const TriangleMesh m = makeCylinderMesh(r, h, S);
    CHECK(m.vertices.size() == static_cast<std::size_t>(2 * S + 2));
    CHECK(m.triangleCount() == static_cast<std::size_t>(4 * S));
    checkClean(m);
    // Prism over the inscribed regular S-gon: area (S/2) r² sin(2π/S).
    CHECK(tetraVolume(m) == Approx(0.5 * S * r * r * std::sin(2 * kPi / S) * h).epsilon(1e-12));
    const Eigen::AlignedBox3d b = bbox(m);
    CHECK(b.min().y() == Approx(-h / 2));
    CHECK(b.max().y() == Approx(h / 2));
    checkUvLayout(m);
}

TEST_CASE("primitives: torus", "[mesh][primitives]") {
    const int M = 64, N = 32;
    const double R = 2.0, r = 0.5;
    const TriangleMesh m = makeTorusMesh(R, r, M, N);
    CHECK(m.vertices.size() == static_cast<std::size_t>(M * N));
    CHECK(m.triangleCount() == static_cast<std::size_t>(2 * M * N));
    checkClean(m);
    // Pappus for the analytic torus 2π² R r²; the tessellation is within 1 %.
    CHECK(tetraVolume(m) == Approx(2 * kPi * kPi * R * r * r).epsilon(0.01));
    CHECK(tetraVolume(m) > 0);
    checkUvLayout(m);
}

TEST_CASE("primitives: bad parameters throw", "[mesh][primitives][errors]") {
    CHECK_THROWS_AS(makeBoxMesh(0, 1, 1), std::invalid_argument);
    CHECK_THROWS_AS(makeSphereMesh(-1), std::invalid_argument);
    CHECK_THROWS_AS(makeSphereMesh(1, 2, 8), std::invalid_argument);
    CHECK_THROWS_AS(makeCylinderMesh(1, std::nan("")), std::invalid_argument);
    CHECK_THROWS_AS(makeTorusMesh(1, 2), std::invalid_argument);
}
