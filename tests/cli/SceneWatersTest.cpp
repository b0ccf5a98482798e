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

namespace {

/// The L-shaped lake [0, 4] × [0, 2] ∪ [0, 2] × [0, 4] in (x, z), bottom −3, top 1.
const std::string kLakeRegion = R"({"polygon": [[0, 0], [4, 0], [4, 2], [2, 2], [2, 4], [0, 4]], "bottom": -3, "top": 1})";

/// A cube tank [6, 8] × [-2, 1] × [0, 2] as an OBJ file's text (outward faces, quads).
const std::string kTankObj = "v 6 -2 0\nv 8 -2 0\nv 8 -2 2\nv 6 -2 2\nv 6 1 0\nv 8 1 0\nv 8 1 2\nv 6 1 2\n"
                             "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";

}  // namespace

TEST_CASE("scene waters: polygon and mesh regions are read and reach the world", "[cli][waters]") {
    const auto dir = std::filesystem::temp_directory_path() / ("buoyancy_regions_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream f(dir / "tank.obj");
        f << kTankObj;
    }
    // An L-shaped lake, the notch's square beside it (sharing two edges), a tank from an OBJ file and a small
    // inline tetrahedron tank.
    const std::string waters = R"([{"type": "flat", "height": 0, "region": )" + kLakeRegion + R"(},
        {"type": "flat", "height": 0.5, "density": 1025, "region": {"polygon": [[2, 2], [4, 2], [4, 4], [2, 4]], "bottom": -2, "top": 1}},
        {"type": "flat", "height": -0.5, "region": {"mesh": "tank.obj"}},
        {"type": "flat", "height": 0, "region": {"vertices": [[10, -1, 0], [12, -1, 0], [10, -1, 2], [10, 1, 0]],
                                                 "triangles": [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]}}])";
    const auto s = parseScene("{\"waters\": " + waters + ", " + kBody + "}", "s.json", dir.string());
    REQUIRE(s.waters.size() == 4);
    CHECK(s.waters[0].regionKind == btWaterRegionKind::Polygon);
    CHECK(s.waters[0].footprint.size() == 6);
    CHECK(s.waters[0].footprint[3] == std::array<double, 2>{2, 2});
    CHECK(s.waters[0].bottom == -3);
    CHECK(s.waters[0].top == 1);
    CHECK(s.waters[0].regionMin == Eigen::Vector3d(0, -3, 0));  // the bounding box
    CHECK(s.waters[0].regionMax == Eigen::Vector3d(4, 1, 4));
    CHECK(s.waters[2].regionKind == btWaterRegionKind::Mesh);
    CHECK(s.waters[2].meshFile == (dir / "tank.obj").string());
    CHECK(s.waters[2].meshVertices.size() == 8);
    CHECK(s.waters[2].meshTriangles.size() == 3 * 12);  // quads fanned
    CHECK(s.waters[3].meshTriangles.size() == 3 * 4);
    auto world = buoyancy::cli::buildSceneWorld(s, 10.0);
    const auto& bodies = world->buoyancy->getWaterBodies();
    REQUIRE(bodies.size() == 4);
    CHECK(bodies[0].kind == btWaterRegionKind::Polygon);
    CHECK(bodies[0].footprintTriangles.size() == 4);
    CHECK(bodies[2].kind == btWaterRegionKind::Mesh);
    CHECK(bodies[2].meshNormals.size() == 6);
    CHECK(bodies[3].meshNormals.size() == 4);
    // Each point answers with the water it is in.
    const auto bodyAt = [&](double x, double y, double z) {
        return world->buoyancy->queryWater(btVector3(btScalar(x), btScalar(y), btScalar(z))).waterBody;
    };
    CHECK(bodyAt(1, -1, 3) == 0);
    CHECK(bodyAt(3, -1, 3) == 1);
    CHECK(bodyAt(7, -1, 1) == 2);
    CHECK(bodyAt(10.2, -0.5, 0.2) == 3);
    CHECK(bodyAt(11.5, -0.5, 1.5) == -1);  // beside the tetrahedron's slanted face
    // The scene file runs (the crate straddles the lake's corner at the origin).
    {
        std::ofstream f(dir / "lakes.json");
        f << "{\"waters\": " << waters << ", " << kBody << "}";
    }
    CHECK(buoyancy::cli::runSceneCommand((dir / "lakes.json").string(), (dir / "out").string(), 0.25) == 0);
    std::filesystem::remove_all(dir);
}

