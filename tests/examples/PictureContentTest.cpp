// What the pictures show, measured: every frame carries its time label; the automatic camera makes a small body
// a visible share of the picture; the wet hull, the dry hull and the water are clearly different colours, with the
// waterline drawn between them; the frames the ball-stability strip shows are frames where the two balls' tilts
// differ (read from the scene's state, not from the picture); force arrows show through the bodies they start in.
// Expected values come from the scene (its poses and the camera it gives) or from thresholds stated here. Pictures
// come from `buoyancy run --png` in a child process (the tests' floating-point traps stay out of Mesa's llvmpipe).

#include "PictureChecks.h"

#include "render/FrameLabel.h"
#include "render/SceneFrame.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace buoyancy;
using buoyancy::test::Picture;

namespace {

const std::string kSource = BUOYANCY_SOURCE_DIR;
const std::string kScenes = kSource + "/bullet_examples/scenes/";

fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("bb_content_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

int shell(const std::string& cmd) {
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/// The output-frame numbers scripts/pictures.sh puts into the strip of `sceneName` (its row: name, duration, frames).
std::vector<int> stripFrames(const std::string& sceneName) {
    std::ifstream in(kSource + "/scripts/pictures.sh");
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream row(line);
        std::string first, name;
        row >> first;
        if (first != "\"" + sceneName && first != "\"" + sceneName + "\"") continue;
        double duration = 0;
        row >> duration;
        std::vector<int> frames;
        int k = 0;
        while (row >> k) frames.push_back(k);
        return frames;
    }
    return {};
}

/// Angle between the body's mesh +y axis and the world's +y, degrees.
double tiltDeg(const btBuoyantBody& b) {
    const btMatrix3x3 m = b.getMeshWorldTransform().getBasis();
    return std::acos(std::clamp(double(m[1][1]), -1.0, 1.0)) * 180.0 / M_PI;
}

/// Pixel (column, row; top-left origin) where the world point p appears through `cam` in a width × height picture.
Eigen::Vector2d project(const render::RenderCamera& cam, const Eigen::Vector3f& p, int width, int height) {
    const Eigen::Vector4f clip = cam.projection(float(width) / float(height)) * cam.view() * p.homogeneous();
    const Eigen::Vector3f ndc = clip.head<3>() / clip.w();
    return {(0.5 * double(ndc.x()) + 0.5) * width, (0.5 - 0.5 * double(ndc.y())) * height};
}

double distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm(); }

}  // namespace

TEST_CASE("time labels read t = seconds with at least one decimal", "[examples]") {
    CHECK(render::timeLabel(0.0) == "t = 0.0 s");
    CHECK(render::timeLabel(-1e-12) == "t = 0.0 s");
    CHECK(render::timeLabel(2.5) == "t = 2.5 s");
    CHECK(render::timeLabel(0.05) == "t = 0.05 s");
    CHECK(render::timeLabel(12.0) == "t = 12.0 s");
    CHECK(render::timeLabel(0.1 + 0.2) == "t = 0.3 s");
}

TEST_CASE("a stamped label fills its box with the box colour and the text colour, nothing outside", "[examples]") {
    const int w = 200, h = 60;
    std::vector<std::uint8_t> rgba(std::size_t(w) * h * 4, 100);
    render::LabelStyle style;
    const render::LabelBox box = render::stampLabel(rgba, w, h, "t = 10.25 s", style);
    CHECK(box.width == render::labelBox("t = 10.25 s", style).width);
    int text = 0, boxColour = 0, outsideChanged = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::uint8_t* p = &rgba[4 * (std::size_t(y) * w + x)];
            const bool inside = x >= box.left && x < box.left + box.width && y >= box.top && y < box.top + box.height;
            if (!inside) {
                outsideChanged += p[0] != 100;
                continue;
            }
            text += p[0] == style.text[0] && p[1] == style.text[1] && p[2] == style.text[2];
            boxColour += p[0] == style.box[0] && p[1] == style.box[1] && p[2] == style.box[2];
        }
    CHECK(outsideChanged == 0);
    CHECK(text + boxColour == box.width * box.height);
    // 9 drawn glyphs of 5×7 dots, each glyph at least 7 dots, 2×2 pixels a dot.
    CHECK(text >= 9 * 7 * 4);
    // A label past the picture's edge is clipped, not written out of bounds.
    render::LabelStyle off = style;
    off.left = w - 10;
    off.top = h - 5;
    render::stampLabel(rgba, w, h, "t = 1.0 s", off);
    CHECK(rgba.size() == std::size_t(w) * h * 4);
}

