// The scene reader on a lone water object (what `buoyancy hydrostatics --water FILE.json` reads): the keys,
// defaults and checks of a scene's "water" object, with messages naming the keys from the object's top level.
#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"

#include <catch2/catch.hpp>

#include <string>

using buoyancy::cli::parseSceneWater;
using buoyancy::cli::UsageError;

TEST_CASE("parseSceneWater names the keys from the water object's top level", "[cli]") {
    const auto s = parseSceneWater(R"({"type": "gerstner", "height": 0.5, "density": 1025,
                                       "waves": [{"amplitude": 0.2, "wavelength": 30}]})",
                                   "w.json", ".", 9.81);
    CHECK(s.water.type == "gerstner");
    CHECK(s.waterHeight == 0.5);
    CHECK(s.waterDensity == 1025);
    REQUIRE(s.water.waves.size() == 1);
    CHECK(s.bodies.empty());
    CHECK_THROWS_WITH(parseSceneWater(R"({"type": "gerstner", "waves": [{"amplitude": 0.2}]})", "w.json", ".", 9.81),
                      "w.json: waves[0].wavelength: missing");
    CHECK_THROWS_AS(parseSceneWater(R"({"type": "flat"})", "w.json", ".", 0.0), UsageError);
    CHECK_THROWS_WITH(parseSceneWater(R"({"type": "fft"})", "w.json", ".", 9.81,
                                      [](const std::string& type) { return type == "fft" ? "not here" : ""; }),
                      "w.json: type: not here");
    // In a whole scene the same mistake still names the key from the scene's top level.
    CHECK_THROWS_WITH(buoyancy::cli::parseScene(R"({"water": {"type": "gerstner", "waves": [{"amplitude": 0.2}]},
                                                    "bodies": []})",
                                                "scene.json", "."),
                      "scene.json: water.waves[0].wavelength: missing");
}
