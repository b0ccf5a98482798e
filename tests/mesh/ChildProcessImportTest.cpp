// Import in a child process: same result as in-process, errors passed through, and a crash or a hang
// of the importer (simulated with the test-only fault hook) becomes a clean MeshError.

#include "scene/ChildProcessImport.h"
#include <BulletBuoyancy/mesh/MeshImport.h>
#include "mesh/MeshTestUtil.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>

#include <unistd.h>

using namespace buoyancy;
using namespace mesh_test;
using buoyancy::cli::ChildImportTestFault;
using buoyancy::cli::importMeshInChildProcess;
using buoyancy::cli::setChildImportTestFaultForTesting;
using Catch::Matchers::Equals;

namespace {
/// Resets the fault hook even when a check throws.
struct FaultGuard {
    explicit FaultGuard(ChildImportTestFault f) { setChildImportTestFaultForTesting(f); }
    ~FaultGuard() { setChildImportTestFaultForTesting(ChildImportTestFault::None); }
};
}  // namespace

TEST_CASE("child import: same soup as in-process, UVs and warnings included", "[mesh][child]") {
    for (const std::string& path : {model("glTF2/BoxTextured-glTF/BoxTextured.gltf"), model("OBJ/testmixed.obj"),
                                    data("node_transforms.gltf")}) {
        INFO(path);
        std::vector<MeshWarning> wIn, wChild;
        const TriangleMesh a = importMeshFile(path, 2.5, &wIn);
        const TriangleMesh b = importMeshInChildProcess(path, 2.5, 10.0, &wChild);
        CHECK(a.vertices == b.vertices);
        CHECK(a.triangles == b.triangles);
        CHECK(a.corner_uvs == b.corner_uvs);
        REQUIRE(wIn.size() == wChild.size());
        for (std::size_t i = 0; i < wIn.size(); ++i) CHECK(wIn[i].message == wChild[i].message);
    }
}

TEST_CASE("child import: import errors come back unchanged", "[mesh][child][errors]") {
    CHECK_THROWS_WITH(importMeshInChildProcess(data("empty.obj"), 1.0, 10.0, nullptr), Equals("empty.obj: empty file"));
    CHECK_THROWS_WITH(importMeshInChildProcess(data("nope.stl"), 1.0, 10.0, nullptr), Equals("nope.stl: file not found"));
    CHECK_THROWS_AS(importMeshInChildProcess(data("box.xyz"), 1.0, 10.0, nullptr), MeshError);
}

TEST_CASE("child import: a hanging importer is killed at the time limit", "[mesh][child][errors]") {
    FaultGuard guard(ChildImportTestFault::Hang);
    const auto t0 = std::chrono::steady_clock::now();
    CHECK_THROWS_WITH(importMeshInChildProcess(model("OBJ/box.obj"), 1.0, 0.3, nullptr),
                      Equals("box.obj: import timed out after 0.3 s"));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(seconds >= 0.3);
    CHECK(seconds < 3.0);
}

TEST_CASE("child import: a crashing importer is reported with its signal", "[mesh][child][errors]") {
    FaultGuard guard(ChildImportTestFault::Crash);
    CHECK_THROWS_WITH(importMeshInChildProcess(model("OBJ/box.obj"), 1.0, 10.0, nullptr),
                      Equals("box.obj: importer crashed (signal 11)"));
}

TEST_CASE("child import: a large mesh (tens of MB through the pipe) does not deadlock", "[mesh][child]") {
    // Binary STL of 300 000 facets (a soup: 900 000 vertices, ~22 MB of doubles back through the pipe).
    const std::string path = "/tmp/buoyancy_mesh_test_large_" + std::to_string(::getpid()) + ".stl";
    const std::uint32_t n = 300000;
    {
        std::ofstream f(path, std::ios::binary);
        char header[80] = {};
        f.write(header, 80);
        f.write(reinterpret_cast<const char*>(&n), 4);
        for (std::uint32_t i = 0; i < n; ++i) {
            const float x = static_cast<float>(i % 1000), z = static_cast<float>(i / 1000);
            const float facet[12] = {0, 1, 0, x, 0, z, x, 0, z + 1, x + 1, 0, z};
            f.write(reinterpret_cast<const char*>(facet), sizeof facet);
            const std::uint16_t attr = 0;
            f.write(reinterpret_cast<const char*>(&attr), 2);
        }
    }
    const TriangleMesh m = importMeshInChildProcess(path, 1.0, 60.0, nullptr);
    std::remove(path.c_str());
    REQUIRE(m.triangleCount() == n);
    CHECK(m.vertices.size() == 3 * n);
    CHECK(m.vertices[m.triangles.back()[2]] == Eigen::Vector3d(999 + 1, 0, 299));
}
