// The paper's automatic water graph from CGAL's SDF segmentation (optional). The graph tests compile
// only when the library was built with -DBULLET_BUOYANCY_CGAL=ON (which defines BULLET_BUOYANCY_HAS_CGAL); the
// default build only checks the scene key's errors ("method": "sdf" without CGAL is a clear error).
// Oracles: a dumbbell built here (two spheres of radius 0.5 joined by a thin neck of radius 0.125, as a
// polyhedral surface of revolution) whose enclosed volume is known exactly from the frustum formula; its two
// lobes are the thick parts, so the SDF segmentation must separate them from the neck. (A dumbbell of two
// boxes does not work with CGAL's SDF segmentation: its flat faces make the graph cut's smoothing merge
// everything into one segment for any λ ≥ 0.02 — measured — so the test shape is smooth like the paper's.)
#include <catch2/catch.hpp>

#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"

#include <string>

namespace {
/// The error of a scene with one box body and the given extra body keys ("no error" when it parses).
std::string sdfSceneError(const std::string& extra) {
    try {
        buoyancy::cli::parseScene(
            std::string(R"({"bodies": [{"name": "b", "shape": {"type": "box", "size": [2, 1, 1]}, "mass": 300)") + extra + "}]}",
            "s.json", ".");
    } catch (const buoyancy::cli::UsageError& e) {
        return e.what();
    }
    return "no error";
}
}  // namespace

TEST_CASE("scene key water_graph.auto.method: unknown values are refused", "[graph][cli]") {
    CHECK_THAT(sdfSceneError(R"(, "water_graph": {"auto": {"nodes": 3, "method": "magic"}})"),
               Catch::Contains("bodies[0].water_graph.auto.method") && Catch::Contains("voxels or sdf"));
    CHECK(sdfSceneError(R"(, "water_graph": {"auto": {"nodes": 3, "method": "voxels"}})") == "no error");
}

#ifndef BULLET_BUOYANCY_HAS_CGAL
TEST_CASE("scene key water_graph.auto.method sdf: a clear error without CGAL", "[graph][cli]") {
    CHECK_THAT(sdfSceneError(R"(, "water_graph": {"auto": {"nodes": 3, "method": "sdf"}})"),
               Catch::Contains("bodies[0].water_graph.auto.method") &&
                   Catch::Contains("built without CGAL (BULLET_BUOYANCY_CGAL=OFF)"));
}
#endif

#ifdef BULLET_BUOYANCY_HAS_CGAL

#include "scene/SceneGraph.h"
#include <BulletBuoyancy/graph/cgal/SdfWaterGraph.h>

#include <cmath>
#include <queue>
#include <stdexcept>
#include <string>
#include <vector>
#include <algorithm>

using namespace buoyancy;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kAround = 32;  // polygon sides of each ring

/// Ring positions x_i (m) and radii r_i (m) of the dumbbell's profile along x: spheres of radius 0.5 centred at
/// x = ±1 joined by a neck of radius 0.125, rings every 0.05 m, poles (r = 0) at x = ±1.5.
void dumbbellProfile(std::vector<double>& xs, std::vector<double>& rs) {
    for (int i = 0; i <= 60; ++i) {
        const double x = -1.5 + 0.05 * i, d = std::abs(x);
        const double sphere = d >= 0.5 ? std::sqrt(std::max(0.0, 0.25 - (d - 1) * (d - 1))) : 0.0;
        xs.push_back(x);
        rs.push_back(i == 0 || i == 60 ? 0.0 : std::max(sphere, 0.125));
    }
}

/// The dumbbell as a closed, welded, outward CCW mesh: regular kAround-gon rings joined by quads, fans to the poles.
TriangleMesh dumbbell() {
    std::vector<double> xs, rs;
    dumbbellProfile(xs, rs);
    TriangleMesh m;
    m.vertices.emplace_back(xs.front(), 0, 0);  // 0: pole at −x
    m.vertices.emplace_back(xs.back(), 0, 0);   // 1: pole at +x
    const int rings = int(xs.size()) - 2;
    auto at = [&](int ring, int j) { return 2 + ring * kAround + (j % kAround); };
    for (int i = 1; i <= rings; ++i)
        for (int j = 0; j < kAround; ++j) {
            const double t = 2 * kPi * j / kAround;
            m.vertices.emplace_back(xs[std::size_t(i)], rs[std::size_t(i)] * std::cos(t), rs[std::size_t(i)] * std::sin(t));
        }
    for (int j = 0; j < kAround; ++j) {
        m.triangles.emplace_back(0, at(0, j + 1), at(0, j));
        m.triangles.emplace_back(1, at(rings - 1, j), at(rings - 1, j + 1));
        for (int i = 0; i + 1 < rings; ++i) {
            m.triangles.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j + 1));
            m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i + 1, j));
        }
    }
    return m;
}

/// Exact enclosed volume of dumbbell(): each band between two similar, aligned regular polygons is a
/// frustum, V = h/3 (A₁ + A₂ + √(A₁A₂)) with A = (n/2) r² sin(2π/n) (the poles are pyramids, A = 0).
double dumbbellVolume() {
    std::vector<double> xs, rs;
    dumbbellProfile(xs, rs);
    double v = 0;
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
        const double a1 = 0.5 * kAround * rs[i] * rs[i] * std::sin(2 * kPi / kAround);
        const double a2 = 0.5 * kAround * rs[i + 1] * rs[i + 1] * std::sin(2 * kPi / kAround);
        v += (xs[i + 1] - xs[i]) / 3 * (a1 + a2 + std::sqrt(a1 * a2));
    }
    return v;
}

