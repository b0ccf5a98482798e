#pragma once
/// @file BakeSamples.h
/// Baking the position and area-vector textures into compacted surface samples (design.md 1.1).

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

namespace buoyancy {

/// Bake samples of `mesh` through the per-corner UVs `cornerUvs` (3·#T, in [0,1]²) at N×N texels.
/// TexelCentre: the paper's rasterisation by texel centre. ExactCoverage: Sutherland–Hodgman clipping of
/// each triangle's UV polygon against each texel square (mirrored UV triangles handled), areas and
/// centroids exact, so Σ A_i = Σ A_tri = 0 on a closed mesh up to rounding. Double precision.
/// @throws std::invalid_argument for N < 1 or N > 16384, or a UV array of the wrong size
SurfaceSamples bakeSurfaceSamples(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs,
                                  int textureSize, BakeMethod method);

}  // namespace buoyancy
