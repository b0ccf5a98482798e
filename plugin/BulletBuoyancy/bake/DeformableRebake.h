#pragma once
/// @file DeformableRebake.h
/// Deformable bodies (paper Fig. 17, the balloon): the texel → (triangle, barycentric) map of a
/// baked mesh is fixed while its vertices move, so positions and area vectors are re-baked in one pass over
/// the pieces, with no clipping. Each sample is a list of pieces; piece k covers the fraction w_k (its UV
/// area / its triangle's UV area) of triangle t_k and has its UV centroid at barycentric (β1, β2). Because the
/// UV→3D map is affine per triangle (design.md 1.1), for any vertex positions
///     A_i = Σ w_k A_tri(t_k),  area_i = Σ w_k |A_tri(t_k)|,  p_i = Σ w_k |A_tri(t_k)| c_k / area_i
/// with c_k = a + β1 (b − a) + β2 (c − a): exactly what a fresh bake of the deformed mesh through the same
/// UVs gives. The per-piece formula is bb_rebake_piece (geometry/SampleFormulas.h), shared with the
/// OpenCL kernel kernels/rebake.cl.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace buoyancy {

/// The fixed piece map of one baked mesh (compressed rows: sample i owns pieces pieceStart[i] … pieceStart[i+1]−1).
struct RebakeMap {
    int texture_size = 0;                      ///< N of the N×N texture
    BakeMethod method = BakeMethod::ExactCoverage;
    std::vector<Eigen::Vector3i> triangles;    ///< #T vertex-index triples of the mesh (topology is fixed)
    std::size_t vertexCount = 0;               ///< #V the vertex arrays must have
    std::vector<std::uint32_t> pieceStart;     ///< #S + 1 offsets
    std::vector<std::uint32_t> pieceTriangle;  ///< #P triangle of each piece
    std::vector<double> pieceWeight;           ///< #P w_k = piece UV area / triangle UV area (dimensionless)
    std::vector<double> pieceBeta1, pieceBeta2; ///< #P barycentric coordinates of the piece's centroid
    std::vector<std::uint32_t> texel;          ///< #S texel index y·N + x (increasing, as bakeSurfaceSamples)
    std::vector<std::uint32_t> triangle;       ///< #S triangle of the largest piece at rest (attribute lookups)
    /// Number of samples.
    std::size_t size() const { return texel.size(); }
};

/// Build the map of `mesh` baked through `cornerUvs` at N×N (same rules and sample order as
/// bakeSurfaceSamples: triangles of zero area at rest are left out, samples sorted by texel).
/// @throws std::invalid_argument for N outside 1..16384, a UV array of the wrong size, UVs outside [0,1] or
///         a triangle with zero UV area but non-zero surface area (the messages of bakeSurfaceSamples)
RebakeMap buildRebakeMap(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs, int textureSize,
                         BakeMethod method);

/// Re-bake the samples for new vertex positions (mesh frame, m). `out` gets p, A, area, texel, triangle
/// (resized when needed; no allocation when already of the right size).
/// @param vertices  #V positions, same order as the mesh the map was built from
/// @throws std::invalid_argument when the vertex count differs from map.vertexCount or a vertex is not finite
void rebakeSamples(const RebakeMap& map, const std::vector<Eigen::Vector3d>& vertices, SurfaceSamples& out);

/// rebakeSamples' checks alone: one vertex per mesh vertex of `map`, every one finite.
/// @throws std::invalid_argument naming the count or the vertex
void checkRebakeVertices(const RebakeMap& map, const std::vector<Eigen::Vector3d>& vertices);

}  // namespace buoyancy
