// The scene runner: CSV format, output times, determinism, and errors that name the key.
#include "scene/SceneErrors.h"
#include "cli/RunCommand.h"
#include "scene/SceneFile.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#include <unistd.h>  // getpid: a private temporary folder per test process

namespace {

const std::string kScenes = std::string(BUOYANCY_SOURCE_DIR) + "/bullet_examples/scenes/";

std::string tempDir(const std::string& name) {
    const auto p = std::filesystem::temp_directory_path() / ("buoyancy_run_test_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(p);
    return p.string();
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

struct Row {
    double t;
    std::string body;
    std::vector<double> v;  // columns after "body"
};

std::vector<Row> readCsv(const std::string& path, std::string* header = nullptr) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    if (header) *header = line;
    std::vector<Row> rows;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string cell;
        Row r;
        std::getline(ss, cell, ',');
        r.t = std::stod(cell);
        std::getline(ss, r.body, ',');
        while (std::getline(ss, cell, ',')) r.v.push_back(std::stod(cell));
        rows.push_back(r);
    }
    return rows;
}

void expectUsageError(const std::string& json, const std::string& keyInMessage) {
    try {
        buoyancy::cli::parseScene(json, "test.json", ".");
        FAIL("no error for " << json);
    } catch (const buoyancy::cli::UsageError& e) {
        INFO(e.what());
        CHECK(std::string(e.what()).find(keyInMessage) != std::string::npos);
    }
}

}  // namespace

TEST_CASE("run writes the trajectory CSV at the output times, deterministically", "[bullet][run]") {
    const std::string out1 = tempDir("plank1"), out2 = tempDir("plank2");
    REQUIRE(buoyancy::cli::runSceneCommand(kScenes + "plank.json", out1, 6.0) == 0);
    REQUIRE(buoyancy::cli::runSceneCommand(kScenes + "plank.json", out2, 6.0) == 0);
    CHECK(readText(out1 + "/trajectory.csv") == readText(out2 + "/trajectory.csv"));

    std::string header;
    const auto rows = readCsv(out1 + "/trajectory.csv", &header);
    CHECK(header.rfind("t,body,x,y,z,qx,qy,qz,qw,cx,cy,cz,vx,vy,vz,wx,wy,wz,submerged_volume,mass,water_volume", 0) == 0);
    // t = 0 and every 0.1 s up to 6 s (frames of 4/240 s: first boundary at or after k·0.1).
    REQUIRE(rows.size() == 61);
    CHECK(rows[0].t == 0.0);
    for (std::size_t k = 1; k < rows.size(); ++k) {
        CHECK(rows[k].t >= 0.1 * k - 1e-9);
        CHECK(rows[k].t < 0.1 * k + 4.0 / 240.0);
    }
    // The plank (2 × 0.4 × 1, s = 0.5) floats with its centre at the water line; mass 400 kg.
    const Row& last = rows.back();
    CHECK(last.body == "plank");
    CHECK(std::abs(last.v[1]) < 0.005 * 0.4);
    CHECK(last.v[17] == Approx(400.0).epsilon(1e-9));
    CHECK(last.v[16] == Approx(0.4).epsilon(0.01));  // submerged volume = m / ρ
}

TEST_CASE("run: hard cases stay finite and bounded", "[bullet][run][hard][slow]") {
    const std::string out = tempDir("hard");
    REQUIRE(buoyancy::cli::runSceneCommand(kScenes + "hard_cases.json", out, std::nullopt) == 0);
    const auto rows = readCsv(out + "/trajectory.csv");
    std::map<std::string, Row> last;
    for (const Row& r : rows) {
        for (double x : r.v) REQUIRE(std::isfinite(x));
        CHECK(std::abs(r.v[0]) < 50);
        CHECK(r.v[1] < 12);
        CHECK(r.v[1] > -6);
        last[r.body] = r;
    }
    // At the end (20 s) everything is at rest: floating ones near the surface, the anvil on the ground.
    for (const auto& [name, r] : last) {
        const double speed = std::sqrt(r.v[10] * r.v[10] + r.v[11] * r.v[11] + r.v[12] * r.v[12]);
        INFO(name << " speed " << speed << " y " << r.v[1]);
        CHECK(speed < 0.1);
    }
    CHECK(last["anvil"].v[1] < -4.5);
    CHECK(last["deep_cork"].v[1] > -0.3);
}

