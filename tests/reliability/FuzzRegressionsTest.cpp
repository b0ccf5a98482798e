// Regression tests for what the fuzzers (fuzz/) found in our code. Each case is the minimised or
// decoded crashing input, written out by hand, with the behaviour it must have now.

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstdio>

#include <catch2/catch.hpp>

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

TEST_CASE("fuzz regression: a cavity poking out of a distorted body is refused by prepareMesh",
          "[reliability][fuzz-regression]") {
    // fuzz_mesh_prepare: a mutated "cube with a cavity" seed. Both components are closed and consistently
    // oriented, but the outer one crosses itself and the inward one sticks out of it: the signed volumes
    // add up to -0.388 m³. prepareMesh accepted it and the CLI then failed with "internal error" (exit 3)
    // in polyhedronMassProperties; it must be a MeshError (exit 2) naming the problem.
    buoyancy::TriangleMesh m;
    m.vertices = {{0.0, 0.0, 0.0},       {1.0, 0.0, 0.0},      {1.0, 1.0, 1.125},    {0.0, -1.0, -0.125},
                  {-0.125, -0.125, -1.125}, {-1.125, 0.0, 1.0}, {1.0, 1.0, 1.0},      {0.0, -3.25, 1.0},
                  {-0.125, -0.125, -0.125}, {1.125, 0.25, 0.25}, {0.75, 0.75, 0.25},  {0.25, 0.75, 0.25},
                  {0.25, 0.25, 0.75},    {0.75, 0.25, 0.75},   {0.75, 0.75, 0.75},   {0.25, 0.75, 0.75}};
    m.triangles = {{0, 2, 1},   {0, 3, 2},    {4, 5, 6},    {4, 6, 7},    {0, 1, 5},    {0, 5, 4},
                   {3, 7, 6},   {3, 6, 2},    {0, 4, 7},    {0, 7, 3},    {1, 2, 6},    {1, 6, 5},
                   {9, 10, 8},  {10, 11, 8},  {14, 13, 12}, {15, 14, 12}, {13, 9, 8},   {12, 13, 8},
                   {14, 15, 11}, {10, 14, 11}, {15, 12, 8}, {11, 15, 8},  {14, 10, 9},  {13, 14, 9}};
    CHECK_THROWS_WITH(buoyancy::prepareMesh(m, "m.obj"), StartsWith("m.obj: encloses no positive volume: the components add up to -0.388"));
}

namespace {

/// A 32 m box (component 1) with n × n small closed boxes of `part` m centred on its top face y = 16 m
/// (components 2…n²+1), each crossing it: the kind of soup that made prepareMesh slow.
buoyancy::TriangleMesh partsOnABigBox(int n, double part) {
    buoyancy::TriangleMesh m = buoyancy::makeBoxMesh(32, 32, 32);
    m.corner_uvs.clear();  // a soup without UVs, like the fuzzer's
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const buoyancy::TriangleMesh b = buoyancy::makeBoxMesh(part, part, part);
            const Eigen::Vector3d at(-15 + 30.0 * (i + 0.37) / n, 16, -15 + 30.0 * (j + 0.61) / n);
            const int base = static_cast<int>(m.vertices.size());
            for (const auto& v : b.vertices) m.vertices.push_back(v + at);
            for (const auto& t : b.triangles) m.triangles.push_back(t + Eigen::Vector3i::Constant(base));
        }
    return m;
}