TEST_CASE("scene waters: bad polygon and mesh regions name their key", "[cli][waters]") {
    const auto one = [](const std::string& region) {
        return parseWaters(R"([{"type": "flat", "region": )" + region + "}]");
    };
    CHECK_THROWS_WITH(one(R"({"polygon": [[0, 0], [2, 2], [2, 0], [0, 2]], "bottom": -1, "top": 1})"),
                      Contains("s.json: waters[0].region.polygon: footprint: not a simple polygon: edge 0"));
    CHECK_THROWS_WITH(one(R"({"polygon": [[0, 0], [2, 0], [2, 2]], "top": 1})"),
                      Contains("s.json: waters[0].region.bottom: missing"));
    CHECK_THROWS_WITH(one(R"({"polygon": [[0, 0], [2, 0], [2, 2]], "bottom": 1, "top": 1})"),
                      Contains("s.json: waters[0].region.top: must be greater than bottom"));
    CHECK_THROWS_WITH(one(R"({"polygon": [[0, 0], [2, 0, 1], [2, 2]], "bottom": 0, "top": 1})"),
                      Contains("s.json: waters[0].region.polygon[1]: expected an array of 2 numbers"));
    CHECK_THROWS_WITH(one(R"({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "polygon": [[0, 0], [2, 0], [2, 2]]})"),
                      Contains("s.json: waters[0].region: more than one shape"));
    CHECK_THROWS_WITH(one(R"({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "bottom": 0})"),
                      Contains("s.json: waters[0].region.bottom: only with \"polygon\""));
    CHECK_THROWS_WITH(one(R"({})"), Contains("s.json: waters[0].region: missing its shape"));
    CHECK_THROWS_WITH(one(R"({"mesh": "no-such-tank.obj"})"), Contains("s.json: waters[0].region.mesh: no such file"));
    CHECK_THROWS_WITH(one(R"({"vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "triangles": [[0, 1, 2], [0, 2, 3]]})"),
                      Contains("s.json: waters[0].region.triangles[1][2]: value 3 out of range"));
    // A tetrahedron with a face turned: open in one direction, not closed.
    CHECK_THROWS_WITH(one(R"({"vertices": [[0, 0, 0], [2, 0, 0], [0, 0, 2], [0, 2, 0]],
                              "triangles": [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 2, 3]]})"),
                      Contains("s.json: waters[0].region.triangles: meshTriangles: the mesh is not closed"));
    // A C-shaped vessel (section in x, y, swept along z): its lower arm's top lies under its upper arm.
    CHECK_THROWS_WITH(
        one(R"({"vertices": [[0,0,0],[3,0,0],[3,1,0],[1,1,0],[1,2,0],[3,2,0],[3,3,0],[0,3,0],
                             [0,0,1],[3,0,1],[3,1,1],[1,1,1],[1,2,1],[3,2,1],[3,3,1],[0,3,1]],
                "triangles": [[0,2,1],[8,9,10],[0,3,2],[8,10,11],[0,4,3],[8,11,12],[0,7,4],[8,12,15],[4,6,5],
                              [12,13,14],[4,7,6],[12,14,15],[0,1,9],[0,9,8],[1,2,10],[1,10,9],[2,3,11],[2,11,10],
                              [3,4,12],[3,12,11],[4,5,13],[4,13,12],[5,6,14],[5,14,13],[6,7,15],[6,15,14],[7,0,8],
                              [7,8,15]]})"),
        Contains("s.json: waters[0].region.triangles: meshTriangles: the region mesh of water body 'waters[0]' "
                 "overhangs: triangles"));
    // Overlapping the lake: named with both entries; touching it: accepted.
    const std::string lake = R"({"type": "flat", "region": )" + kLakeRegion + "}";
    CHECK_THROWS_WITH(parseWaters("[" + lake + R"(, {"type": "flat", "region": {"box": {"min": [3, -1, 1], "max": [5, 0, 3]}}}])"),
                      Contains("s.json: waters[1].region: the box [3, -1, 1] to [5, 0, 3] overlaps waters[0].region (polygon of 6 corners"));
    CHECK(parseWaters("[" + lake + R"(, {"type": "flat", "region": {"box": {"min": [2, -1, 2], "max": [5, 0, 3]}}}])")
              .waters.size() == 2);
}
