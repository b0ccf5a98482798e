#pragma once
/// @file VertexPassKernels.h
/// The passes of the per-vertex exact-mesh hydrostatics (VertexHydrostatics.cpp; the shares are defined in
/// VertexShares.h), several vertices or triangles per instruction (SSE2, AVX2 or AVX-512 chosen at run time, as for the
/// Gerstner queries; VertexPassKernels.inl holds the code of one width):
///  1. vertexDepthsOnPatch: each vertex's depth D_v = y_v − f(x_v, z_v), f the water patch's bicubic (the body → world
///     transform and the interpolation fused; interpolatePatchHeights is the same interpolation at given points);
///  2. sumWetShares: the shares of the vertices under water;
///  3. sumWetTriangles: each triangle's class (entirely wet: its (Σ D_i)² A_t summed; a wet corner but not entirely
///     wet: listed);
///  4. sumStraddlingTriangles: the listed triangles' exact wet parts in closed form.
/// Every lane computes the operations of the one-by-one code in the same order (the wide builds may fuse a multiply
/// and an add), so the depths agree with WaterPatch::height to rounding and the sums differ from one-by-one sums by the
/// order of the additions. Measured on the 3,400-triangle benchmark boat in the scaling sea (AVX-512): an exact evaluation
/// 33 → 20 µs with passes 1, 3 and 4 vectorised (pass 2 was already).

#include <BulletBuoyancy/integrals/VertexShares.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/integrals/WetTriangleIntegrals.h>

#include <cstddef>
#include <cstdint>

namespace buoyancy {

/// Pass 1 on a water patch: D[v] = y_v − f(x_v, z_v) for v in [0, n), (x_v, y_v, z_v) = R q_v + t the world position of
/// the body-frame vertex q_v, f the patch's interpolant (clamped outside its footprint like WaterPatch::height). A
/// vertex with y_v > waterHigh (above every value the interpolant can take) gets D = +∞ (dry; its depth is computed
/// only if a straddling triangle needs it).
/// @param R  body → world rotation, row-major (R[3 i + j] = row i, column j); t  translation, m
/// @param cells  the patch's cells (WaterPatch::cellGrid)
/// @param lanes  0: the widest the CPU runs; 2, 4 or 8 asks for that width (falls back to the widest below it)
/// @return false when an interpolated height was not finite (D is then unusable)
bool vertexDepthsOnPatch(const VertexShares& shares, const double R[9], const double t[3],
                         const WaterPatch::CellGrid& cells, double waterHigh, double* D, int lanes = 0);

/// Layout of the sums: Σ D B (3, m³), Σ D T (3, about the body origin, m⁴), Σ D² B (3, m⁴), Σ B (3, m²), Σ a (1, m²),
/// Σ D M (9, row-major, m⁴), all over the vertices with D ≤ 0, body frame.
enum ShareSum { kFx, kFy, kFz, kTx, kTy, kTz, kGx, kGy, kGz, kBx, kBy, kBz, kArea, kM, kShareSums = kM + 9 };

/// Add the shares of the vertices 0..n−1 whose D[v] ≤ 0 to out[kShareSums] (D > 0, +∞ or NaN add nothing).
/// @param lanes  0: the widest the CPU runs; 2, 4 or 8 asks for that width (the tests run every width the CPU has), a
///               width the CPU lacks falls back to the widest it has below it
void sumWetShares(const VertexShares& shares, const double* D, std::size_t n, double* out, int lanes = 0);

/// Lanes the kernels of this file use on this CPU by default (8 AVX-512F, 4 AVX2, 2 otherwise).
int vertexKernelLanes();

/// The patch's interpolant at the world points (x[k], z[k]), k < n (WaterPatch::heights for many points): the
/// operations of WaterPatch::height lane by lane (clamped outside the footprint; x, z finite).
/// @param cells  the patch's cells (WaterPatch::cellGrid)
/// @param lanes  as for vertexDepthsOnPatch
void interpolatePatchHeights(const WaterPatch::CellGrid& cells, const double* x, const double* z, std::size_t n,
                             double* outHeight, int lanes = 0);

/// Pass 3: over every triangle of `shares` with the depths D of its corners,
///  - all three corners wet (D ≤ 0) and not two of them exactly on the water: S += (D_0 + D_1 + D_2)² A_t (m⁴);
///  - otherwise, at least one corner wet: its index appended to `straddling` (room for every triangle).
/// @param S  three sums (x, y, z; added to)
/// @param lanes  as for vertexDepthsOnPatch
/// @return the number of triangles listed
std::size_t sumWetTriangles(const VertexShares& shares, const double* D, double S[3], std::int32_t* straddling,
                            int lanes = 0);

/// What pass 4 adds for the listed triangles: their wet parts less the shares pass 2 added for their wet corners, body
/// frame, about the body origin, each sum scaled as noted (the divisions are left to the caller), and the waterline's
/// segments (world horizontal coordinates relative to the reference point).
struct StraddlingSums {
    double F[3] = {0, 0, 0};  ///< ∫ D n × 3, m³
    double T[3] = {0, 0, 0};  ///< ∫ D q × n × 12, m⁴
    double Q[3] = {0, 0, 0};  ///< ∫ q D n_y × 12, m⁴
    double B[3] = {0, 0, 0};  ///< ∫ n × 3, m²
    double D2 = 0;            ///< ∫ D² n_y × 12, m⁴
    double area = 0;          ///< wetted area × 3, m²
    WaterlineSums waterline;  ///< the wet parts' edges on the water
};

/// Pass 4: the triangles list[0, count) (from sumWetTriangles) in closed form (the derivation is in
/// VertexHydrostatics.cpp), several per instruction, added to `out`.
/// @param D  depths with every corner of a listed triangle finite
/// @param u  world up in the body frame; X, Z  world x and z in the body frame (the rows of R)
/// @param xr, zr  X·q_r and Z·q_r, the reference point's world horizontal coordinates about the body origin, m
/// @param lanes  as for vertexDepthsOnPatch
void sumStraddlingTriangles(const VertexShares& shares, const double* D, const std::int32_t* list, std::size_t count,
                            const double u[3], const double X[3], const double Z[3], double xr, double zr,
                            StraddlingSums& out, int lanes = 0);

}  // namespace buoyancy