TEST_CASE("the scene's camera block overrides the automatic framing field by field", "[examples]") {
    const std::string scene = R"({"water": {"type": "flat", "height": 0},
        "bodies": [{"shape": {"type": "sphere", "radius": 0.2}, "density": 500}]})";
    const cli::Scene automatic = cli::parseScene(scene, "auto.json", ".");
    auto world = cli::buildSceneWorld(automatic, 10.0);
    const render::RenderCamera cam = render::frameSceneCamera(automatic, *world);
    // A 0.2 m ball fills about half the picture's height: the eye is within 3 m (no fixed minimum distance).
    CHECK(cam.distance < 3.f);
    CHECK(cam.distance > 0.4f);

    cli::Scene given = automatic;
    given.camera.distance = 7.5;
    given.camera.yaw = 10;
    const render::RenderCamera override = render::frameSceneCamera(given, *world);
    CHECK(override.distance == 7.5f);
    CHECK(override.yawDeg == 10.f);
    CHECK(override.pitchDeg == cam.pitchDeg);
    CHECK(override.target.isApprox(cam.target));
}

TEST_CASE("the ball-stability strip shows frames where the uniform ball has rolled over and the ballasted one has not",
          "[examples]") {
    const std::vector<int> frames = stripFrames("ball_stability");
    REQUIRE(frames.size() == 3);
    const cli::Scene scene = cli::loadSceneFile(kScenes + "ball_stability.json");
    REQUIRE(scene.bodies.size() == 2);
    REQUIRE(scene.bodies[0].name == "uniform");
    auto world = cli::buildSceneWorld(scene, 10.0);
    std::vector<double> uniform, ballasted;
    for (int k : frames) {
        const double t = k * scene.outputInterval;
        while (world->time() < t - 1e-9) cli::stepSceneFrame(scene, *world);
        uniform.push_back(tiltDeg(*world->bodies[0]));
        ballasted.push_back(tiltDeg(*world->bodies[1]));
    }
    std::ostringstream tilts;
    for (std::size_t i = 0; i < frames.size(); ++i)
        tilts << "frame " << frames[i] << ": uniform " << uniform[i] << " deg, ballasted " << ballasted[i] << " deg; ";
    INFO(tilts.str());
    // The last picture: the uniform ball past lying on its side, the ballasted one near upright, 60° apart at least.
    CHECK(uniform.back() > 90.0);
    CHECK(ballasted.back() < 20.0);
    CHECK(uniform.back() - ballasted.back() > 60.0);
    // Across the strip the uniform ball turns further while the ballasted one rights itself.
    CHECK(uniform.back() > uniform.front());
    CHECK(ballasted.back() < ballasted.front());
}