double prepareSeconds(buoyancy::TriangleMesh& m, buoyancy::MeshReport& report) {
    const auto t0 = std::chrono::steady_clock::now();
    report = buoyancy::prepareMesh(m, "parts.obj");
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST_CASE("fuzz regression: many small parts crossing a large one are checked quickly",
          "[reliability][fuzz-regression]") {
    // fuzz_mesh_prepare: a 4096-triangle soup of small closed parts crossing large triangles took 26 s.
    // The component-intersection check built a hash grid per pair of components with the cell size of the
    // median triangle, and a large triangle went into every cell its box covered (up to 16M). Now one
    // bounding-volume hierarchy over all triangles: near-linear in the triangle count.
    // Expected values by construction: every small box crosses the top face of the big one and no other
    // small box (they are 30/n m apart), so exactly n² pairs (1&2, 1&3, ...) intersect.
    buoyancy::MeshReport small, large;
    buoyancy::TriangleMesh a = partsOnABigBox(12, 0.002), b = partsOnABigBox(48, 0.002);  // 1740 and 27660 triangles
    const double ta = prepareSeconds(a, small), tb = prepareSeconds(b, large);
    std::printf("parts on a big box: %zu triangles %.4f s, %zu triangles %.4f s\n", a.triangles.size(), ta,
                b.triangles.size(), tb);
    CHECK(small.components == 145);
    CHECK(large.components == 2305);
    bool warnedSmall = false, warnedLarge = false;
    for (const auto& w : small.warnings)
        warnedSmall |= w.message == "parts.obj: 144 pairs of components intersect each other (1&2, 1&3, 1&4, 1&5, "
                                    "1&6, ...): the volume they share is counted twice";
    for (const auto& w : large.warnings)
        warnedLarge |= w.message.rfind("parts.obj: 2304 pairs of components intersect each other (1&2, ", 0) == 0;
    CHECK(warnedSmall);
    CHECK(warnedLarge);
    // The old check took 24 s for 6 × 6 such parts (444 triangles; 4.4 s for 12 × 12 parts of 1 cm) and grew
    // with (big / small)² per pair; now (Release, 2 cores) ≈ 0.02 s and 0.2 s: the bounds leave 25×.
    CHECK(ta < 1.0);
    CHECK(tb < 5.0);
}

TEST_CASE("fuzz regression: two crossing parts that each hold the other's probe point do not hang",
          "[reliability][fuzz-regression]") {
    // fuzz_mesh_prepare (timeout, a 175-byte input: two closed 12-triangle parts crossing each other): the
    // nesting test found each part "inside" the other (the winding number at a point of one surface is 1
    // for the other), so the parent links formed a cycle and the walk to the outermost part never ended.
    // Generated input of the same kind: a unit cube and the same cube turned 45° about the vertical axis
    // through its centre (each one's first face centroid lies inside the other). Expected by construction:
    // two components, not nested, one intersecting pair.
    buoyancy::TriangleMesh m = buoyancy::makeBoxMesh(1, 1, 1);
    m.corner_uvs.clear();
    const buoyancy::TriangleMesh b = buoyancy::makeBoxMesh(1, 1, 1);
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const int base = static_cast<int>(m.vertices.size());
    for (const auto& v : b.vertices) m.vertices.push_back(turn * v);
    for (const auto& t : b.triangles) m.triangles.push_back(t + Eigen::Vector3i::Constant(base));
    const buoyancy::MeshReport r = buoyancy::prepareMesh(m, "crossing.obj");
    CHECK(r.components == 2);
    CHECK(r.cavities == 0);
    CHECK(r.flipped_components == 0);
    REQUIRE(r.warnings.size() == 1);
    CHECK(r.warnings[0].message ==
          "crossing.obj: 1 pair of components intersect each other (1&2): the volume they share is counted twice");
}

#if defined(BUOYANCY_CLI_PATH)

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

struct CliResult {
    int exitCode = -1;
    std::string output;  // stdout + stderr
};

CliResult runCli(const std::string& args) {
    CliResult r;
    const std::string cmd = std::string(BUOYANCY_CLI_PATH) + " " + args + " 2>&1";
    FILE* p = ::popen(cmd.c_str(), "r");
    REQUIRE(p != nullptr);
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
    const int status = ::pclose(p);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

std::string scratchFile(const std::string& name, const std::string& text) {
    const auto dir = std::filesystem::temp_directory_path() / ("bb-reliability-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / name;
    std::ofstream(path) << text;
    return path.string();
}

}  // namespace

TEST_CASE("fuzz regression: the CLI reports bad input with exit 2, never an internal error",
          "[reliability][fuzz-regression][cli]") {
    SECTION("texel-centre at a texture too coarse for the mesh (fuzz_atlas_bake)") {
        // A cube whose corner 0 was moved onto corner 4: texel-centre baking at 8×8 gives a negative
        // sampled volume; `buoyancy hydrostatics` reported "internal error" (exit 3).
        const std::string obj = scratchFile("coarse.obj",
                                            "v 0 0 1\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                            "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                            "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n");
        const CliResult r = runCli("hydrostatics " + obj + " --method texel-centre --texture 8");
        INFO(r.output);
        CHECK(r.exitCode == 2);
        CHECK_THAT(r.output, Contains("texture 8 is too coarse for this mesh"));
    }
    SECTION("a number too large for a double in a scene (fuzz_scene_json)") {
        // nlohmann's out_of_range escaped parseScene: std::terminate (SIGABRT).
        const std::string scene = scratchFile(
            "big.json", "{\"bodies\": [{\"shape\": {\"type\": \"box\", \"size\": [1, 1, 1]}, \"density\": 1e400}]}");
        const CliResult r = runCli("run " + scene + " --out " + scene + ".out");
        INFO(r.output);
        CHECK(r.exitCode == 2);
        CHECK_THAT(r.output, Contains("big.json: invalid JSON: [json.exception.out_of_range.406] number overflow"));
    }
}

#endif