TEST_CASE("scene errors name the key and nothing runs", "[bullet][run][errors]") {
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": 500, "colour": 1}]})",
                     "bodies[0].colour: unknown key");
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": "heavy"}]})",
                     "bodies[0].density: expected a number");
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,-1,1]}, "density": 500}]})",
                     "bodies[0].shape.size[1]");
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}}]})", "bodies[0]: missing");
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": 1, "mass": 2}]})",
                     "exactly one");
    expectUsageError(R"({"bodies": [{"shape": {"type": "mesh", "file": "no_such.obj"}, "density": 1}]})",
                     "bodies[0].shape.file: no such file");
    expectUsageError(R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}, "density": 1},
                                    {"name": "a", "shape": {"type": "sphere", "radius": 1}, "density": 1}]})",
                     "bodies[1].name: duplicate");
    expectUsageError(R"({"bodies": [{"shape": {"type": "sphere", "radius": 1}, "density": 1,
                                     "rotation": {"axis": [0,0,0], "degrees": 3}}]})",
                     "bodies[0].rotation.axis: zero axis");
    expectUsageError(R"({"gravity": [0, 0, -9.81], "water": {"frame": {"up": [0, 1, 0]}}, "bodies": []})",
                     "water.frame.up: (0, 1, 0) is not antiparallel to the scene's gravity (0, 0, -9.81)");
    expectUsageError(R"({"dt": 0, "bodies": []})", "dt");
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": 5,
                                     "buoyancy": {"method": "magic"}}]})",
                     "bodies[0].buoyancy.method");
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": 5,
                                     "buoyancy": {"water_acceleration": "froude"}}]})",
                     "bodies[0].buoyancy.water_acceleration: unknown value \"froude\"");
    expectUsageError(R"({"water": {"type": "waves"}, "bodies": []})", "water.type");
    expectUsageError(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": 5, "mass_model": "shell"}]})",
                     "bodies[0].thickness");
    expectUsageError("{\"bodies\": [", "invalid JSON");
    // A valid scene parses, with the documented defaults.
    const auto s = buoyancy::cli::parseScene(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": 5}]})",
                                             "ok.json", ".");
    CHECK(s.bodies.at(0).name == "body0");
    CHECK(s.bodies.at(0).buoyancy.waterAcceleration == btWaterAccelerationForce::None);
    for (const auto& [name, value] : {std::pair<const char*, btWaterAccelerationForce>{"none", btWaterAccelerationForce::None},
                                      {"added-mass", btWaterAccelerationForce::AddedMass},
                                      {"added-mass-and-froude-krylov", btWaterAccelerationForce::AddedMassAndFroudeKrylov}}) {
        const auto w = buoyancy::cli::parseScene(
            std::string(R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}, "density": 5, "buoyancy": )"
                        R"({"water_acceleration": ")") + name + "\"}}]}",
            "ok.json", ".");
        CHECK(w.bodies.at(0).buoyancy.waterAcceleration == value);
    }
    CHECK(s.dt == Approx(1.0 / 240.0));
    CHECK(s.substepsPerFrame == 4);
    CHECK(s.duration == 10.0);
    CHECK(s.outputInterval == Approx(0.1));
    CHECK(s.waterDensity == 1000.0);
    // Missing scene file: exit code 2.
    CHECK(buoyancy::cli::runSceneCommand("/nonexistent/scene.json", tempDir("missing"), std::nullopt) == 2);
}