#ifdef BUOYANCY_CLI_PATH
TEST_CASE("every picture of buoyancy run --png carries its time in a label", "[examples]") {
    const fs::path d = scratch("label");
    REQUIRE(shell(std::string(BUOYANCY_CLI_PATH) + " run " + kScenes + "heave_box.json --duration 0.02 --out " +
                  (d / "out").string() + " --png " + (d / "png").string() + " --size 240 135 2>/dev/null") == 0);
    // output_interval 0.01 s, frames of 4 × 1/240 s: pictures at the frame boundaries t = 0, 1/60, 2/60 s.
    for (const auto& [file, label] : {std::pair{"frame_00000.png", "t = 0.0 s"}, std::pair{"frame_00001.png", "t = 0.02 s"},
                                      std::pair{"frame_00002.png", "t = 0.03 s"}}) {
        Picture p;
        REQUIRE(p.load((d / "png" / file).string()));
        // The expected label: the same text stamped by the font onto a blank picture of the same size.
        std::vector<std::uint8_t> expected(std::size_t(p.width) * p.height * 4, 0);
        const render::LabelStyle style;
        const render::LabelBox box = render::stampLabel(expected, p.width, p.height, label, style);
        const Eigen::Vector3d text(style.text[0], style.text[1], style.text[2]);
        int textPixels = 0, mismatches = 0;
        for (int y = box.top; y < box.top + box.height; ++y)
            for (int x = box.left; x < box.left + box.width; ++x) {
                const std::uint8_t* e = &expected[4 * (std::size_t(y) * p.width + x)];
                const Eigen::Vector3d want(e[0], e[1], e[2]);
                mismatches += distance(p.at(x, y), want) > 0.5;
                textPixels += distance(p.at(x, y), text) < 0.5;
            }
        INFO(file << " (" << label << "): " << textPixels << " text pixels, " << mismatches << " pixels differ of "
                  << box.width * box.height);
        CHECK(mismatches == 0);
        // At least 7 dots of 2 × 2 pixels per drawn glyph.
        CHECK(textPixels >= 7 * 4 * int(std::count_if(label, label + std::strlen(label), [](char c) { return c != ' '; })));
    }
    fs::remove_all(d);
}

TEST_CASE("the automatic camera makes the plush bear at least 2 % of the picture", "[examples]") {
    const fs::path d = scratch("bear");
    REQUIRE(shell(std::string(BUOYANCY_CLI_PATH) + " run " + kScenes + "plush_toy.json --duration 0 --out " +
                  (d / "out").string() + " --png " + (d / "png").string() + " --size 320 180 2>/dev/null") == 0);
    Picture p;
    REQUIRE(p.load((d / "png" / "frame_00000.png").string()));
    // The bear is orange (the palette's first colour), wet or dry: red well above blue. The water, sand and sky are not.
    const int bear = p.countInBox(0, 0, p.width, p.height, [](const Eigen::Vector3d& c) { return c.x() > c.z() + 40 && c.x() > 60; });
    const double share = double(bear) / double(p.width * p.height);
    INFO("bear pixels " << bear << " = " << 100 * share << " % of the picture");
    CHECK(share >= 0.02);
    CHECK(share <= 0.5);  // and the picture still shows its surroundings
    fs::remove_all(d);
}

