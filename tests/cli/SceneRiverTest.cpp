// The water type "river" (docs/scene-format.md): a flat water whose current follows a centreline, usable as the scene's
// "water" and in a "waters" entry. Its keys are read into btRiverSettings and the world gets a btRiverSurface; every
// mistake is a usage error naming the file and the key.
#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"

#include <BulletBuoyancy/water/btRiverSurface.h>

#include <catch2/catch.hpp>

#include <string>

using buoyancy::cli::parseScene;
using Catch::Matchers::Equals;

namespace {

const std::string kBody = R"("bodies": [{"shape": {"type": "box", "size": [1, 0.5, 1]}, "density": 500}])";

/// A scene whose "water" is the object `water` (its text) and one crate.
buoyancy::cli::Scene waterScene(const std::string& water) {
    return parseScene("{\"water\": " + water + ", " + kBody + "}", "s.json", ".");
}

/// A river object with `extra` keys appended (text starting with ", ") and the given centreline.
std::string river(const std::string& extra = "", const std::string& centreline = "[[-10, 0], [0, 0], [10, 5]]") {
    return R"({"type": "river", "height": 0.5, "centreline": )" + centreline + R"(, "width": 6, "speed": 1.2)" + extra +
           "}";
}

}  // namespace

TEST_CASE("scene river: the keys are read and the world's water is the river", "[cli][river]") {
    const auto s = waterScene(river(", \"density\": 1010"));
    CHECK(s.water.type == "river");
    CHECK(s.waterHeight == 0.5);
    CHECK(s.waterDensity == 1010);
    REQUIRE(s.water.river.centreline.size() == 3);
    CHECK(s.water.river.centreline[2].x == 10);
    CHECK(s.water.river.centreline[2].z == 5);
    CHECK(s.water.river.width == 6);
    CHECK(s.water.river.surfaceSpeed == 1.2);
    auto world = buoyancy::cli::buildSceneWorld(s, 1.0);
    const auto* surface = dynamic_cast<const btRiverSurface*>(world->buoyancy->getWater());
    REQUIRE(surface != nullptr);
    CHECK(surface->level() == 0.5);
    double x = -5, y = 0, z = 0, vx = 0, vy = 0, vz = 0;
    surface->velocities(&x, &y, &z, 1, 0.0, &vx, &vy, &vz);
    CHECK(vx == Approx(1.2).epsilon(1e-12));  // on the centreline of the first segment
    CHECK(vz == Approx(0.0).margin(1e-12));
}

TEST_CASE("scene river: a waters entry can be a river with its own level and density", "[cli][river][waters]") {
    const auto s = parseScene(R"({"waters": [{"type": "flat", "height": 2, "region": {"box": {"min": [-5, -1, -5], "max": [5, 3, 5]}}},
        {"type": "river", "height": 0, "density": 1000, "centreline": [[10, 0], [40, 0]], "width": 8, "speed": 1.5,
         "region": {"box": {"min": [5, -2, -4], "max": [40, 1, 4]}}}], )" + kBody + "}",
                              "s.json", ".");
    REQUIRE(s.waters.size() == 2);
    CHECK(s.waters[1].water.type == "river");
    CHECK(s.waters[1].height == 0);
    auto world = buoyancy::cli::buildSceneWorld(s, 1.0);
    REQUIRE(world->buoyancy->getWaterBodies().size() == 2);
    const auto* surface = dynamic_cast<const btRiverSurface*>(world->buoyancy->getWaterBodies()[1].surface);
    REQUIRE(surface != nullptr);
    CHECK(surface->settings().width == 8);
    CHECK(surface->settings().surfaceSpeed == 1.5);
}

