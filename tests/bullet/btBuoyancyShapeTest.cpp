// btBuoyancyShape::create runs the mesh checks of the command line on any mesh it is given: an open, inside-out or
// degenerate mesh is refused with std::invalid_argument and the same message prepareMesh gives, so no shape can be
// built from a mesh that encloses no well-defined volume. Oracles: the unit box's volume (1 m³, any face order) and
// the messages prepareMesh itself writes for the same meshes.
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

using Catch::Matchers::Contains;

namespace {

/// The message prepareMesh throws for `mesh` (the CLI's check), without the source name it puts first.
std::string prepareMeshMessage(buoyancy::TriangleMesh mesh) {
    try {
        buoyancy::prepareMesh(mesh, "mesh");
    } catch (const buoyancy::MeshError& e) {
        return e.what();
    }
    return "";
}

/// A 1 m box written by hand: 8 corners, 12 outward triangles, no duplicate vertices.
buoyancy::TriangleMesh unitBox() {
    buoyancy::TriangleMesh m;
    for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {1, 3, 7, 5}, {0, 4, 6, 2}};
    for (const auto& q : quads) {
        m.triangles.push_back({q[0], q[1], q[2]});
        m.triangles.push_back({q[0], q[2], q[3]});
    }
    return m;
}

}  // namespace

TEST_CASE("btBuoyancyShape::create: a closed box is accepted, with its volume", "[bullet][shape]") {
    const buoyancy::TriangleMesh box = unitBox();
    REQUIRE(prepareMeshMessage(box).empty());  // the hand-written box is closed and outward
    const auto shape = btBuoyancyShape::create(box);
    CHECK(shape->getVolume() == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("btBuoyancyShape::create: open, inside-out and flat meshes are refused with prepareMesh's message",
          "[bullet][shape]") {
    SECTION("a box with one face missing (any face: the volume was 0.5 or 1.0 depending on which)") {
        for (int face = 0; face < 6; ++face) {
            buoyancy::TriangleMesh open = unitBox();
            open.triangles.erase(open.triangles.begin() + 2 * face, open.triangles.begin() + 2 * face + 2);
            const std::string expected = prepareMeshMessage(open);
            REQUIRE_THAT(expected, Contains("open surface"));
            try {
                btBuoyancyShape::create(open);
                FAIL("face " << face << " missing: accepted");
            } catch (const std::invalid_argument& e) {
                CHECK(std::string(e.what()) == expected);
            }
        }
    }
    SECTION("a box with one triangle flipped (not consistently oriented)") {
        buoyancy::TriangleMesh flipped = unitBox();
        std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
        const std::string expected = prepareMeshMessage(flipped);
        REQUIRE_FALSE(expected.empty());
        CHECK_THROWS_WITH(btBuoyancyShape::create(flipped), expected);
    }
    SECTION("a single flat sheet (two triangles)") {
        buoyancy::TriangleMesh sheet;
        sheet.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
        sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
        const std::string expected = prepareMeshMessage(sheet);
        REQUIRE_FALSE(expected.empty());
        CHECK_THROWS_AS(btBuoyancyShape::create(sheet), std::invalid_argument);
        CHECK_THROWS_WITH(btBuoyancyShape::create(sheet), expected);
    }
}

TEST_CASE("btBuoyancyShape::create: an inside-out closed box is turned outward, as the command line does",
          "[bullet][shape]") {
    buoyancy::TriangleMesh inside = unitBox();
    for (auto& t : inside.triangles) std::swap(t[1], t[2]);
    const auto shape = btBuoyancyShape::create(inside);
    CHECK(shape->getVolume() == Approx(1.0).epsilon(1e-12));  // not −1
    CHECK_FALSE(shape->getMeshWarnings().empty());            // and it says so
}
