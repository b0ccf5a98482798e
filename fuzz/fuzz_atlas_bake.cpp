/// @file fuzz_atlas_bake.cpp
/// libFuzzer target: UV layout choice (the model's UVs or a generated atlas) and baking by both methods
/// on arbitrary soups that prepareMesh accepts, then the sampled mass properties.
/// One extra leading byte picks the texture size (1..256) and the options.
/// Contract checked: failures are std::runtime_error / std::invalid_argument / MeshError with a message;
/// UVs in [0,1]², samples finite and non-negative in area, mass properties finite.
#include "FuzzMeshDecode.h"

#include <BulletBuoyancy/atlas/UvLayout.h>
#include <BulletBuoyancy/bake/BakeSamples.h>
#include <BulletBuoyancy/integrals/MassProperties.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

using buoyancy::fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    buoyancy::fuzz::ByteReader in(data, size);
    const std::uint8_t options = in.u8();
    const int textureSize = 1 + in.u8();  // 1..256: small enough for thousands of runs per second
    const bool preferModelUvs = (options & 1) != 0;
    const buoyancy::BakeMethod method =
        (options & 2) ? buoyancy::BakeMethod::TexelCentre : buoyancy::BakeMethod::ExactCoverage;
    buoyancy::TriangleMesh mesh;
    if (!buoyancy::fuzz::decodePreparedSoup(in, 512, mesh)) return 0;
    buoyancy::UvLayout layout;
    try {
        layout = buoyancy::chooseUvLayout(mesh, textureSize, preferModelUvs);
    } catch (const std::runtime_error& e) {
        if (!*e.what()) violated("empty atlas error message");
        return 0;
    }
    if (layout.corner_uvs.size() != 3 * mesh.triangles.size()) violated("UV count");
    for (const auto& uv : layout.corner_uvs)
        if (!uv.allFinite() || uv.minCoeff() < 0 || uv.maxCoeff() > 1) violated("UV outside [0,1]^2");
    buoyancy::SurfaceSamples s;
    try {
        s = buoyancy::bakeSurfaceSamples(mesh, layout.corner_uvs, textureSize, method);
    } catch (const std::invalid_argument&) {
        violated("bake rejected a layout chooseUvLayout produced");
    }
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (!std::isfinite(s.px[i]) || !std::isfinite(s.py[i]) || !std::isfinite(s.pz[i]) || !std::isfinite(s.ax[i]) ||
            !std::isfinite(s.ay[i]) || !std::isfinite(s.az[i]) || !std::isfinite(s.area[i]))
            violated("non-finite sample");
        if (s.area[i] < 0) violated("negative sample area");
        if (s.texel[i] >= std::uint32_t(textureSize) * std::uint32_t(textureSize)) violated("texel index");
        if (s.triangle[i] >= mesh.triangles.size()) violated("triangle index");
    }
    // A texture too coarse for the mesh can give a non-positive sampled volume: a clear invalid_argument
    // (btBuoyancyShape::create and the CLI pass it on as bad input).
    try {
        const buoyancy::MassProperties mp = buoyancy::solidMassProperties(s, 1.0);
        if (!std::isfinite(mp.volume) || !(mp.volume > 0) || !mp.inertia.allFinite() || !mp.centre.allFinite())
            violated("non-finite sampled mass properties");
    } catch (const std::invalid_argument& e) {
        if (!*e.what()) violated("empty mass-properties error message");
    }
    return 0;
}