TEST_CASE("scene river: bad river keys name the file and the key", "[cli][river][bad-input]") {
    CHECK_THROWS_AS(waterScene(river("", "[[0, 0]]")), buoyancy::cli::UsageError);
    CHECK_THROWS_WITH(waterScene(river("", "[[0, 0]]")),
                      Equals("s.json: water.centreline: expected an array of at least 2 [x, z] points, m, upstream first"));
    CHECK_THROWS_WITH(waterScene(river("", "[[0, 0], [5, 1], [5, 1]]")),
                      Equals("s.json: water.centreline[2]: repeats centreline[1]: consecutive points must be at least "
                             "1e-6 m apart"));
    CHECK_THROWS_WITH(waterScene(river("", "[[0, 0], [5, 1, 2]]")),
                      Equals("s.json: water.centreline[1]: expected an array of 2 numbers"));
    CHECK_THROWS_WITH(waterScene(river("", "{\"x\": 1}")),
                      Equals("s.json: water.centreline: expected an array of at least 2 [x, z] points, m, upstream first"));
    CHECK_THROWS_WITH(waterScene(R"({"type": "river", "centreline": [[0, 0], [1, 0]], "speed": 1})"),
                      Equals("s.json: water.width: missing (the channel's width, m, > 0)"));
    CHECK_THROWS_WITH(waterScene(R"({"type": "river", "centreline": [[0, 0], [1, 0]], "width": 0, "speed": 1})"),
                      Equals("s.json: water.width: value 0 out of range (0, 1e+06]"));
    CHECK_THROWS_WITH(waterScene(R"({"type": "river", "centreline": [[0, 0], [1, 0]], "width": -3, "speed": 1})"),
                      Equals("s.json: water.width: value -3 out of range (0, 1e+06]"));
    CHECK_THROWS_WITH(waterScene(R"({"type": "river", "centreline": [[0, 0], [1, 0]], "width": 4})"),
                      Equals("s.json: water.speed: missing (the surface speed on the centreline, m/s, >= 0)"));
    CHECK_THROWS_WITH(waterScene(R"({"type": "river", "centreline": [[0, 0], [1, 0]], "width": 4, "speed": -1})"),
                      Equals("s.json: water.speed: must be >= 0 m/s (the current runs from the first centreline point "
                             "to the last: list the points the other way round to reverse it)"));
    CHECK_THROWS_WITH(waterScene(R"({"type": "river", "centreline": [[0, 0], [1, 0]], "width": 4, "speed": "fast"})"),
                      Equals("s.json: water.speed: expected a number"));
    // JSON has no NaN: a number too large for a double is refused by the parser.
    CHECK_THROWS_WITH(waterScene(R"({"type": "river", "centreline": [[0, 0], [1, 0]], "width": 4, "speed": 1e400})"),
                      Equals("s.json: invalid JSON: [json.exception.out_of_range.406] number overflow parsing '1e400'"));
    CHECK_THROWS_WITH(waterScene(river(", \"current\": [1, 0]")), Equals("s.json: water.current: unknown key"));
    CHECK_THROWS_WITH(waterScene(river(", \"centerline\": [[0, 0], [1, 0]]")),
                      Equals("s.json: water.centerline: unknown key"));
    // In a "waters" entry the keys are named from the entry.
    CHECK_THROWS_WITH(parseScene(R"({"waters": [{"type": "river", "centreline": [[0, 0], [0, 0]], "width": 4, "speed": 1,
        "region": {"box": {"min": [-5, -1, -5], "max": [5, 3, 5]}}}], )" + kBody + "}",
                                 "s.json", "."),
                      Equals("s.json: waters[0].centreline[1]: repeats centreline[0]: consecutive points must be at "
                             "least 1e-6 m apart"));
    CHECK_THROWS_WITH(parseScene(R"({"waters": [{"type": "river", "centreline": [[0, 0], [1, 0]], "speed": 1,
        "region": {"box": {"min": [-5, -1, -5], "max": [5, 3, 5]}}}], )" + kBody + "}",
                                 "s.json", "."),
                      Equals("s.json: waters[0].width: missing (the channel's width, m, > 0)"));
}
