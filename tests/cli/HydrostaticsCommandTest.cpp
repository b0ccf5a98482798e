// End-to-end tests of `buoyancy hydrostatics`: flags, JSON, exit codes, on meshes with analytic answers.
#include "CliRunner.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

using buoyancy_test::runCli;
using buoyancy_test::scratchDir;
using buoyancy_test::writeBoxObj;
using Catch::Matchers::Contains;

namespace {
nlohmann::json runJson(const std::vector<std::string>& args) {
    auto r = runCli(args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
}
}  // namespace

TEST_CASE("hydrostatics: half-submerged 2x1x1 box matches Archimedes", "[cli]") {
    const std::string obj = scratchDir("box") + "/box.obj";
    writeBoxObj(obj, 2.0, 1.0, 1.0);
    for (const char* method : {"default", "exact-mesh", "exact-coverage", "texel-centre"}) {
        SECTION(method) {
            const auto j = runJson({"hydrostatics", obj, "--method", method, "--json"});
            // Analytic: V = 2, half submerged: V_sub = 1, C_B = (0, -0.25, 0), F = rho g V_sub up, A_wp = 2.
            const double tol = std::string(method) == "texel-centre" ? 5e-3 : 1e-9;
            CHECK(j["mesh"]["volume"].get<double>() == Approx(2.0).epsilon(tol));
            CHECK(j["mesh"]["area"].get<double>() == Approx(10.0).epsilon(tol));
            CHECK(j["submerged"]["volume"].get<double>() == Approx(1.0).epsilon(tol));
            CHECK(j["submerged"]["centre_of_buoyancy"][1].get<double>() == Approx(-0.25).epsilon(10 * tol));
            CHECK(j["submerged"]["force"][1].get<double>() == Approx(1000 * 9.81).epsilon(tol));
            // Horizontal force: zero by symmetry; the sampled methods' waterline error is O(h^2) (design.md 2.4).
            const double weight = 1000 * 9.81 * 1.0;
            CHECK(std::fabs(j["submerged"]["force"][0].get<double>()) < (tol > 1e-9 ? 1e-3 : 1e-6) * weight);
            CHECK(std::fabs(j["submerged"]["force"][2].get<double>()) < (tol > 1e-9 ? 1e-3 : 1e-6) * weight);
            CHECK(j["submerged"]["waterline_area"].get<double>() == Approx(2.0).epsilon(10 * tol));
            CHECK(j["mesh"]["triangles"].get<int>() == 12);
            CHECK(j["mesh"]["components"].get<int>() == 1);
            // Unit-density inertia of a box about its centre: V (b^2 + c^2) / 12 ...
            CHECK(j["mesh"]["inertia_unit_density"][0][0].get<double>() == Approx(2.0 * (1 + 1) / 12).epsilon(1e-2));
            CHECK(j["mesh"]["inertia_unit_density"][1][1].get<double>() == Approx(2.0 * (4 + 1) / 12).epsilon(1e-2));
        }
    }
}

TEST_CASE("hydrostatics: pose, water level, density and gravity flags", "[cli]") {
    const std::string obj = scratchDir("pose") + "/box.obj";
    writeBoxObj(obj, 2.0, 1.0, 1.0);
    // 90 degrees about z puts the 2 m side vertical (y in [-1, 1]); lifted by 0.5 -> y in [-0.5, 1.5]:
    // 0.5 m of a 1x1 section under water at y = 0.
    auto j = runJson({"hydrostatics", obj, "--rotate", "0", "0", "2", "90", "--translate", "0", "0.5", "0", "--json"});
    CHECK(j["submerged"]["volume"].get<double>() == Approx(0.5).epsilon(1e-9));
    CHECK(j["submerged"]["centre_of_buoyancy"][1].get<double>() == Approx(-0.25).epsilon(1e-9));
    // Water at y = 0.25 on the unposed box (y in [-0.5, 0.5]): 0.75 of the height wet; seawater; moon gravity.
    j = runJson({"hydrostatics", obj, "--water-height", "0.25", "--water-density", "1025", "--gravity", "1.62",
                 "--json"});
    CHECK(j["submerged"]["volume"].get<double>() == Approx(1.5).epsilon(1e-9));
    CHECK(j["submerged"]["force"][1].get<double>() == Approx(1025 * 1.62 * 1.5).epsilon(1e-9));
    // Scale 2: volume x8.
    j = runJson({"hydrostatics", obj, "--scale", "2", "--water-height", "-10", "--json"});
    CHECK(j["mesh"]["volume"].get<double>() == Approx(16.0).epsilon(1e-9));
    CHECK(j["submerged"]["centre_of_buoyancy"].is_null());
    CHECK(j["submerged"]["volume"].get<double>() == 0.0);
    // Fully submerged: no net horizontal force, vertical = rho g V.
    j = runJson({"hydrostatics", obj, "--water-height", "10", "--method", "exact-coverage", "--json"});
    CHECK(j["submerged"]["volume"].get<double>() == Approx(2.0).epsilon(1e-9));
    CHECK(std::fabs(j["submerged"]["force"][0].get<double>()) < 1e-6);
    CHECK(std::fabs(j["submerged"]["force"][2].get<double>()) < 1e-6);
}

TEST_CASE("hydrostatics: heeled box torque matches the wall-sided GZ formula", "[cli]") {
    const std::string obj = scratchDir("tilt") + "/box.obj";
    writeBoxObj(obj, 2.0, 1.0, 1.0);
    // Square section (1 x 1), half submerged (s = 0.5): GM = KB + BM - KG = 0.25 + 1/6 - 0.5 < 0, the log is
    // unstable flat (design.md 5). Heeled by phi about x, the torque about the centre of volume is
    // tau_x = -rho g V GZ with the wall-sided GZ = sin(phi) (GM + BM tan^2(phi) / 2), exact for a box while no
    // edge emerges; and a wide box (4 m beam) at the same draft is stable: its torque must turn it back.
    const double phi = 10 * M_PI / 180;
    auto gzOf = [&](double beam) {
        const double V = 2.0 * beam * 0.5, BM = (2.0 * beam * beam * beam / 12) / V, GM = 0.25 + BM - 0.5;
        return std::sin(phi) * (GM + 0.5 * BM * std::tan(phi) * std::tan(phi));
    };
    auto j = runJson({"hydrostatics", obj, "--rotate", "1", "0", "0", "10", "--json"});
    CHECK(j["submerged"]["torque"][0].get<double>() > 0);  // capsizing
    CHECK(j["submerged"]["torque"][0].get<double>() == Approx(-1000 * 9.81 * 1.0 * gzOf(1.0)).epsilon(1e-6));
    const std::string wide = scratchDir("tilt") + "/wide.obj";
    writeBoxObj(wide, 2.0, 1.0, 4.0);
    j = runJson({"hydrostatics", wide, "--rotate", "1", "0", "0", "10", "--json"});
    CHECK(j["submerged"]["torque"][0].get<double>() < 0);  // righting
    CHECK(j["submerged"]["torque"][0].get<double>() == Approx(-1000 * 9.81 * 4.0 * gzOf(4.0)).epsilon(1e-6));
}

TEST_CASE("hydrostatics: --texture with exact-mesh is ignored with a warning", "[cli]") {
    const std::string obj = scratchDir("warn") + "/box.obj";
    writeBoxObj(obj, 1, 1, 1);
    const auto r = runCli({"hydrostatics", obj, "--method", "exact-mesh", "--texture", "64", "--json"});
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.err, Contains("--texture is ignored"));
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["method"]["texture"].get<int>() == 0);
    CHECK(j["method"]["name"].get<std::string>() == "exact-mesh");
}

