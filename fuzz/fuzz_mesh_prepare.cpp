/// @file fuzz_mesh_prepare.cpp
/// libFuzzer target: prepareMesh (welding, degenerate removal, closedness/orientation checks) on
/// arbitrary triangle soups, then the exact polyhedral mass properties of what it accepts.
/// Contract checked: bad input ends as buoyancy::MeshError; an accepted mesh is closed with finite
/// coordinates, valid indices, UVs that followed their triangles, and finite positive volume.
#include "FuzzMeshDecode.h"

#include <BulletBuoyancy/integrals/MassProperties.h>

#include <cmath>

using buoyancy::fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    buoyancy::fuzz::ByteReader in(data, size);
    // Header bit 6 (FuzzMeshDecode.h): per-corner UVs; an accepted soup had at least one triangle, so UVs.
    const bool hadUvs = size > 0 && (data[0] & 0x40) != 0;
    buoyancy::TriangleMesh mesh;
    if (!buoyancy::fuzz::decodePreparedSoup(in, 4096, mesh)) return 0;
    if (mesh.triangles.empty()) violated("accepted mesh without triangles");
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || std::size_t(t[k]) >= mesh.vertices.size()) violated("vertex index out of range");
    for (const auto& v : mesh.vertices)
        if (!v.allFinite()) violated("non-finite vertex accepted");
    if (hadUvs && !mesh.hasUvs()) violated("UVs lost");
    const buoyancy::MassProperties mp = buoyancy::polyhedronMassProperties(mesh, 1.0);
    if (!std::isfinite(mp.volume) || !(mp.volume > 0)) violated("accepted mesh has no positive finite volume");
    if (!mp.inertia.allFinite() || !mp.centre.allFinite()) violated("non-finite mass properties");
    return 0;
}
