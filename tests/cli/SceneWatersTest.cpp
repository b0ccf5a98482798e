// The scene key "waters" (docs/scene-format.md): bounded water bodies, each a water object with a box region.
// Every mistake is a usage error (exit 2) naming its key; overlapping regions name both entries.
#include "cli/RunCommand.h"
#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

using buoyancy::cli::parseScene;
using buoyancy::cli::UsageError;
using Catch::Matchers::Contains;

namespace {

const std::string kBody = R"("bodies": [{"shape": {"type": "box", "size": [1, 0.5, 1]}, "density": 500}])";

/// A scene of `waters` (the JSON array's text) and one crate.
buoyancy::cli::Scene parseWaters(const std::string& waters) {
    return parseScene("{\"waters\": " + waters + ", " + kBody + "}", "s.json", ".");
}

const std::string kPool = R"({"type": "flat", "height": 0, "region": {"box": {"min": [-5, -3, -2], "max": [-1, 0, 2]}}})";

}  // namespace

TEST_CASE("scene waters: each entry's surface, level, density and box are read", "[cli][waters]") {
    const auto s = parseWaters("[" + kPool + R"(, {"type": "gerstner", "height": 1, "density": 1025,
        "waves": [{"amplitude": 0.1, "wavelength": 8}], "region": {"box": {"min": [1, -2, -2], "max": [5, 1.5, 2]}}}])");
    REQUIRE(s.waters.size() == 2);
    CHECK(s.waters[0].water.type == "flat");
    CHECK(s.waters[0].density == 1000);
    CHECK(s.waters[0].regionMin == Eigen::Vector3d(-5, -3, -2));
    CHECK(s.waters[0].regionMax == Eigen::Vector3d(-1, 0, 2));
    CHECK(s.waters[1].water.type == "gerstner");
    CHECK(s.waters[1].height == 1);
    CHECK(s.waters[1].density == 1025);
    CHECK(s.waters[1].water.waves.size() == 1);
    // The world gets no unbounded water and one water body per entry, named after it.
    auto world = buoyancy::cli::buildSceneWorld(s, 10.0);
    CHECK(world->buoyancy->getWater() == nullptr);
    REQUIRE(world->buoyancy->getWaterBodies().size() == 2);
    CHECK(world->buoyancy->getWaterBodies()[1].name == "waters[1]");
    CHECK(world->buoyancy->getWaterBodies()[1].fluidDensity == 1025);
    // Without "waters", the single water as before.
    CHECK(parseScene("{" + kBody + "}", "s.json", ".").waters.empty());
}

TEST_CASE("scene waters: bad entries name their key", "[cli][waters]") {
    CHECK_THROWS_WITH(parseScene(R"({"water": {"type": "flat"}, "waters": [)" + kPool + "], " + kBody + "}", "s.json", "."),
                      Contains("s.json: water, waters: give either"));
    CHECK_THROWS_WITH(parseWaters("[" + kPool + R"(, {"type": "flat", "height": 1,
        "region": {"box": {"min": [1, -2, -2], "max": [5, -2, 2]}}}])"),
                      Contains("s.json: waters[1].region.box.max: must be greater than min on every axis (y:"));
    CHECK_THROWS_WITH(parseWaters("[" + kPool + R"(, {"type": "flat", "region": {"box": {"min": [1, -2, -2], "max": [5, 1e999, 2]}}}])"),
                      Contains("s.json: invalid JSON"));  // 1e999 is not a JSON number a double holds
    CHECK_THROWS_WITH(parseWaters("[" + kPool + R"(, {"type": "flat", "region": {"box": {"min": [1, -2, -2], "max": [5, "a", 2]}}}])"),
                      Contains("s.json: waters[1].region.box.max[1]: expected a number"));
    CHECK_THROWS_WITH(parseWaters(R"([{"type": "flat", "height": 0}])"), Contains("s.json: waters[0].region: missing"));
    CHECK_THROWS_WITH(parseWaters(R"([{"type": "flat", "region": {"sphere": 1}}])"),
                      Contains("s.json: waters[0].region.sphere: unknown key"));
    CHECK_THROWS_WITH(parseWaters(R"([{"type": "flat", "region": {"box": {"min": [0, 0, 0]}}}])"),
                      Contains("s.json: waters[0].region.box.max: missing"));
    CHECK_THROWS_WITH(parseWaters(R"([{"type": "flat", "height": "high", "region": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}}])"),
                      Contains("s.json: waters[0].height: expected a number"));
    CHECK_THROWS_WITH(parseWaters(R"([{"type": "interactive", "region": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}}])"),
                      Contains("s.json: waters[0].type: interactive water is not supported"));
    CHECK_THROWS_WITH(parseWaters(R"([{"type": "flat", "frame": {"up": [0, 1, 0]}, "region": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}}])"),
                      Contains("s.json: waters[0].frame: not allowed"));
    CHECK_THROWS_WITH(parseWaters("[]"), Contains("s.json: waters: empty"));
    CHECK_THROWS_WITH(parseWaters("{}"), Contains("s.json: waters: expected an array"));
}

TEST_CASE("scene waters: overlapping regions exit 2 with a message naming both entries", "[cli][waters]") {
    const std::string overlapping = "[" + kPool + R"(, {"type": "flat", "height": 1,
        "region": {"box": {"min": [-2, -2, -2], "max": [5, 1, 2]}}}])";
    CHECK_THROWS_WITH(parseWaters(overlapping), Contains("s.json: waters[1].region: the box") && Contains("overlaps waters[0].region"));
    // Touching boxes (a shared face at x = -1) are two water bodies side by side.
    CHECK(parseWaters("[" + kPool + R"(, {"type": "flat", "height": 1,
        "region": {"box": {"min": [-1, -2, -2], "max": [5, 1, 2]}}}])").waters.size() == 2);
    // Through the runner: exit 2.
    const auto dir = std::filesystem::temp_directory_path() / ("buoyancy_waters_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream f(dir / "overlap.json");
        f << "{\"waters\": " << overlapping << ", " << kBody << "}";
    }
    CHECK(buoyancy::cli::runSceneCommand((dir / "overlap.json").string(), (dir / "out").string(), 0.0) == 2);
    std::filesystem::remove_all(dir);
}
