// prepareMesh: the catalogue of broken meshes, each with its exact error, and what it repairs.
// Expected counts are the ones built by hand in tests/data/meshes/generate.py or below.

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include "mesh/MeshTestUtil.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <ctime>
#include <cmath>
#include <limits>

using namespace buoyancy;
using namespace mesh_test;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;

namespace {

/// The hand-written unit cube [0,1]³ (same corner numbering and outward quads as generate.py).
TriangleMesh unitCube() {
    TriangleMesh m;
    appendUnitCube(m);
    return m;
}

MeshReport prepareFile(const std::string& name, TriangleMesh* out = nullptr) {
    TriangleMesh m = importMeshFile(data(name));
    MeshReport r = prepareMesh(m, name);
    if (out) *out = m;
    return r;
}

}  // namespace

TEST_CASE("repair: the catalogue of broken files, each with its error", "[mesh][repair][errors]") {
    CHECK_THROWS_WITH(prepareFile("open_box.obj"), Equals("open_box.obj: open surface: 4 boundary edges"));
    CHECK_THROWS_WITH(prepareFile("nonmanifold_edge.obj"),
                      Equals("nonmanifold_edge.obj: non-manifold: 1 edge shared by more than two faces"));
    CHECK_THROWS_WITH(prepareFile("flipped_patch.obj"),
                      Equals("flipped_patch.obj: inconsistent orientation: 4 edges used twice in the same "
                             "direction (flipped triangles)"));
    // assimp's OBJ reader gives each face corner its own vertex; corner 7 is in 6 of the cube's triangles.
    CHECK_THROWS_WITH(prepareFile("nan_vertex.obj"),
                      Equals("nan_vertex.obj: non-finite coordinates: 6 triangles have a NaN or Inf corner"));
    CHECK_THROWS_WITH(prepareFile("huge_coordinates.obj"),
                      StartsWith("huge_coordinates.obj: coordinates too large: |x| up to 1e+30 m exceeds the limit of 1e+06 m"));
}

TEST_CASE("repair: an all-inward mesh is flipped with a warning", "[mesh][repair]") {
    TriangleMesh m;
    const MeshReport r = prepareFile("inverted_box.obj", &m);
    CHECK(r.flipped_components == 1);
    REQUIRE(r.warnings.size() == 1);
    CHECK_THAT(r.warnings[0].message, Equals("inverted_box.obj: mesh was inside-out (volume -1 m^3): flipped outward"));
    CHECK(tetraVolume(m) == Approx(1.0));
}

TEST_CASE("repair: zero-area triangles are removed and counted", "[mesh][repair]") {
    TriangleMesh m;
    const MeshReport r = prepareFile("zero_area.obj", &m);
    CHECK(r.input_triangles == 15);
    CHECK(r.degenerate_removed == 3);
    CHECK(m.triangleCount() == 12);
    CHECK(m.vertices.size() == 8);  // the midpoint used only by the removed triangles is gone
    CHECK(tetraVolume(m) == Approx(1.0));
}

TEST_CASE("repair: a cavity (inward box inside an outward box) is kept", "[mesh][repair]") {
    TriangleMesh m;
    const MeshReport r = prepareFile("box_with_cavity.obj", &m);
    CHECK(r.components == 2);
    CHECK(r.cavities == 1);
    CHECK(r.flipped_components == 0);
    CHECK(r.warnings.empty());
    CHECK(tetraVolume(m) == Approx(4.0 * 4 * 4 - 2.0 * 2 * 2));
}

