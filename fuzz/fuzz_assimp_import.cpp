/// @file fuzz_assimp_import.cpp
/// libFuzzer target: importMeshFile (assimp, in-process) on arbitrary bytes saved under an allow-listed
/// extension, then prepareMesh on what it returns. The first byte picks the extension.
/// In process, a crash inside assimp takes this fuzzer down: scripts/fuzz-run.sh tells those apart (top
/// frames in libassimp) and checks that the `buoyancy` CLI, which imports in a child process, turns the
/// same file into a clear error. Known assimp crashes: third_party_notes/assimp.md.
/// Contract checked here (our code): failures end as MeshError; accepted soups have valid indices.
#include "FuzzContract.h"

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

using buoyancy::fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const auto& exts = buoyancy::supportedMeshExtensions();
    const std::string ext = exts[data[0] % exts.size()];
    static const std::string dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        return std::string(tmp && *tmp ? tmp : "/tmp");
    }();
    const std::string path = dir + "/bb-fuzz-" + std::to_string(::getpid()) + ext;
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    }
    buoyancy::TriangleMesh mesh;
    try {
        mesh = buoyancy::importMeshFile(path, 1.0);
    } catch (const buoyancy::MeshError&) {
        std::remove(path.c_str());
        return 0;
    }
    std::remove(path.c_str());
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || std::size_t(t[k]) >= mesh.vertices.size()) violated("vertex index out of range");
    if (!mesh.corner_uvs.empty() && mesh.corner_uvs.size() != 3 * mesh.triangles.size()) violated("UV count");
    try {
        buoyancy::prepareMesh(mesh, "fuzz");
    } catch (const buoyancy::MeshError&) {
    }
    return 0;
}
