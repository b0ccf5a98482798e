// The offscreen renderer (`buoyancy run --png`) and the browser's screenshot under Xvfb produce
// pictures that show water and the body. Both run as child processes (the tests' floating-point traps and
// sanitizers stay out of Mesa's llvmpipe).

#include "PictureChecks.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using buoyancy::test::PictureStats;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("bb_examples_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

int shell(const std::string& cmd) {
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

const std::string kScenes = std::string(BUOYANCY_SOURCE_DIR) + "/bullet_examples/scenes/";

}  // namespace

#ifdef BUOYANCY_CLI_PATH
TEST_CASE("buoyancy run --png renders one picture per output interval showing water and the body", "[examples][slow]") {
    const fs::path d = scratch("png");
    const std::string cmd = std::string(BUOYANCY_CLI_PATH) + " run " + kScenes + "buoy_waves.json --duration 0.2 --out " +
                            (d / "out").string() + " --png " + (d / "png").string() + " --size 320 180 2>/dev/null";
    REQUIRE(shell(cmd) == 0);
    // t = 0, 0.1, 0.2 (output_interval 0.1): three pictures.
    CHECK(fs::exists(d / "png" / "frame_00000.png"));
    CHECK(fs::exists(d / "png" / "frame_00002.png"));
    CHECK_FALSE(fs::exists(d / "png" / "frame_00003.png"));
    PictureStats s;
    REQUIRE(buoyancy::test::analysePicture((d / "png" / "frame_00002.png").string(), s));
    CHECK(s.width == 320);
    CHECK(s.height == 180);
    INFO("water " << s.waterLower << ", warm " << s.warm << ", colours " << s.distinctColours);
    CHECK(s.waterLower > 0.5);   // the camera looks down at the sea: the lower half is mostly water
    CHECK(s.warm > 50);          // the orange buoy
    CHECK(s.distinctColours >= 8);
    fs::remove_all(d);
}

TEST_CASE("buoyancy run --size rejects bad sizes", "[examples]") {
    const fs::path d = scratch("size");
    const std::string base = std::string(BUOYANCY_CLI_PATH) + " run " + kScenes + "buoy_waves.json --duration 0 --out " +
                             (d / "out").string() + " --png " + (d / "png").string();
    CHECK(shell(base + " --size 8 8 2>/dev/null") == 2);
    CHECK(shell(base + " --size 320 2>/dev/null") == 2);
    fs::remove_all(d);
}
#endif

#if defined(BUOYANCY_BROWSER_PATH) && defined(BUOYANCY_XVFB_RUN)
TEST_CASE("the browser starts under Xvfb, renders a scene and its screenshot shows water and the body", "[examples][slow]") {
    const fs::path d = scratch("browser");
    const fs::path png = d / "shot.png";
    const std::string cmd = std::string(BUOYANCY_XVFB_RUN) + " -a -s '-screen 0 1280x720x24' " + BUOYANCY_BROWSER_PATH +
                            " --scene 'Buoy in waves' --size 1280 720 --frames 8 --screenshot " + png.string() +
                            " >/dev/null 2>&1";
    REQUIRE(shell(cmd) == 0);
    PictureStats s;
    REQUIRE(buoyancy::test::analysePicture(png.string(), s, 400));  // right of the panel: the 3D view
    CHECK(s.width == 1280);
    CHECK(s.height == 720);
    INFO("water " << s.waterLower << ", warm " << s.warm << ", colours " << s.distinctColours);
    CHECK(s.waterLower > 0.4);
    CHECK(s.warm > 30);
    CHECK(s.distinctColours >= 8);
    PictureStats all;
    REQUIRE(buoyancy::test::analysePicture(png.string(), all));
    CHECK(all.distinctColours > s.distinctColours);  // the panel adds its own colours (text, buttons)

    // The panel takes what it needs: the box around its dark-grey background (every channel below 48, within 10
    // of each other; the scene has no such colour) covers at most 15 % of a 1280 × 720 window.
    buoyancy::test::Picture p;
    REQUIRE(p.load(png.string()));
    int left = p.width, top = p.height, right = -1, bottom = -1;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) {
            const Eigen::Vector3d c = p.at(x, y);
            if (c.maxCoeff() < 48 && c.maxCoeff() - c.minCoeff() <= 10) {
                left = std::min(left, x);
                right = std::max(right, x);
                top = std::min(top, y);
                bottom = std::max(bottom, y);
            }
        }
    REQUIRE(right >= left);
    const double share = double(right - left + 1) * double(bottom - top + 1) / double(p.width * p.height);
    INFO("panel box x " << left << ".." << right << ", y " << top << ".." << bottom << ": " << 100 * share << " % of the window");
    CHECK(share <= 0.15);
    CHECK(right < 400);  // the 3D view checked above starts right of it
    fs::remove_all(d);
}
#endif