TEST_CASE("repair: an inverted box inside nothing next to a good one is flipped, intersecting parts warned",
          "[mesh][repair]") {
    TriangleMesh m;
    const MeshReport r = prepareFile("intersecting_boxes.obj", &m);
    CHECK(r.components == 2);
    REQUIRE(r.warnings.size() == 1);
    CHECK_THAT(r.warnings[0].message, Contains("1 pair of components intersect each other (1&2)"));

    // Two separate cubes, the second inside-out: flipped, the first untouched.
    TriangleMesh two = unitCube();
    TriangleMesh second = unitCube();
    for (Eigen::Vector3i t : second.triangles) two.triangles.emplace_back(t[0] + 8, t[2] + 8, t[1] + 8);
    for (Eigen::Vector3d v : second.vertices) two.vertices.push_back(v + Eigen::Vector3d(5, 0, 0));
    const MeshReport r2 = prepareMesh(two, "two.obj");
    CHECK(r2.components == 2);
    CHECK(r2.flipped_components == 1);
    CHECK(r2.cavities == 0);
    REQUIRE(r2.warnings.size() == 1);
    CHECK_THAT(r2.warnings[0].message, Equals("two.obj: component 2 of 2 was inside-out (volume -1 m^3): flipped outward"));
    CHECK(tetraVolume(two) == Approx(2.0));
}

TEST_CASE("repair: a whole model exported inside-out (with its cavity) is flipped as a whole", "[mesh][repair]") {
    TriangleMesh m = importMeshFile(data("box_with_cavity.obj"));
    for (Eigen::Vector3i& t : m.triangles) std::swap(t[1], t[2]);
    const MeshReport r = prepareMesh(m, "inside_out_cavity");
    CHECK(r.flipped_components == 2);
    CHECK(r.cavities == 1);
    CHECK(tetraVolume(m) == Approx(56.0));
}

TEST_CASE("repair: in-memory bad input", "[mesh][repair][errors]") {
    TriangleMesh nan = unitCube();
    nan.vertices[0].x() = std::numeric_limits<double>::quiet_NaN();  // corner 0 is in 6 triangles
    CHECK_THROWS_WITH(prepareMesh(nan, "m"), Equals("m: non-finite coordinates: 6 triangles have a NaN or Inf corner"));
    TriangleMesh inf = unitCube();
    inf.vertices[7].z() = std::numeric_limits<double>::infinity();  // corner 7: 6 triangles
    CHECK_THROWS_WITH(prepareMesh(inf, "m"), StartsWith("m: non-finite coordinates: 6 triangles"));
    TriangleMesh big = unitCube();
    for (auto& v : big.vertices) v *= 2e6;
    CHECK_THROWS_WITH(prepareMesh(big, "m"), StartsWith("m: coordinates too large: |x| up to 2e+06 m"));
    TriangleMesh tiny = unitCube();
    for (auto& v : tiny.vertices) v *= 1e-9;
    CHECK_THROWS_WITH(prepareMesh(tiny, "m"), StartsWith("m: model too small"));
    TriangleMesh badIndex = unitCube();
    badIndex.triangles[3][1] = 42;
    CHECK_THROWS_WITH(prepareMesh(badIndex, "m"), Equals("m: vertex index out of range: 1 corner"));
    TriangleMesh empty;
    CHECK_THROWS_WITH(prepareMesh(empty, "m"), Equals("m: no triangles"));
    TriangleMesh allDegenerate;
    allDegenerate.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    allDegenerate.triangles = {{0, 1, 2}, {0, 0, 1}};
    CHECK_THROWS_WITH(prepareMesh(allDegenerate, "m"),
                      Equals("m: no triangles left after removing 2 degenerate (zero-area) triangles"));
    // Two coincident opposite triangles: closed, consistent, but enclosing nothing.
    TriangleMesh flat;
    flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    flat.triangles = {{0, 1, 2}, {0, 2, 1}};
    CHECK_THROWS_WITH(prepareMesh(flat, "m"), StartsWith("m: flat component: component 1 of 1"));
}

