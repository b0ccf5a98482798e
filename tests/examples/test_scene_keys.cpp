// Issue 8 scene keys: "ground.normal" (a sloped beach) and "camera" (the view of the pictures and the browser),
// and the browser's command line. Bad values are errors naming the key (docs/bad-input.md).

#include "browser/BrowserOptions.h"
#include "cli/CliErrors.h"
#include "cli/SceneFile.h"
#include "cli/SceneWorld.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace buoyancy;
using Catch::Matchers::Contains;

namespace {
const std::string kBody = R"("bodies": [{"shape": {"type": "box", "size": [1, 1, 1]}, "density": 500}])";
cli::Scene parse(const std::string& extra) { return cli::parseScene("{" + extra + ", " + kBody + "}", "s.json", "."); }
}  // namespace

TEST_CASE("ground.normal slopes the floor through (0, height, 0)", "[examples]") {
    const cli::Scene s = parse(R"("ground": {"height": -2, "normal": [-1, 7, 0]})");
    REQUIRE(s.groundHeight);
    CHECK(s.groundNormal.norm() == Approx(1.0));
    CHECK(s.groundNormal.x() == Approx(-1 / std::sqrt(50.0)));
    // The world's plane n·p = d passes through (0, -2, 0): d = n_y · (−2); and through the point 1 m along x
    // where the slope 1/7 has risen by 1/7 m.
    auto w = cli::buildSceneWorld(s, 10.0);
    CHECK(w->groundOffset == Approx(s.groundNormal.y() * -2.0));
    const Eigen::Vector3d p(1.0, -2.0 + 1.0 / 7.0, 0.0);
    CHECK(w->groundNormal.dot(p) == Approx(w->groundOffset).margin(1e-12));
    CHECK(parse(R"("ground": {"height": 1})").groundNormal == Eigen::Vector3d::UnitY());  // default flat
}

TEST_CASE("bad ground.normal and camera values name their key", "[examples]") {
    CHECK_THROWS_WITH(parse(R"("ground": {"normal": [0, 0, 0]})"), Contains("s.json: ground.normal: zero vector"));
    CHECK_THROWS_WITH(parse(R"("ground": {"normal": [1, 0, 0]})"), Contains("ground.normal: must point up"));
    CHECK_THROWS_WITH(parse(R"("ground": {"normal": [1, 2]})"), Contains("ground.normal"));
    CHECK_THROWS_WITH(parse(R"("camera": {"pitch": 95})"), Contains("camera.pitch: value 95 out of range"));
    CHECK_THROWS_WITH(parse(R"("camera": {"distance": 0})"), Contains("camera.distance"));
    CHECK_THROWS_WITH(parse(R"("camera": {"zoom": 2})"), Contains("camera.zoom: unknown key"));
    CHECK_THROWS_WITH(parse(R"("camera": 3)"), Contains("camera: expected an object"));
    CHECK_THROWS_AS(parse(R"("camera": {"target": [0, "a", 0]})"), cli::UsageError);
}

TEST_CASE("camera keys are read as given", "[examples]") {
    const cli::Scene s = parse(R"("camera": {"target": [1, 2, 3], "distance": 7, "yaw": -30, "pitch": 15})");
    REQUIRE(s.camera.target);
    CHECK(*s.camera.target == Eigen::Vector3d(1, 2, 3));
    CHECK(*s.camera.distance == 7);
    CHECK(*s.camera.yaw == -30);
    CHECK(*s.camera.pitch == 15);
    CHECK_FALSE(parse(R"("dt": 0.01)").camera.distance);
}

TEST_CASE("browser command line: values and errors", "[examples]") {
    auto parseArgs = [](std::vector<std::string> a) {
        std::vector<char*> argv;
        static std::string name = "buoyancy_browser";
        argv.push_back(name.data());
        for (auto& s : a) argv.push_back(s.data());
        return browser::parseBrowserOptions(int(argv.size()), argv.data());
    };
    const browser::BrowserOptions o = parseArgs({"--scene", "Crate splash", "--size", "640", "360", "--frames", "5",
                                                 "--screenshot", "x.png"});
    CHECK(o.scene == "Crate splash");
    CHECK(o.width == 640);
    CHECK(o.height == 360);
    CHECK(o.frames == 5);
    CHECK(o.screenshot == "x.png");
    CHECK_THROWS_WITH(parseArgs({"--frames", "0"}), Contains("--frames: expected an integer in [1, 1000000]"));
    CHECK_THROWS_WITH(parseArgs({"--size", "640"}), Contains("--size: missing value"));
    CHECK_THROWS_WITH(parseArgs({"--size", "64x", "360"}), Contains("--size"));
    CHECK_THROWS_WITH(parseArgs({"--fullscreen"}), Contains("unknown option \"--fullscreen\""));
}
