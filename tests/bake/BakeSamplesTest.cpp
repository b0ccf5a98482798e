// Tests of bakeSurfaceSamples (design.md 1.1) against sums computed here from the triangles.
#include <BulletBuoyancy/bake/BakeSamples.h>
#include <BulletBuoyancy/geometry/PolygonClip.h>
#include <BulletBuoyancy/atlas/UvLayout.h>
#include "oracles/OracleMeshes.h"

#include "bake/BakeTestMeshes.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

using namespace buoyancy;
using namespace bake_test;

namespace {

struct SampleSums {
    Eigen::Vector3d A = Eigen::Vector3d::Zero();        ///< Σ A_i
    double area = 0;                                    ///< Σ area_i
    double volume = 0;                                  ///< Σ A^y y (design.md 2.1)
    Eigen::Vector3d areaMoment = Eigen::Vector3d::Zero(); ///< Σ area_i p_i
};

SampleSums sampleSums(const SurfaceSamples& s) {
    SampleSums r;
    for (std::size_t i = 0; i < s.size(); ++i) {
        r.A += Eigen::Vector3d(s.ax[i], s.ay[i], s.az[i]);
        r.area += s.area[i];
        r.volume += s.ay[i] * s.py[i];
        r.areaMoment += s.area[i] * Eigen::Vector3d(s.px[i], s.py[i], s.pz[i]);
    }
    return r;
}

}  // namespace

TEST_CASE("polygon clipping: areas and centroids of known shapes", "[bake]") {
    // Unit square clipped by the half-plane left of the diagonal (0,0)→(1,1): the triangle above it.
    ClipPolygon sq;
    sq.n = 4;
    sq.v[0] = {0, 0};
    sq.v[1] = {1, 0};
    sq.v[2] = {1, 1};
    sq.v[3] = {0, 1};
    ClipPolygon out;
    clipHalfPlane(sq, {0, 0}, {1, 1}, out);
    double a;
    Eigen::Vector2d c;
    areaAndCentroid(out, a, c);
    CHECK(a == Approx(0.5));
    CHECK(c.x() == Approx(1.0 / 3));
    CHECK(c.y() == Approx(2.0 / 3));
    // Axis clip keeps the winding: a clockwise square gives a negative area.
    ClipPolygon cw;
    cw.n = 4;
    cw.v[0] = {0, 0};
    cw.v[1] = {0, 2};
    cw.v[2] = {2, 2};
    cw.v[3] = {2, 0};
    clipAxisAligned(cw, 0, 0.5, true, out);
    areaAndCentroid(out, a, c);
    CHECK(a == Approx(-3.0));
    CHECK(c.x() == Approx(1.25));
    CHECK(c.y() == Approx(1.0));
    // Two triangles: the right triangle (0,0),(2,0),(0,2) and its mirror (2,2),(0,2),(2,0) meet on an edge.
    CHECK(triangleIntersectionArea({0, 0}, {2, 0}, {0, 2}, {2, 2}, {0, 2}, {2, 0}) == Approx(0).margin(1e-15));
    // Shifted by (0.5, 0.5) the overlap is a right triangle with legs 1: area 0.5 (either winding).
    CHECK(triangleIntersectionArea({0, 0}, {2, 0}, {0, 2}, {0.5, 0.5}, {0.5, 2.5}, {2.5, 0.5}) == Approx(0.5));
}

TEST_CASE("exact coverage: closed meshes have zero net area vector and exact area and area moment", "[bake]") {
    struct Case {
        const char* name;
        TriangleMesh mesh;
    };
    std::vector<Case> cases = {{"box (face charts)", uvBox(1.0, 0.6, 2.2)},
                               {"sphere (lat-long UVs)", uvSphere(0.8, 48, 24)},
                               {"torus (angle UVs)", uvTorus(1.0, 0.3, 48, 24)}};
    for (const Case& c : cases) {
        const MeshSums ref = meshSums(c.mesh);
        for (int N : {16, 64, 200}) {
            INFO(c.name << " at " << N);
            const SurfaceSamples s = bakeSurfaceSamples(c.mesh, c.mesh.corner_uvs, N, BakeMethod::ExactCoverage);
            REQUIRE(s.size() > 0);
            CHECK(s.method == BakeMethod::ExactCoverage);
            CHECK(s.texture_size == N);
            const SampleSums got = sampleSums(s);
            CHECK(got.A.norm() <= 1e-9 * ref.area);
            CHECK(std::abs(got.area - ref.area) <= 1e-9 * ref.area);
            // Σ area_i p_i = ∫_S p dA exactly: p_i is the area-weighted centroid of the texel's pieces.
            CHECK((got.areaMoment - ref.areaMoment).norm() <= 1e-9 * ref.area * 2.5);
            // Samples are compacted and in increasing texel order, one per texel.
            for (std::size_t i = 1; i < s.size(); ++i) REQUIRE(s.texel[i] > s.texel[i - 1]);
            for (std::size_t i = 0; i < s.size(); ++i) {
                REQUIRE(s.texel[i] < static_cast<std::uint32_t>(N * N));
                REQUIRE(s.triangle[i] < c.mesh.triangles.size());
                REQUIRE(s.area[i] >= Eigen::Vector3d(s.ax[i], s.ay[i], s.az[i]).norm() * (1 - 1e-12));
            }
        }
    }
}