TEST_CASE("hydrostatics: texture methods report their texture and sample count", "[cli]") {
    const std::string obj = scratchDir("tex") + "/box.obj";
    writeBoxObj(obj, 1, 1, 1);
    const auto j = runJson({"hydrostatics", obj, "--method", "exact-coverage", "--texture", "64", "--json"});
    CHECK(j["method"]["texture"].get<int>() == 64);
    CHECK(j["method"]["samples"].get<int>() > 0);
    CHECK(j["method"]["samples"].get<int>() <= 64 * 64);
    CHECK(j["mesh"]["uv"].get<std::string>() == "generated");  // an OBJ without UVs
}

TEST_CASE("hydrostatics: bad input exits 2 with a message", "[cli]") {
    const std::string dir = scratchDir("bad");
    const std::string obj = dir + "/box.obj";
    writeBoxObj(obj, 1, 1, 1);
    std::ofstream(dir + "/open.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir + "/empty.obj") << "";
    std::ofstream(dir + "/notes.txt") << "hello\n";
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"hydrostatics", dir + "/open.obj"}, "open surface"},
        {{"hydrostatics", dir + "/missing.obj"}, "missing.obj"},
        {{"hydrostatics", dir + "/empty.obj"}, "empty.obj"},
        {{"hydrostatics", dir + "/notes.txt"}, "notes.txt"},
        {{"hydrostatics", obj, "--no-such-flag"}, "no-such-flag"},
        {{"hydrostatics", obj, "--rotate", "0", "0", "0", "30"}, "axis"},
        {{"hydrostatics", obj, "--method", "magic"}, "magic"},
        {{"hydrostatics", obj, "--scale", "-1"}, "--scale"},
        {{"hydrostatics", obj, "--texture", "0", "--method", "exact-coverage"}, "--texture"},
        {{"hydrostatics", obj, "--water-density", "nan"}, "--water-density"},
        {{"hydrostatics"}, "MESH"},
        {{"no-such-command"}, "no-such-command"},
    };
    for (const auto& c : cases) {
        const auto r = runCli(c.args);
        INFO(c.args.back() << " -> exit " << r.exit_code << ", stderr: " << r.err);
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains(c.message));
    }
}

