// prepareMesh with PrepareMeshOptions::repair: what is repaired, what is still refused, and the report. Expected
// volumes and areas are those of the unit cubes and boxes the tests build (closed forms), never the library's
// output.

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include "mesh/MeshTestUtil.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace buoyancy;
using namespace mesh_test;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

/// The unit cube [0,1]³ shifted by `offset`, outward, appended to m.
void addCube(TriangleMesh& m, const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) { appendUnitCube(m, offset); }

PrepareMeshOptions repairing() {
    PrepareMeshOptions o;
    o.repair = true;
    return o;
}

bool warned(const MeshReport& r, const std::string& text) {
    for (const auto& w : r.warnings)
        if (w.message.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("repair option: an open box is closed at its rim, the cap is reported", "[mesh][repair]") {
    TriangleMesh m = importMeshFile(data("open_box.obj"));  // the unit cube without its z = 1 face
    TriangleMesh strict = m;
    CHECK_THROWS_WITH(prepareMesh(strict, "open_box.obj"), Contains("open surface: 4 boundary edges"));
    const MeshReport r = prepareMesh(m, "open_box.obj", repairing());
    CHECK(r.repair.holes_closed == 1);
    CHECK(r.repair.hole_edges == 4);
    CHECK(r.repair.area_added == Approx(1.0));
    CHECK(r.repair.volume_after == Approx(1.0));
    CHECK(tetraVolume(m) == Approx(1.0).epsilon(1e-12));
    REQUIRE(r.repair.hole_triangles.size() == 2);
    for (std::size_t t : r.repair.hole_triangles)
        for (int k = 0; k < 3; ++k) CHECK(m.corner(t, k).z() == 1.0);
    // The open surface closed through its bounding-box centre (0.5, 0.5, 0.5): the cone over the missing face
    // (area 1, height 0.5) is 1/6 of the cube, so 5/6 is left.
    CHECK(r.repair.volume_before == Approx(5.0 / 6.0));
    CHECK(warned(r, "repaired: closed 1 hole (4 boundary edges, 1 m^2 added)"));
}

TEST_CASE("repair option: faces turned the wrong way are turned back", "[mesh][repair]") {
    TriangleMesh m = importMeshFile(data("flipped_patch.obj"));  // the unit cube with its x = 1 face reversed
    const MeshReport r = prepareMesh(m, "flipped_patch.obj", repairing());
    CHECK(r.repair.faces_reoriented == 2);
    CHECK(r.repair.holes_closed == 0);
    CHECK(tetraVolume(m) == Approx(1.0).epsilon(1e-12));
    CHECK(r.repair.volume_after == Approx(1.0));
}

TEST_CASE("repair option: faces given twice", "[mesh][repair]") {
    SECTION("the same way: one is kept") {
        TriangleMesh m;
        addCube(m);
        m.triangles.push_back(m.triangles[3]);
        TriangleMesh strict = m;
        CHECK_THROWS_WITH(prepareMesh(strict, "cube"), Contains("non-manifold"));
        const MeshReport r = prepareMesh(m, "cube", repairing());
        CHECK(r.repair.duplicate_faces_removed == 1);
        CHECK(m.triangles.size() == 12);
        CHECK(tetraVolume(m) == Approx(1.0).epsilon(1e-12));
    }
    SECTION("opposite ways between two cubes (an inner wall): both go, the cubes merge") {
        TriangleMesh m;
        addCube(m);
        addCube(m, Eigen::Vector3d(1, 0, 0));  // shares the face x = 1 (welded: the same four vertices)
        const MeshReport r = prepareMesh(m, "two cubes", repairing());
        CHECK(r.repair.duplicate_faces_removed == 4);
        CHECK(r.components == 1);
        CHECK(tetraVolume(m) == Approx(2.0).epsilon(1e-12));
    }
}

TEST_CASE("repair option: two solids touching along an edge are accepted", "[mesh][repair]") {
    TriangleMesh m = importMeshFile(data("nonmanifold_edge.obj"));  // two unit cubes sharing one edge
    TriangleMesh strict = m;
    CHECK_THROWS_WITH(prepareMesh(strict, "nonmanifold_edge.obj"), Contains("non-manifold: 1 edge"));
    const MeshReport r = prepareMesh(m, "nonmanifold_edge.obj", repairing());
    CHECK(r.repair.paired_nonmanifold_edges == 1);
    CHECK(r.components == 2);
    CHECK(tetraVolume(m) == Approx(2.0).epsilon(1e-12));
}

TEST_CASE("repair option: what cannot be repaired is still refused", "[mesh][repair][errors]") {
    SECTION("a one-sided surface (a Moebius band, closed by nothing)") {
        TriangleMesh m;
        const int n = 12;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * 3.14159265358979323846 * i / n, half = a / 2;
            const Eigen::Vector3d c(std::cos(a), 0, std::sin(a)), radial = c, up(0, 1, 0);
            const Eigen::Vector3d w = std::cos(half) * radial * 0.3 + std::sin(half) * up * 0.3;
            m.vertices.push_back(c + w);
            m.vertices.push_back(c - w);
        }
        for (int i = 0; i < n; ++i) {
            const int a0 = 2 * i, a1 = 2 * i + 1;
            // After a full turn the band's two edges swap: the last strip joins a to b.
            const int b0 = i + 1 < n ? 2 * (i + 1) : 1, b1 = i + 1 < n ? 2 * (i + 1) + 1 : 0;
            m.triangles.emplace_back(a0, b0, b1);
            m.triangles.emplace_back(a0, b1, a1);
        }
        CHECK_THROWS_WITH(prepareMesh(m, "band", repairing()), StartsWith("band: cannot be repaired") &&
                                                                   Contains("cannot be oriented consistently"));
    }
    SECTION("a hole larger than the limit") {
        TriangleMesh m = importMeshFile(data("open_box.obj"));
        PrepareMeshOptions o = repairing();
        o.maxHoleEdges = 3;
        CHECK_THROWS_WITH(prepareMesh(m, "open_box.obj", o),
                          StartsWith("open_box.obj: ") && Contains("4 boundary edges") && Contains("3"));
    }
}

TEST_CASE("repair option: a fin (a sheet on an edge) is closed on itself and removed", "[mesh][repair]") {
    TriangleMesh m;
    addCube(m);
    m.vertices.emplace_back(0.5, -1.0, 0.0);  // a fin on the cube's edge (0,0,0)–(1,0,0)
    m.triangles.emplace_back(0, 1, int(m.vertices.size()) - 1);
    TriangleMesh strict = m;
    CHECK_THROWS_WITH(prepareMesh(strict, "fin"), Contains("open surface") && Contains("non-manifold"));
    const MeshReport r = prepareMesh(m, "fin", repairing());
    CHECK(r.repair.flat_parts_removed == 1);
    CHECK(r.components == 1);
    CHECK(m.triangles.size() == 12);
    CHECK(tetraVolume(m) == Approx(1.0).epsilon(1e-12));
    CHECK(r.repair.volume_after == Approx(1.0));
    CHECK(warned(r, "removed 1 flat part enclosing no volume"));
}

TEST_CASE("repair option: a clean mesh is unchanged and reports nothing", "[mesh][repair]") {
    TriangleMesh m;
    addCube(m);
    const TriangleMesh before = m;
    const MeshReport r = prepareMesh(m, "cube", repairing());
    CHECK_FALSE(r.repair.changed());
    CHECK(std::isnan(r.repair.volume_before));
    CHECK(r.warnings.empty());
    CHECK(m.triangles == before.triangles);
}