TEST_CASE("exact coverage: volume exact when every texel holds coplanar pieces (box)", "[bake]") {
    const double a = 1.3, b = 0.7, c = 2.1;
    const TriangleMesh box = uvBox(a, b, c);
    for (int N : {16, 64, 128}) {
        const SurfaceSamples s = bakeSurfaceSamples(box, box.corner_uvs, N, BakeMethod::ExactCoverage);
        const SampleSums got = sampleSums(s);
        INFO("N = " << N);
        CHECK(std::abs(got.volume - a * b * c) <= 1e-9 * a * b * c);
        // Each sample lies on the box surface: one coordinate at ± half its extent, the others inside.
        for (std::size_t i = 0; i < s.size(); ++i) {
            const Eigen::Vector3d p(s.px[i] / a, s.py[i] / b, s.pz[i] / c);
            REQUIRE(std::abs(p.cwiseAbs().maxCoeff() - 0.5) <= 1e-12);
        }
    }
}

TEST_CASE("exact coverage with a generated atlas: volume of closed meshes", "[bake]") {
    using namespace buoyancy_test;
    struct Case {
        const char* name;
        OracleMesh mesh;
        double tol;  // relative volume tolerance at N = 128
    };
    // Curved meshes: texels mixing pieces of non-coplanar triangles cost O(h²) (design.md 2.4 measured
    // 0.003–0.03 % at 128² on parametric layouts; our atlas uses ~40 % of the texture, so h is larger).
    // Flat-faced charts (box, tetrahedron): pieces in a texel are coplanar, the volume is exact.
    std::vector<Case> cases = {{"box", oracleBox(1.0, 2.0, 0.5), 1e-9},
                               {"tetrahedron", oracleTetrahedron(1.5), 1e-9},
                               {"sphere", oracleSphere(1.0, 64, 32), 5e-4},
                               {"torus", oracleTorus(1.0, 0.35, 64, 32), 2e-3},
                               {"cylinder", oracleCylinder(0.5, 1.5, 64), 1e-9}};  // sides have A^y = 0
    for (const Case& c : cases) {
        const TriangleMesh mesh = toTriangleMesh(c.mesh);
        const MeshSums ref = meshSums(mesh);
        const std::vector<Eigen::Vector2d> uvs = generateAtlas(mesh, 128);
        const SurfaceSamples s = bakeSurfaceSamples(mesh, uvs, 128, BakeMethod::ExactCoverage);
        const SampleSums got = sampleSums(s);
        INFO(c.name);
        CHECK(got.A.norm() <= 1e-9 * ref.area);
        CHECK(std::abs(got.area - ref.area) <= 1e-9 * ref.area);
        CHECK(std::abs(got.volume - ref.volume) <= c.tol * std::abs(ref.volume));
        // O(h²) convergence: doubling N divides the error by about 4 (at least by 3 here) — unless the atlas
        // already made the volume exact at 128² (charts of coplanar triangles), when it must stay exact.
        const double err128 = std::abs(got.volume - ref.volume);
        if (c.tol > 1e-9 && err128 <= 1e-12 * std::abs(ref.volume)) {
            const std::vector<Eigen::Vector2d> uvs2 = generateAtlas(mesh, 256);
            const SampleSums got2 = sampleSums(bakeSurfaceSamples(mesh, uvs2, 256, BakeMethod::ExactCoverage));
            CHECK(std::abs(got2.volume - ref.volume) <= 1e-12 * std::abs(ref.volume));
        } else if (c.tol > 1e-9) {
            const std::vector<Eigen::Vector2d> uvs2 = generateAtlas(mesh, 256);
            const SampleSums got2 = sampleSums(bakeSurfaceSamples(mesh, uvs2, 256, BakeMethod::ExactCoverage));
            CHECK(std::abs(got2.volume - ref.volume) < err128 / 3);
        }
    }
}

TEST_CASE("mirrored UVs give the same samples' sums", "[bake]") {
    for (BakeMethod method : {BakeMethod::ExactCoverage, BakeMethod::TexelCentre}) {
        for (const TriangleMesh& mesh : {uvBox(1.0, 0.6, 2.2), uvSphere(0.8, 32, 16), uvTorus(1.0, 0.3, 32, 16)}) {
            const TriangleMesh mirrored = mirroredUvs(mesh);
            const SampleSums a = sampleSums(bakeSurfaceSamples(mesh, mesh.corner_uvs, 64, method));
            const SurfaceSamples sm = bakeSurfaceSamples(mirrored, mirrored.corner_uvs, 64, method);
            const SampleSums b = sampleSums(sm);
            INFO(bakeMethodName(method));
            REQUIRE(sm.size() > 0);
            const double ref = meshSums(mesh).area;
            CHECK(std::abs(a.area - b.area) <= 1e-9 * ref);
            CHECK((a.A - b.A).norm() <= 1e-9 * ref);
            CHECK(std::abs(a.volume - b.volume) <= 1e-9 * std::abs(meshSums(mesh).volume));
            if (method == BakeMethod::ExactCoverage) CHECK(std::abs(b.area - ref) <= 1e-9 * ref);
        }
    }
}

