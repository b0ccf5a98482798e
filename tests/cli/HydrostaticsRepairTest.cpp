// `buoyancy hydrostatics --repair` and `--convex-hull` as a user runs them: on Debian's broken assimp test models
// and on an open-deck boat. Expected values come from the files themselves (the rim polygon's area by the
// shoelace formula, the closed hull's volume by a tetrahedra sum about a point of the deck plane) or from
// inequalities a repair must satisfy, never from the tool's own output.
#include "CliRunner.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

using buoyancy_test::runCli;
using buoyancy_test::scratchDir;
using buoyancy_test::writeBoxObj;
using Catch::Matchers::Contains;

namespace {

const std::string kModels = BUOYANCY_ASSIMP_MODELS_DIR;
const std::string kOpenBoat = std::string(BUOYANCY_SOURCE_DIR) + "/bullet_examples/models/open_boat.obj";

nlohmann::json runJson(const std::vector<std::string>& args) {
    auto r = runCli(args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
}

struct Obj {
    std::vector<std::array<double, 3>> v;
    std::vector<std::array<int, 3>> f;  // 0-based
};

/// A minimal reader for the "v x y z" / "f a b c" files our generator writes.
Obj readObj(const std::string& path) {
    Obj o;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::string tag;
        s >> tag;
        if (tag == "v") { std::array<double, 3> p{}; s >> p[0] >> p[1] >> p[2]; o.v.push_back(p); }
        if (tag == "f") { std::array<int, 3> t{}; s >> t[0] >> t[1] >> t[2]; for (int& k : t) --k; o.f.push_back(t); }
    }
    return o;
}

}  // namespace

TEST_CASE("hydrostatics --repair: an open-deck boat is closed at its gunwale", "[cli][repair]") {
    const Obj boat = readObj(kOpenBoat);
    REQUIRE(boat.f.size() > 100);
    // The rim: the deck-edge vertices (y = 0.3). Going round: starboard (z < 0) from stern to bow, then port back.
    std::vector<std::array<double, 3>> starboard, port;
    for (const auto& p : boat.v)
        if (std::abs(p[1] - 0.3) < 1e-9 && std::abs(p[2]) > 1e-9) (p[2] < 0 ? starboard : port).push_back(p);
    auto byX = [](const auto& a, const auto& b) { return a[0] < b[0]; };
    std::sort(starboard.begin(), starboard.end(), byX);
    std::sort(port.begin(), port.end(), [&](const auto& a, const auto& b) { return byX(b, a); });
    std::vector<std::array<double, 3>> rim = starboard;
    rim.insert(rim.end(), port.begin(), port.end());
    double twiceArea = 0;
    for (std::size_t i = 0; i < rim.size(); ++i) {
        const auto& a = rim[i];
        const auto& b = rim[(i + 1) % rim.size()];
        twiceArea += a[0] * b[2] - b[0] * a[2];
    }
    const double deckArea = 0.5 * std::abs(twiceArea);
    // Volume of the closed hull: the open surface's tetrahedra about a point of the deck plane (the flat deck cap
    // adds nothing about such a point).
    double six = 0;
    for (const auto& t : boat.f) {
        double a[3], b[3], c[3];
        for (int k = 0; k < 3; ++k) {
            a[k] = boat.v[t[0]][k] - (k == 1 ? 0.3 : 0.0);
            b[k] = boat.v[t[1]][k] - (k == 1 ? 0.3 : 0.0);
            c[k] = boat.v[t[2]][k] - (k == 1 ? 0.3 : 0.0);
        }
        six += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    const double volume = std::abs(six) / 6.0;

    const auto refused = runCli({"hydrostatics", kOpenBoat});
    CHECK(refused.exit_code == 2);
    CHECK_THAT(refused.err, Contains("open surface: 50 boundary edges") && Contains("--repair"));

    const auto j = runJson({"hydrostatics", kOpenBoat, "--repair", "--method", "exact-mesh", "--json"});
    CHECK(j["repair"]["holes_closed"].get<int>() == 1);
    CHECK(j["repair"]["hole_edges"].get<int>() == int(rim.size()));
    // The importer reads coordinates in single precision: agreement to ~1e-7 relative.
    CHECK(j["repair"]["area_added"].get<double>() == Approx(deckArea).epsilon(1e-6));
    CHECK(j["repair"]["volume_after"].get<double>() == Approx(volume).epsilon(1e-6));
    CHECK(j["mesh"]["volume"].get<double>() == Approx(volume).epsilon(1e-6));
    bool said = false;
    for (const auto& w : j["mesh"]["warnings"]) said = said || w.get<std::string>().find("repaired: closed 1 hole") != std::string::npos;
    CHECK(said);
}

TEST_CASE("hydrostatics --repair on Debian's broken test models", "[cli][repair]") {
    // Each is refused without the flag and floats with it; a repaired model must lie inside its convex hull.
    for (const char* rel : {"STL/sphereWithHole.stl", "STL/Spider_ascii.stl", "STL/Wuson.stl", "OBJ/spider.obj"}) {
        SECTION(rel) {
            const std::string file = kModels + "/" + rel;
            CHECK(runCli({"hydrostatics", file}).exit_code == 2);
            const auto j = runJson({"hydrostatics", file, "--repair", "--method", "exact-mesh", "--json"});
            CHECK(j["repair"]["holes_closed"].get<int>() >= 1);
            const double v = j["mesh"]["volume"].get<double>();
            const auto h = runJson({"hydrostatics", file, "--convex-hull", "--method", "exact-mesh", "--json"});
            const double hull = h["convex_hull"]["volume"].get<double>();
            CHECK(v > 0);
            CHECK(v <= hull * (1 + 1e-9));
            CHECK(h["mesh"]["volume"].get<double>() == Approx(hull).epsilon(1e-9));
        }
    }
    SECTION("sphereWithHole: a convex model with three triangular holes is repaired into its own hull") {
        // Each hole is one missing triangle of a convex polyhedron: the least-area cap of a 3-edge loop is that
        // triangle, a face of the hull, so the repaired model and the hull enclose the same volume.
        const auto j = runJson({"hydrostatics", kModels + "/STL/sphereWithHole.stl", "--repair", "--method",
                                "exact-mesh", "--json"});
        const auto h = runJson({"hydrostatics", kModels + "/STL/sphereWithHole.stl", "--convex-hull", "--method",
                                "exact-mesh", "--json"});
        CHECK(j["repair"]["holes_closed"].get<int>() == 3);
        CHECK(j["repair"]["hole_edges"].get<int>() == 9);
        CHECK(j["mesh"]["volume"].get<double>() == Approx(h["convex_hull"]["volume"].get<double>()).epsilon(1e-9));
    }
}

TEST_CASE("hydrostatics --convex-hull: a cube's hull is the cube and the volume added is stated", "[cli][repair]") {
    const std::string obj = scratchDir("hull") + "/box.obj";
    writeBoxObj(obj, 2.0, 1.0, 1.0);
    const auto j = runJson({"hydrostatics", obj, "--convex-hull", "--json"});
    CHECK(j["convex_hull"]["volume"].get<double>() == Approx(2.0).epsilon(1e-12));
    CHECK(j["convex_hull"]["model_volume"].get<double>() == Approx(2.0).epsilon(1e-12));
    CHECK(j["repair"].is_null());
    const auto r = runCli({"hydrostatics", obj, "--convex-hull"});
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.err, Contains("replaced by its convex hull") && Contains("(+0 %)"));
    // --repair on a closed model: accepted, nothing done.
    const auto k = runJson({"hydrostatics", obj, "--repair", "--json"});
    CHECK(k["repair"]["holes_closed"].get<int>() == 0);
    CHECK(k["repair"]["volume_after"].is_null());
}