TEST_CASE("wet hull, dry hull and water are clearly different colours, with the waterline drawn between", "[examples]") {
    const fs::path d = scratch("wet");
    // A 2 × 1 × 2 m box of half the water's density floats with its centre at the waterline (draft 0.5 m).
    const std::string text = R"({"duration": 0, "water": {"type": "flat", "height": 0, "density": 1000},
        "bodies": [{"name": "box", "shape": {"type": "box", "size": [2, 1, 2]}, "density": 500, "position": [0, 0, 0]}]})";
    const fs::path sceneFile = d / "box.json";
    std::ofstream(sceneFile) << text;
    const int W = 320, H = 180;
    REQUIRE(shell(std::string(BUOYANCY_CLI_PATH) + " run " + sceneFile.string() + " --duration 0 --out " + (d / "out").string() +
                  " --png " + (d / "png").string() + " --size 320 180 2>/dev/null") == 0);
    Picture p;
    REQUIRE(p.load((d / "png" / "frame_00000.png").string()));
    const cli::Scene scene = cli::parseScene(text, "box.json", d.string());
    auto world = cli::buildSceneWorld(scene, 10.0);
    const render::RenderCamera cam = render::frameSceneCamera(scene, *world);
    REQUIRE(cam.eye().z() > 1.f);  // the +z face is seen
    // Points of the +z face (z = 1): dry 0.25 m above the water, wet 0.25 m below; open water 1.5 m beside the box.
    const Eigen::Vector2d dryAt = project(cam, {0.f, 0.25f, 1.001f}, W, H), wetAt = project(cam, {0.f, -0.25f, 1.001f}, W, H),
                          lineAt = project(cam, {0.f, 0.f, 1.001f}, W, H), waterAt = project(cam, {-2.5f, 0.f, 1.5f}, W, H);
    const Eigen::Vector3d dry = p.meanAround(dryAt, 1), wet = p.meanAround(wetAt, 1), water = p.meanAround(waterAt, 1);
    INFO("dry " << dry.transpose() << " at " << dryAt.transpose() << ", wet " << wet.transpose() << " at " << wetAt.transpose()
                << ", water " << water.transpose() << " at " << waterAt.transpose());
    INFO("wet-water " << distance(wet, water) << ", dry-wet " << distance(dry, wet) << ", dry-water " << distance(dry, water));
    // Euclidean distance in 8-bit RGB (0..441): 60 is a difference seen at a glance.
    CHECK(distance(wet, water) > 60);
    CHECK(distance(dry, wet) > 60);
    CHECK(distance(dry, water) > 60);
    // The waterline: a light pixel (every channel ≥ 200) within 3 rows of where the face meets the water.
    bool line = false;
    for (int dy = -3; dy <= 3; ++dy) {
        const Eigen::Vector3d c = p.at(int(lineAt.x()), int(lineAt.y()) + dy);
        line = line || c.minCoeff() >= 200;
    }
    CHECK(line);
    fs::remove_all(d);
}
TEST_CASE("force arrows are drawn on top: the weight arrow shows inside the ball it starts in", "[examples]") {
    const fs::path d = scratch("arrow");
    const int W = 320, H = 180;
    REQUIRE(shell(std::string(BUOYANCY_CLI_PATH) + " run " + kScenes + "ball_stability.json --duration 0 --out " +
                  (d / "out").string() + " --png " + (d / "png").string() + " --size 320 180 2>/dev/null") == 0);
    Picture p;
    REQUIRE(p.load((d / "png" / "frame_00000.png").string()));
    const cli::Scene scene = cli::loadSceneFile(kScenes + "ball_stability.json");
    auto world = cli::buildSceneWorld(scene, 10.0);
    const render::RenderCamera cam = render::frameSceneCamera(scene, *world);
    // The weight arrow of each ball runs down from its centre of mass; 0.15 m below it the arrow is still inside
    // the ball (radius 0.5 m), so only an arrow drawn on top shows there. Arrow red: red over twice green and blue
    // (the balls are orange, yellow and white; the water blue).
    int found = 0;
    std::ostringstream seen;
    for (const auto& body : world->bodies) {
        const btVector3 com = body->getRigidBody()->getCenterOfMassPosition();
        const Eigen::Vector3f inside(float(com.x()), float(com.y()) - 0.15f, float(com.z()));
        const btVector3 ballCentre = body->getMeshWorldTransform().getOrigin();  // the sphere's mesh is centred
        REQUIRE(double((inside - Eigen::Vector3f(float(ballCentre.x()), float(ballCentre.y()), float(ballCentre.z()))).norm()) < 0.5);
        const Eigen::Vector2d at = project(cam, inside, W, H);
        bool red = false;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const Eigen::Vector3d c = p.at(int(at.x()) + dx, int(at.y()) + dy);
                red = red || (c.x() > 2 * c.y() && c.x() > 2 * c.z() && c.x() > 80);
            }
        seen << p.at(int(at.x()), int(at.y())).transpose() << " at " << at.transpose() << "; ";
        found += red ? 1 : 0;
    }
    INFO(seen.str());
    CHECK(found == 2);
    fs::remove_all(d);
}
#endif