TEST_CASE("texel-centre: area converges as the texture grows", "[bake]") {
    const TriangleMesh sphere = uvSphere(1.0, 48, 24);
    const double ref = meshSums(sphere).area;
    double previous = INFINITY;
    for (int N : {64, 256, 1024}) {
        const SurfaceSamples s = bakeSurfaceSamples(sphere, sphere.corner_uvs, N, BakeMethod::TexelCentre);
        const double err = std::abs(sampleSums(s).area - ref) / ref;
        INFO("N = " << N << " relative area error " << err);
        CHECK(err < previous);
        previous = err;
        // One sample per covered texel: with a single chart filling (almost) all of [0,1]², ~N² samples.
        CHECK(s.size() > 0.9 * 0.98 * 0.98 * N * N);
    }
    CHECK(previous < 0.01);
    // Texel centres exactly on shared edges are counted once: a UV square split on its diagonal, whose
    // diagonal passes through texel centres, yields each texel once (16 texels of a 4×4 texture).
    TriangleMesh quad;
    quad.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, -1}};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    quad.corner_uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    const SurfaceSamples q = bakeSurfaceSamples(quad, quad.corner_uvs, 4, BakeMethod::TexelCentre);
    CHECK(q.size() == 16);
    CHECK(sampleSums(q).area == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("bake rejects bad input with a clear message", "[bake]") {
    const TriangleMesh box = uvBox(1, 1, 1);
    CHECK_THROWS_WITH(bakeSurfaceSamples(box, box.corner_uvs, 0, BakeMethod::ExactCoverage),
                      Catch::Contains("texture size"));
    CHECK_THROWS_WITH(bakeSurfaceSamples(box, {}, 64, BakeMethod::ExactCoverage), Catch::Contains("corner UVs"));
    std::vector<Eigen::Vector2d> bad = box.corner_uvs;
    bad[4].x() = 1.5;
    CHECK_THROWS_WITH(bakeSurfaceSamples(box, bad, 64, BakeMethod::TexelCentre), Catch::Contains("outside [0,1]"));
    bad[4].x() = NAN;
    CHECK_THROWS_WITH(bakeSurfaceSamples(box, bad, 64, BakeMethod::ExactCoverage), Catch::Contains("not finite"));
    bad = box.corner_uvs;
    bad[1] = bad[0];
    bad[2] = bad[0];
    CHECK_THROWS_WITH(bakeSurfaceSamples(box, bad, 64, BakeMethod::ExactCoverage), Catch::Contains("zero UV area"));
}

TEST_CASE("bake accuracy table: dry volume error of primitives (printed)", "[bake][long]") {
    using namespace buoyancy_test;
    struct Case {
        const char* name;
        TriangleMesh mesh;
    };
    std::vector<Case> cases = {{"sphere 64x32", toTriangleMesh(oracleSphere(1.0, 64, 32))},
                               {"box", toTriangleMesh(oracleBox(1.0, 2.0, 0.5))},
                               {"torus 64x32", toTriangleMesh(oracleTorus(1.0, 0.35, 64, 32))},
                               {"cylinder 64", toTriangleMesh(oracleCylinder(0.5, 1.5, 64))}};
    for (const Case& c : cases) {
        const double V = meshSums(c.mesh).volume;
        for (auto [method, sizes] : {std::pair<BakeMethod, std::vector<int>>{BakeMethod::ExactCoverage, {64, 128, 256}},
                                     {BakeMethod::TexelCentre, {256, 512, 1024}}}) {
            for (int N : sizes) {
                const auto t0 = std::chrono::steady_clock::now();
                const std::vector<Eigen::Vector2d> uvs = generateAtlas(c.mesh, N);
                const auto t1 = std::chrono::steady_clock::now();
                const SurfaceSamples s = bakeSurfaceSamples(c.mesh, uvs, N, method);
                const auto t2 = std::chrono::steady_clock::now();
                const double err = (sampleSums(s).volume - V) / V;
                std::printf("%-12s %-15s N=%5d samples=%8zu volume err=%+.3e atlas=%.1f ms bake=%.1f ms\n", c.name,
                            bakeMethodName(method), N, s.size(), err,
                            std::chrono::duration<double, std::milli>(t1 - t0).count(),
                            std::chrono::duration<double, std::milli>(t2 - t1).count());
                if (method == BakeMethod::ExactCoverage) CHECK(std::abs(err) < 1e-2);
            }
        }
    }
}
