// End-to-end tests of `buoyancy hydrostatics --water FILE.json [--time T]`: the mesh in the water a scene file
// describes, against closed forms; the flags it refuses and the water files it rejects.
#include "CliRunner.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

using buoyancy_test::runCli;
using buoyancy_test::scratchDir;
using buoyancy_test::writeBoxObj;
using Catch::Matchers::Contains;

namespace {

nlohmann::json runJson(const std::vector<std::string>& args) {
    const auto r = runCli(args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
}

void writeJson(const std::string& path, const nlohmann::json& j) { std::ofstream(path) << j.dump(2) << '\n'; }

/// True when `text` names the flag `flag` itself (not only a longer flag it begins, as --water in --water-height).
bool namesFlag(const std::string& text, const std::string& flag) {
    for (std::size_t at = text.find(flag); at != std::string::npos; at = text.find(flag, at + 1)) {
        const std::size_t end = at + flag.size();
        if (end == text.size() || !(std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-'))
            return true;
    }
    return false;
}

}  // namespace

TEST_CASE("hydrostatics --water: a box in a single Airy wave matches the closed form at each --time", "[cli]") {
    // A 2 x 1 x 1 m box, x in [x0, x1] after the translation, bottom y_b = -0.5, top +0.5, in one sine wave
    // (Gerstner, steepness 0) travelling along +x, crests along z:
    //   y = a cos(k x - w t),  k = 2 pi / lambda,  w = sqrt(g k)  (btGerstnerWaterSurface.h, deep water).
    // With |a| < 0.5 the bottom is wet and the top dry everywhere, so the submerged volume is the water column
    // over the bottom:  V = L_z [ (a/k) (sin(k x1 - w t) - sin(k x0 - w t)) - y_b (x1 - x0) ].
    // The box is off centre so that V depends on the sign of w t, not only on cos(w t).
    const std::string dir = scratchDir("airy");
    const std::string obj = dir + "/box.obj", water = dir + "/airy.json";
    writeBoxObj(obj, 2.0, 1.0, 1.0);
    const double a = 0.15, lambda = 20.0, g = 9.81, shiftX = 1.3;
    writeJson(water, {{"type", "gerstner"},
                      {"height", 0},
                      {"density", 1000},
                      {"waves", {{{"amplitude", a}, {"wavelength", lambda}, {"direction", {1, 0}}, {"steepness", 0},
                                  {"phase", 0}}}}});
    const double k = 2 * M_PI / lambda, w = std::sqrt(g * k);
    const double x0 = -1 + shiftX, x1 = 1 + shiftX, yBottom = -0.5, lengthZ = 1.0;
    for (const double t : {0.0, 0.5, 1.0, 2.5}) {
        const double expected =
            lengthZ * ((a / k) * (std::sin(k * x1 - w * t) - std::sin(k * x0 - w * t)) - yBottom * (x1 - x0));
        const auto j = runJson({"hydrostatics", obj, "--translate", std::to_string(shiftX), "0", "0", "--water", water,
                                "--time", std::to_string(t), "--json"});
        INFO("t = " << t << " s, closed form V = " << expected << " m^3");
        // 0.1 % of the box's volume: the bar of the exact-mesh default on smooth waves (design.md 2.5).
        CHECK(std::abs(j["submerged"]["volume"].get<double>() - expected) <= 1e-3 * 2.0);
        CHECK(j["submerged"]["force"][1].get<double>() ==
              Approx(1000 * g * j["submerged"]["volume"].get<double>()).epsilon(0.02));
        CHECK(j["water"]["type"] == "gerstner");
        CHECK(j["water"]["file"] == water);
        CHECK(j["water"]["time"].get<double>() == Approx(t).margin(1e-12));
        CHECK(j["water"]["density"].get<double>() == 1000.0);
    }
    // The table names the water and its time.
    const auto r = runCli({"hydrostatics", obj, "--water", water, "--time", "0.5"});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("gerstner from " + water + " at t = 0.5 s"));
}

TEST_CASE("hydrostatics --water: a flat water file gives the result of --water-height and --water-density", "[cli]") {
    const std::string dir = scratchDir("flat_file");
    const std::string obj = dir + "/box.obj", water = dir + "/flat.json";
    writeBoxObj(obj, 2.0, 1.0, 1.0);
    writeJson(water, {{"type", "flat"}, {"height", 0.25}, {"density", 1025}});
    for (const char* method : {"default", "exact-coverage"}) {
        SECTION(method) {
            const std::vector<std::string> pose = {"--rotate", "1", "0", "0", "10", "--translate", "0", "0.1", "0"};
            auto fromFile = pose, fromFlags = pose;
            fromFile.insert(fromFile.begin(), {"hydrostatics", obj, "--method", method, "--water", water, "--json"});
            fromFlags.insert(fromFlags.begin(), {"hydrostatics", obj, "--method", method, "--water-height", "0.25",
                                                 "--water-density", "1025", "--json"});
            const auto a = runJson(fromFile), b = runJson(fromFlags);
            CHECK(a["submerged"] == b["submerged"]);
            CHECK(a["mesh"] == b["mesh"]);
            CHECK(a["method"] == b["method"]);
            CHECK(a["water"] == nlohmann::json({{"type", "flat"}, {"file", water}, {"time", 0.0}, {"height", 0.25},
                                                {"density", 1025.0}}));
            CHECK(b["water"] == nlohmann::json({{"type", "flat"}, {"file", nullptr}, {"time", 0.0}, {"height", 0.25},
                                                {"density", 1025.0}}));
        }
    }
    // A water file without "density" has the scene's default, 1000 kg/m^3.
    writeJson(water, {{"type", "flat"}, {"height", 0.25}});
    const auto j = runJson({"hydrostatics", obj, "--water", water, "--json"});
    CHECK(j["water"]["density"].get<double>() == 1000.0);
    CHECK(j["submerged"]["volume"].get<double>() == Approx(1.5).epsilon(1e-12));
}

TEST_CASE("hydrostatics --water: a grid's relative file is read from the water file's folder", "[cli]") {
    // Heights h(x) = 0.25 + 0.1 x on a 5 x 5 grid (x, z in [-4, 4], spacing 2, clamped): a plane, which the
    // bilinear grid and the exact-mesh clip represent exactly. Box x in [-1, 1], bottom -0.5, L_z = 1:
    //   V = int (h(x) + 0.5) dx = 1.5 m^3,  x_B = int x (h(x) + 0.5) dx / V = 0.1 (2/3) / 1.5.
    const std::string dir = scratchDir("grid_relative");
    std::filesystem::create_directories(dir + "/sea/heights");
    const std::string obj = dir + "/box.obj", water = dir + "/sea/grid.json";
    writeBoxObj(obj, 2.0, 1.0, 1.0);
    {
        std::ofstream csv(dir + "/sea/heights/tilted.csv");
        csv.precision(17);
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 5; ++col) csv << 0.25 + 0.1 * (-4 + 2 * col) << (col < 4 ? "," : "\n");
    }
    writeJson(water, {{"type", "grid"},
                      {"file", "heights/tilted.csv"},
                      {"spacing", 2},
                      {"origin", {-4, -4}},
                      {"periodic", false}});
    const auto j = runJson({"hydrostatics", obj, "--water", water, "--time", "3", "--json"});
    CHECK(j["submerged"]["volume"].get<double>() == Approx(1.5).epsilon(1e-9));
    CHECK(j["submerged"]["centre_of_buoyancy"][0].get<double>() == Approx(0.1 * (2.0 / 3.0) / 1.5).epsilon(1e-9));
    CHECK(j["water"]["type"] == "grid");
    CHECK(j["water"]["height"].is_null());  // a grid holds absolute heights: no mean level
    CHECK(j["water"]["time"].get<double>() == 3.0);
    // The same name next to the mesh instead is not found: the error names the key and the path it tried.
    std::filesystem::remove(dir + "/sea/heights/tilted.csv");
    const auto r = runCli({"hydrostatics", obj, "--water", water});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(water));
    CHECK_THAT(r.err, Contains("file: cannot read"));
    CHECK_THAT(r.err, Contains("sea/heights/tilted.csv"));
}

