#pragma once
/// @file VertexShares.h
/// The exact-mesh integrals regrouped by vertex (design.md 2.5, "doing less work"), for water whose height over
/// each triangle is the plane through its corners' heights (the clip of ClippedHydrostatics.cpp). Over a triangle t
/// that is entirely under water, D = y − f is linear, D = Σ_i λ_i D_i, and every integral the action needs is linear
/// in the corner values D_i (or, for ∫ D² n_y, quadratic). With s = q − q_r (q body frame, q_r the reference point)
/// and A_t the triangle's area vector, the edge-midpoint rule gives (exact for these degree ≤ 2 integrands)
///   ∫ D n        = Σ_i D_i A_t / 3
///   ∫ D s × n    = Σ_i D_i (w_i × A_t) − q_r × ∫ D n,            w_i = (q_i + q_a + q_b + q_c) / 12
///   ∫ s D n_y    = Σ_i D_i w_i (A_t · u) − q_r ∫ D n_y,          u = world up in the body frame
///   ∫ D² n_y     = (A_t · u) (Σ_i D_i² + (Σ_i D_i)²) / 12.
/// Summed over the triangles around a vertex v, the corner terms become per-vertex constants (body frame, computed
/// once per mesh): B_v = Σ_t A_t / 3, T_v = Σ_t w_v × A_t, M_v = Σ_t w_v A_tᵀ, a_v = Σ_t |A_t| / 3. A pose then
/// costs one D_v per vertex and a few multiply-adds per wet vertex, instead of a clip and a cross product per
/// triangle; only the triangles that straddle the waterline are clipped (VertexHydrostatics.cpp).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace buoyancy {

/// Per-vertex and per-triangle constants of one mesh (immutable once built; shared by every body using the mesh).
/// Structure of arrays: the per-substep pass streams them.
struct VertexShares {
    // ---- per vertex (index = the mesh's vertex index), body frame ----
    std::vector<double> qx, qy, qz;    ///< vertex position q, m
    std::vector<double> bx, by, bz;    ///< B_v = Σ_{t ∋ v} A_t / 3, m²
    std::vector<double> tx, ty, tz;    ///< T_v = Σ_{t ∋ v} w_{v,t} × A_t (w about the body origin), m³
    std::vector<double> m[9];          ///< M_v = Σ_{t ∋ v} w_{v,t} A_tᵀ, row-major (m[3i + j] = row i, column j), m³
    std::vector<double> area;          ///< a_v = Σ_{t ∋ v} |A_t| / 3, m²
    // ---- per triangle (the mesh's order) ----
    std::vector<std::int32_t> corner[3]; ///< vertex indices
    std::vector<double> ax, ay, az;    ///< area vector A_t = ½ (q_1 − q_0) × (q_2 − q_0), m²
    std::vector<double> absArea;       ///< |A_t|, m²

    /// Number of vertices.
    std::size_t vertexCount() const { return qx.size(); }
    /// Number of triangles.
    std::size_t triangleCount() const { return ax.size(); }
};

/// Build the shares of `mesh` (O(vertices + triangles), once per shape).
/// @throws std::invalid_argument for a vertex index out of range or a non-finite vertex
VertexShares buildVertexShares(const TriangleMesh& mesh);

}  // namespace buoyancy