TEST_CASE("repair: welding tolerance is relative to the model size", "[mesh][repair]") {
    for (double size : {1e-3, 1.0, 1e4}) {
        INFO(size);
        // Soup of the cube with each corner copy moved by 1e-8 of the size: must weld to 8 vertices.
        TriangleMesh cube = unitCube();
        TriangleMesh soup;
        int n = 0;
        for (const Eigen::Vector3i& t : cube.triangles) {
            for (int k = 0; k < 3; ++k)
                soup.vertices.push_back(size * (cube.vertices[t[k]] + 1e-8 * Eigen::Vector3d(n % 3, (n / 3) % 2, n % 5 * 0.1)));
            soup.triangles.emplace_back(3 * n, 3 * n + 1, 3 * n + 2);
            ++n;
        }
        TriangleMesh welded = soup;
        const MeshReport r = prepareMesh(welded, "soup");
        CHECK(welded.vertices.size() == 8);
        CHECK(r.welded_vertices == 36 - 8);
        CHECK(tetraVolume(welded) == Approx(size * size * size).epsilon(1e-6));
        // Moved by 1e-3 of the size: far beyond the tolerance, the soup stays open (36 boundary edges).
        for (std::size_t i = 0; i < soup.vertices.size(); ++i) soup.vertices[i] += size * 1e-3 * Eigen::Vector3d(i % 7, i % 3, 0);
        CHECK_THROWS_WITH(prepareMesh(soup, "soup"), StartsWith("soup: open surface: "));
    }
}

TEST_CASE("repair: UVs follow their triangles through removal and flipping", "[mesh][repair]") {
    TriangleMesh m = unitCube();
    for (int t = 0; t < 12; ++t)
        for (int k = 0; k < 3; ++k) m.corner_uvs.emplace_back(t, k);  // (triangle, corner) tags
    for (Eigen::Vector3i& t : m.triangles) std::swap(t[1], t[2]);    // inside-out
    m.triangles.insert(m.triangles.begin(), Eigen::Vector3i(0, 0, 1));  // a degenerate first triangle
    m.corner_uvs.insert(m.corner_uvs.begin(), {{-1, 0}, {-1, 1}, {-1, 2}});
    const MeshReport r = prepareMesh(m, "m");
    CHECK(r.degenerate_removed == 1);
    CHECK(r.flipped_components == 1);
    REQUIRE(m.corner_uvs.size() == 36);
    for (int t = 0; t < 12; ++t) {
        // Flipping swaps corners 1 and 2, with their UVs: the tags come back in the original corner order.
        CHECK(m.corner_uvs[3 * t + 0] == Eigen::Vector2d(t, 0));
        CHECK(m.corner_uvs[3 * t + 1] == Eigen::Vector2d(t, 2));
        CHECK(m.corner_uvs[3 * t + 2] == Eigen::Vector2d(t, 1));
    }
    CHECK(tetraVolume(m) == Approx(1.0));
}

TEST_CASE("repair: a large soup is welded and checked quickly", "[mesh][repair]") {
    // A 200 × 200 × 6 grid cube surface as a soup: 480 000 triangles.
    const int n = 200;
    TriangleMesh soup;
    auto add = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
        const int base = static_cast<int>(soup.vertices.size());
        soup.vertices.push_back(a);
        soup.vertices.push_back(b);
        soup.vertices.push_back(c);
        soup.triangles.emplace_back(base, base + 1, base + 2);
    };
    TriangleMesh cube = unitCube();
    for (int q = 0; q < 6; ++q) {
        const Eigen::Vector3d o = cube.vertices[cube.triangles[2 * q][0]];
        const Eigen::Vector3d u = cube.vertices[cube.triangles[2 * q][1]] - o;
        const Eigen::Vector3d v = cube.vertices[cube.triangles[2 * q + 1][2]] - o;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const Eigen::Vector3d p = o + u * i / n + v * j / n, du = u / n, dv = v / n;
                add(p, p + du, p + du + dv);
                add(p, p + du + dv, p + dv);
            }
    }
    // The calling thread's CPU time (prepareMesh runs on it): a loaded machine does not slow this clock (on wall time
    // the check failed under a load of 9, at 6 s against 1.7 s alone).
    auto cpuSeconds = [] {
        timespec ts{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
        return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
    };
    const double t0 = cpuSeconds();
    const MeshReport r = prepareMesh(soup, "grid");
    const double seconds = cpuSeconds() - t0;
    CHECK(r.components == 1);
    CHECK(soup.vertices.size() == static_cast<std::size_t>(6 * n * n + 2));  // Euler: V = E − F + 2 = F/2 + 2
    CHECK(tetraVolume(soup) == Approx(1.0).epsilon(1e-9));
    CHECK(seconds < 5.0);
}