TEST_CASE("scene keys repair, convex_hull and open_top", "[cli][repair]") {
    using buoyancy::cli::parseScene;
    auto scene = [](const std::string& shapeExtra) {
        return std::string(R"({"bodies": [{"shape": {"type": "mesh", "file": ")") + kOpenBoat + "\"" + shapeExtra +
               R"(}, "mass": 2300}]})";
    };
    // Without a key the open boat is refused with the keys that would save it.
    CHECK_THROWS_WITH(buoyancy::cli::buildSceneWorld(parseScene(scene(""), "s.json", "."), 10.0),
                      Contains("bodies[0].shape") && Contains("open surface") && Contains("\"repair\": true"));
    // "repair": closed; "open_top": closed with an opening and an automatic water graph; "convex_hull": a hull.
    auto repaired = buoyancy::cli::buildSceneWorld(parseScene(scene(R"(, "repair": true)"), "s.json", "."), 10.0);
    CHECK(repaired->floods.at(0) == nullptr);
    const auto openScene = parseScene(scene(R"(, "open_top": true)"), "s.json", ".");
    CHECK(openScene.bodies.at(0).flooding.enabled);
    auto open = buoyancy::cli::buildSceneWorld(openScene, 10.0);
    CHECK(open->floods.at(0) != nullptr);
    CHECK(buoyancy::cli::buildSceneWorld(parseScene(scene(R"(, "convex_hull": true)"), "s.json", "."), 10.0));
    // Errors name the key.
    CHECK_THROWS_WITH(parseScene(scene(R"(, "repair": 1)"), "s.json", "."), Contains("bodies[0].shape.repair"));
    CHECK_THROWS_WITH(parseScene(scene(R"(, "open_top": true, "convex_hull": true)"), "s.json", "."),
                      Contains("bodies[0].shape.open_top") && Contains("convex_hull"));
    const std::string closed = scratchDir("closed_top") + "/box.obj";
    writeBoxObj(closed, 1.0, 1.0, 1.0);
    const std::string closedScene = std::string(R"({"bodies": [{"shape": {"type": "mesh", "file": ")") + closed +
                                    R"(", "open_top": true}, "mass": 300}]})";
    CHECK_THROWS_WITH(buoyancy::cli::buildSceneWorld(parseScene(closedScene, "s.json", "."), 10.0),
                      Contains("open_top") && Contains("no hole to open"));
}