TEST_CASE("hydrostatics: a model over 1 km or under 1 mm gets a size warning with a --scale hint, and runs", "[cli]") {
    const std::string dir = scratchDir("model_size");
    SECTION("a 2 m box written in millimetres") {
        writeBoxObj(dir + "/mm.obj", 2000, 1000, 1000);
        const auto r = runCli({"hydrostatics", dir + "/mm.obj"});
        CHECK(r.exit_code == 0);
        CHECK_THAT(r.err, Contains("the model's largest side is 2000 m"));
        CHECK_THAT(r.err, Contains("--scale 0.001"));
        // Following the hint gives the box's volume in m³ and no warning.
        const auto scaled = runCli({"hydrostatics", dir + "/mm.obj", "--scale", "0.001", "--json"});
        REQUIRE(scaled.exit_code == 0);
        CHECK(scaled.err.find("largest side") == std::string::npos);
        CHECK(nlohmann::json::parse(scaled.out)["mesh"]["volume"].get<double>() == Approx(2.0).epsilon(1e-9));
    }
    SECTION("a 0.5 mm box") {
        writeBoxObj(dir + "/tiny.obj", 0.0005, 0.0005, 0.0005);
        const auto r = runCli({"hydrostatics", dir + "/tiny.obj"});
        CHECK(r.exit_code == 0);
        CHECK_THAT(r.err, Contains("largest side is 0.0005 m"));
        CHECK_THAT(r.err, Contains("--scale 1000"));
    }
    SECTION("1 mm and 1 km are still in range") {
        writeBoxObj(dir + "/km.obj", 1000, 10, 10);
        const auto r = runCli({"hydrostatics", dir + "/km.obj"});
        CHECK(r.exit_code == 0);
        CHECK(r.err.find("largest side") == std::string::npos);
    }
}
