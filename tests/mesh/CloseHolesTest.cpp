// closeHoles: boundary loops closed by least-area caps. Expected areas and volumes are closed forms (polygon
// areas, prism volumes) computed here, never the library's output.

#include <BulletBuoyancy/mesh/CloseHoles.h>
#include <BulletBuoyancy/mesh/MeshImport.h>
#include "mesh/MeshTestUtil.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <map>

using namespace buoyancy;
using namespace mesh_test;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A prism of height h over the polygon `outline` (counter-clockwise seen from +y, in x–z as (x, z)), outward,
/// with its side faces and its bottom cap (a fan from `fanCentre`, valid for the star-shaped outlines used here)
/// but no top: the top rim is the only hole.
TriangleMesh openPrism(const std::vector<Eigen::Vector2d>& outline, double h, const Eigen::Vector2d& fanCentre) {
    TriangleMesh m;
    const int n = int(outline.size());
    for (const auto& p : outline) m.vertices.emplace_back(p.x(), 0.0, p.y());
    for (const auto& p : outline) m.vertices.emplace_back(p.x(), h, p.y());
    m.vertices.emplace_back(fanCentre.x(), 0.0, fanCentre.y());
    const int c = 2 * n;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        // Sides and bottom agree with each other; which way they face depends on the outline's turn (the callers
        // turn the whole mesh outward).
        m.triangles.emplace_back(i, j, n + j);
        m.triangles.emplace_back(i, n + j, n + i);
        m.triangles.emplace_back(c, j, i);
    }
    return m;
}

/// Signed area of a polygon in (x, z) by the shoelace formula.
double shoelace(const std::vector<Eigen::Vector2d>& p) {
    double a = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const auto& u = p[i];
        const auto& v = p[(i + 1) % p.size()];
        a += u.x() * v.y() - v.x() * u.y();
    }
    return 0.5 * a;
}

/// Every directed edge a→b is matched by one b→a (a closed, consistently oriented surface).
bool closedAndConsistent(const TriangleMesh& m) {
    std::map<std::pair<int, int>, int> count;
    for (const auto& t : m.triangles)
        for (int k = 0; k < 3; ++k) ++count[{t[k], t[(k + 1) % 3]}];
    for (const auto& [e, c] : count)
        if (c != 1 || count.count({e.second, e.first}) == 0 || count.at({e.second, e.first}) != 1) return false;
    return true;
}

}  // namespace

TEST_CASE("close holes: the open top of a regular 12-gon prism gets exactly the polygon's area", "[mesh][repair]") {
    const int n = 12;
    const double r = 0.7, h = 1.3;
    std::vector<Eigen::Vector2d> outline;
    for (int i = 0; i < n; ++i) outline.emplace_back(r * std::cos(2 * kPi * i / n), -r * std::sin(2 * kPi * i / n));
    TriangleMesh m = openPrism(outline, h, Eigen::Vector2d::Zero());
    if (tetraVolume(m) < 0) for (auto& t : m.triangles) std::swap(t[1], t[2]);  // outward, whatever the outline's turn
    const std::size_t before = m.triangles.size();
    const HoleClosing c = closeHoles(m, 1000, 1e-18);
    const double polygonArea = 0.5 * n * r * r * std::sin(2 * kPi / n);  // n isosceles triangles
    CHECK(c.holes == 1);
    CHECK(c.boundary_edges == std::size_t(n));
    CHECK(c.triangles.size() == std::size_t(n - 2));  // no new vertices: a triangulation of the 12 rim vertices
    CHECK(c.triangles.front() == before);
    CHECK(c.area_added == Approx(polygonArea).epsilon(1e-12));
    CHECK(closedAndConsistent(m));
    CHECK(tetraVolume(m) == Approx(polygonArea * h).epsilon(1e-12));
    for (std::size_t t : c.triangles)
        for (int k = 0; k < 3; ++k) CHECK(m.corner(t, k).y() == h);  // the cap lies on the rim
}

TEST_CASE("close holes: a non-convex (L-shaped) planar hole is triangulated inside its outline", "[mesh][repair]") {
    // An L: the unit square [0,2]x[0,2] minus [1,2]x[1,2]; area 3. Any triangle reaching outside the L (across
    // the notch) would add area: the least-area cap is a triangulation of the L itself.
    const std::vector<Eigen::Vector2d> outline{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    const double h = 0.5;
    TriangleMesh m = openPrism(outline, h, Eigen::Vector2d(0.5, 0.5));
    if (tetraVolume(m) < 0) for (auto& t : m.triangles) std::swap(t[1], t[2]);
    const HoleClosing c = closeHoles(m, 1000, 1e-18);
    REQUIRE(std::abs(shoelace(outline)) == Approx(3.0));
    CHECK(c.holes == 1);
    CHECK(c.area_added == Approx(3.0).epsilon(1e-12));
    CHECK(closedAndConsistent(m));
    CHECK(tetraVolume(m) == Approx(3.0 * h).epsilon(1e-12));
}

TEST_CASE("close holes: a closed mesh is left as it is and a hole over the limit is refused", "[mesh][repair][errors]") {
    std::vector<Eigen::Vector2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    TriangleMesh m = openPrism(square, 1.0, Eigen::Vector2d(0.5, 0.5));
    if (tetraVolume(m) < 0) for (auto& t : m.triangles) std::swap(t[1], t[2]);
    closeHoles(m, 1000, 1e-18);
    const TriangleMesh closed = m;
    const HoleClosing again = closeHoles(m, 1000, 1e-18);
    CHECK(again.holes == 0);
    CHECK(m.triangles == closed.triangles);

    std::vector<Eigen::Vector2d> many;
    for (int i = 0; i < 40; ++i) many.emplace_back(std::cos(2 * kPi * i / 40), std::sin(2 * kPi * i / 40));
    TriangleMesh big = openPrism(many, 1.0, Eigen::Vector2d::Zero());
    CHECK_THROWS_AS(closeHoles(big, 39, 1e-18), MeshError);
    CHECK_THROWS_WITH(closeHoles(big, 39, 1e-18), Contains("40 boundary edges") && Contains("39"));
}

TEST_CASE("close holes: two holes touching at one vertex are closed separately", "[mesh][repair]") {
    // The unit cube (12 triangles) without two triangles that share only corner 7 = (1,1,1): one from the top
    // face (z = 1) and one from the face x = 1. The boundary walks through corner 7 twice.
    TriangleMesh m;
    appendUnitCube(m);
    // (4,7,6) of the top and (1,3,7) of the side x = 1 share only vertex 7.
    std::vector<Eigen::Vector3i> kept;
    for (const auto& t : m.triangles)
        if (!(t == Eigen::Vector3i(4, 7, 6)) && !(t == Eigen::Vector3i(1, 3, 7))) kept.push_back(t);
    REQUIRE(kept.size() == 10);
    m.triangles = kept;
    const HoleClosing c = closeHoles(m, 1000, 1e-18);
    CHECK(c.holes == 2);
    CHECK(c.boundary_edges == 6);
    CHECK(c.area_added == Approx(1.0));  // two half unit squares
    CHECK(closedAndConsistent(m));
    CHECK(tetraVolume(m) == Approx(1.0).epsilon(1e-12));
}
