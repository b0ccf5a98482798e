// Scene keys "ground.normal" (a sloped beach) and "camera" (the view of the pictures and the browser),
// and the browser's command line. Bad values are errors naming the key (docs/bad-input.md).

#include "browser/BrowserOptions.h"
#include "example_scenes/ExampleEntries.h"
#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

TEST_CASE("browser command line: --help, and --scene by name or by number 1..N", "[examples]") {
    std::vector<std::string> a = {"buoyancy_browser", "--help"};
    std::vector<char*> argv;
    for (auto& s : a) argv.push_back(s.data());
    const browser::BrowserOptions help = browser::parseBrowserOptions(int(argv.size()), argv.data());
    CHECK(help.help);
    CHECK_THAT(std::string(browser::browserUsage()), Contains("--scene NAME|NUMBER"));

    // The scenes in table order, counted here from the table itself (rows with a create function).
    std::vector<int> sceneRows;
    for (int i = 0; i < examples::exampleEntryCount(); ++i)
        if (examples::exampleEntry(i).createFunc) sceneRows.push_back(i);
    const int n = int(sceneRows.size());
    REQUIRE(n == examples::exampleSceneCount());
    REQUIRE(n >= 2);
    const std::string range = "1.." + std::to_string(n);
    std::string error;
    CHECK(examples::findExampleScene("1", error) == sceneRows.front());
    CHECK(examples::findExampleScene(std::to_string(n), error) == sceneRows.back());
    CHECK(examples::findExampleScene("Crate splash", error) ==
          int(examples::findExampleEntry("Crate splash") - &examples::exampleEntry(0)));
    for (const std::string bad : {std::string("0"), std::to_string(n + 1), std::string("99999")}) {
        error.clear();
        CHECK(examples::findExampleScene(bad, error) == -1);
        CHECK_THAT(error, Contains("scenes are numbered " + range));
    }
    // A group heading is not a scene.
    int heading = -1;
    for (int i = 0; i < examples::exampleEntryCount() && heading < 0; ++i)
        if (!examples::exampleEntry(i).createFunc) heading = i;
    REQUIRE(heading >= 0);
    error.clear();
    CHECK(examples::findExampleScene(examples::exampleEntry(heading).name, error) == -1);
    CHECK_THAT(error, Contains("is a group heading, not a scene"));
    CHECK_THAT(error, Contains(range));
    error.clear();
    CHECK(examples::findExampleScene("nope", error) == -1);
    CHECK_THAT(error, Contains("no scene \"nope\""));
    CHECK_THAT(error, Contains(range));
}

#ifdef BUOYANCY_BROWSER_EXE
TEST_CASE("buoyancy_browser --help and --list exit 0 without a display, a bad --scene exits 2 naming the range", "[examples]") {
    const std::string out = (std::filesystem::temp_directory_path() / "buoyancy_browser_help.txt").string();
    auto run = [&](const std::string& args) {
        const int status = std::system((std::string("DISPLAY= ") + BUOYANCY_BROWSER_EXE + " " + args + " >" + out + " 2>&1").c_str());
        std::ifstream f(out);
        std::stringstream s;
        s << f.rdbuf();
        return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, s.str());
    };
    const auto help = run("--help");
    CHECK(help.first == 0);
    CHECK_THAT(help.second, Contains("usage: buoyancy_browser"));
    const auto list = run("--list");
    CHECK(list.first == 0);
    CHECK_THAT(list.second, Contains("1\t"));
    const auto zero = run("--scene 0");
    CHECK(zero.first == 2);
    CHECK_THAT(zero.second, Contains("error: --scene: no scene number 0: scenes are numbered 1.." +
                                     std::to_string(examples::exampleSceneCount())));
}
#endif