TEST_CASE("hydrostatics --water: flags that cannot go together are refused naming both", "[cli]") {
    const std::string dir = scratchDir("water_flags");
    const std::string obj = dir + "/box.obj", water = dir + "/flat.json";
    writeBoxObj(obj, 1, 1, 1);
    writeJson(water, {{"type", "flat"}});
    struct Case {
        std::vector<std::string> args;
        std::vector<std::string> flags;
    };
    const std::vector<Case> cases = {
        {{"hydrostatics", obj, "--water", water, "--water-height", "1"}, {"--water", "--water-height"}},
        {{"hydrostatics", obj, "--water", water, "--water-density", "1025"}, {"--water", "--water-density"}},
        {{"hydrostatics", obj, "--time", "1"}, {"--time", "--water"}},
        {{"hydrostatics", obj, "--water-height", "0.5", "--time", "1"}, {"--time", "--water"}},
    };
    for (const auto& c : cases) {
        const auto r = runCli(c.args);
        INFO(c.args[2] << " " << c.args.back() << " -> exit " << r.exit_code << ", stderr: " << r.err);
        CHECK(r.exit_code == 2);
        for (const auto& flag : c.flags) CHECK(namesFlag(r.err, flag));
    }
    for (const char* bad : {"nan", "inf", "-inf"}) {
        const auto r = runCli({"hydrostatics", obj, "--water", water, "--time", bad});
        INFO("--time " << bad << ": stderr " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(namesFlag(r.err, "--time"));
    }
}

TEST_CASE("hydrostatics --water: bad water files exit 2 naming the file and the key", "[cli]") {
    const std::string dir = scratchDir("water_files");
    const std::string obj = dir + "/box.obj";
    writeBoxObj(obj, 1, 1, 1);
    std::ofstream(dir + "/junk.json") << "{\"type\": \"flat\",";
    writeJson(dir + "/array.json", {1, 2, 3});
    writeJson(dir + "/unknown_type.json", {{"type", "lake"}});
    writeJson(dir + "/bad_key.json", {{"type", "flat"}, {"heigth", 1}});
    writeJson(dir + "/bad_wave.json", {{"type", "gerstner"}, {"waves", {{{"amplitude", 0.1}, {"wavelength", -3}}}}});
    writeJson(dir + "/looping.json",
              {{"type", "gerstner"}, {"waves", {{{"amplitude", 5}, {"wavelength", 10}, {"steepness", 1}}}}});
    writeJson(dir + "/interactive.json", {{"type", "interactive"}, {"size", {10, 10}}});
    writeJson(dir + "/frame_up.json", {{"type", "flat"}, {"frame", {{"up", {0, 0, 1}}}}});
    writeJson(dir + "/frame_shifted.json", {{"type", "flat"}, {"frame", {{"origin", {0, 1, 0}}}}});
    struct Case {
        std::string file;
        std::vector<std::string> message;
    };
    const std::vector<Case> cases = {
        {dir + "/missing.json", {"cannot read"}},
        {dir, {"not a file"}},
        {dir + "/junk.json", {"invalid JSON"}},
        {dir + "/array.json", {"expected an object"}},
        {dir + "/unknown_type.json", {"type:", "lake"}},
        {dir + "/bad_key.json", {"heigth: unknown key"}},
        {dir + "/bad_wave.json", {"waves[0].wavelength"}},
        {dir + "/looping.json", {"loop"}},
        {dir + "/interactive.json", {"simulation", "buoyancy run"}},
        // The command's world is y-up in the water's own coordinates: another up is against its gravity, another
        // frame would be ignored.
        {dir + "/frame_up.json", {"frame.up: (0, 0, 1) is not antiparallel to the scene's gravity (0, -9.81, 0)"}},
        {dir + "/frame_shifted.json", {"frame:", "--rotate / --translate"}},
    };
    for (const auto& c : cases) {
        const auto r = runCli({"hydrostatics", obj, "--water", c.file, "--json"});
        INFO(c.file << " -> exit " << r.exit_code << ", stderr: " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(r.out.empty());
        CHECK_THAT(r.err, Contains(c.file));
        for (const auto& m : c.message) CHECK_THAT(r.err, Contains(m));
    }
}