int nearestNode(const WaterGraph& g, const Eigen::Vector3d& p) {
    int best = 0;
    for (int i = 1; i < int(g.nodes.size()); ++i)
        if ((g.nodes[std::size_t(i)].position - p).norm() < (g.nodes[std::size_t(best)].position - p).norm()) best = i;
    return best;
}

bool connected(const WaterGraph& g, int a, int b) {
    std::vector<char> seen(g.nodes.size(), 0);
    std::queue<int> q;
    q.push(a);
    seen[std::size_t(a)] = 1;
    while (!q.empty()) {
        const int x = q.front();
        q.pop();
        if (x == b) return true;
        for (const WaterEdge& e : g.edges) {
            const int y = e.from == x ? e.to : e.to == x ? e.from : -1;
            if (y >= 0 && !seen[std::size_t(y)]) {
                seen[std::size_t(y)] = 1;
                q.push(y);
            }
        }
    }
    return false;
}

}  // namespace

TEST_CASE("sdf water graph: a dumbbell's lobes become different, connected nodes", "[graph][cgal]") {
    const TriangleMesh mesh = dumbbell();
    const double volume = dumbbellVolume();  // exact, frustum formula
    const double lobe = 0.5 * volume;         // the neck's voxels go to the neck's node or split evenly
    for (int k : {2, 3}) {
        INFO("k = " << k);
        SdfWaterGraphSettings s;
        s.nodes = k;
        s.fill = 0.8;
        const WaterGraph g = sdfWaterGraph(mesh, s);
        REQUIRE(g.nodes.size() >= 2);
        CHECK(g.nodes.size() == 3);  // the two lobes and the neck (three parts of distinct thickness)
        double total = 0;
        for (const WaterNode& n : g.nodes) total += n.capacity;
        CHECK(total == Approx(s.fill * volume).epsilon(1e-12));

        const int a = nearestNode(g, Eigen::Vector3d(-1, 0, 0));
        const int b = nearestNode(g, Eigen::Vector3d(1, 0, 0));
        CHECK(a != b);
        // Each lobe node sits in its lobe and holds about its sphere's share (voxel-level error at the neck).
        CHECK(std::abs(g.nodes[std::size_t(a)].position.x() + 1) < 0.25);
        CHECK(std::abs(g.nodes[std::size_t(b)].position.x() - 1) < 0.25);
        // A lobe is a sphere of radius 0.5 (polygonised): at most fill × its share, at least most of the sphere.
        const double sphere = 4.0 / 3.0 * kPi * 0.125;
        for (int n : {a, b}) {
            CHECK(g.nodes[std::size_t(n)].capacity < s.fill * lobe * 1.001);
            CHECK(g.nodes[std::size_t(n)].capacity > 0.8 * s.fill * sphere);
        }
        // The mirror-symmetric shape gives mirror-symmetric lobe nodes.
        CHECK(g.nodes[std::size_t(a)].capacity == Approx(g.nodes[std::size_t(b)].capacity).epsilon(0.02));
        // Water can pass from one lobe to the other (directly or through the neck's node).
        CHECK(connected(g, a, b));
        CHECK_NOTHROW(g.validate());
    }
}

TEST_CASE("sdf water graph: bad input is refused with a named problem", "[graph][cgal]") {
    TriangleMesh mesh = dumbbell();
    SdfWaterGraphSettings s;
    s.nodes = 0;
    CHECK_THROWS_WITH(sdfWaterGraph(mesh, s), Catch::Contains("sdf.nodes"));
    s = SdfWaterGraphSettings{};
    s.fill = 1.5;
    CHECK_THROWS_WITH(sdfWaterGraph(mesh, s), Catch::Contains("sdf.fill"));
    s = SdfWaterGraphSettings{};
    mesh.triangles.pop_back();  // a hole: not closed
    CHECK_THROWS_WITH(sdfWaterGraph(mesh, s), Catch::Contains("not closed"));
    CHECK_THROWS_AS(sdfWaterGraph(TriangleMesh{}, s), std::invalid_argument);
}

TEST_CASE("scene key water_graph.auto.method sdf builds the SDF graph", "[graph][cli][cgal]") {
    CHECK_THAT(sdfSceneError(R"(, "water_graph": {"auto": {"nodes": 65, "method": "sdf"}})"),
               Catch::Contains("water_graph.auto.nodes"));
    const buoyancy::cli::Scene scene = buoyancy::cli::parseScene(
        R"({"bodies": [{"name": "b", "shape": {"type": "box", "size": [2, 1, 1]}, "mass": 300,
            "water_graph": {"auto": {"nodes": 2, "method": "sdf", "fill": 0.5}}}]})", "s.json", ".");
    const buoyancy::cli::SceneFlooding& f = scene.bodies[0].flooding;
    REQUIRE(f.automatic);
    REQUIRE(f.sdf);
    const WaterGraph g = buoyancy::cli::buildSceneWaterGraph(f, dumbbell());
    CHECK(g.nodes.size() == 3);
    CHECK(g.nodes[0].name.rfind("sdf", 0) == 0);
    double total = 0;
    for (const WaterNode& n : g.nodes) total += n.capacity;
    CHECK(total == Approx(0.5 * dumbbellVolume()).epsilon(1e-12));
}

#endif  // BULLET_BUOYANCY_HAS_CGAL
