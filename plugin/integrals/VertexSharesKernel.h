#pragma once
/// @file VertexSharesKernel.h
/// Pass 2 of the per-vertex exact-mesh hydrostatics (VertexHydrostatics.cpp; the shares are defined in
/// VertexShares.h): the sums over the vertices under water (D ≤ 0) of D B, D T, D² B, B, a and D M, several vertices
/// per instruction (SSE2, AVX2 or AVX-512 chosen at run time, as for the Gerstner queries; VertexSharesKernel.inl).

#include "integrals/VertexShares.h"

#include <cstddef>

namespace buoyancy {

/// Layout of the sums: Σ D B (3, m³), Σ D T (3, about the body origin, m⁴), Σ D² B (3, m⁴), Σ B (3, m²), Σ a (1, m²),
/// Σ D M (9, row-major, m⁴), all over the vertices with D ≤ 0, body frame.
enum ShareSum { kFx, kFy, kFz, kTx, kTy, kTz, kGx, kGy, kGz, kBx, kBy, kBz, kArea, kM, kShareSums = kM + 9 };

/// Add the shares of the vertices 0..n−1 whose D[v] ≤ 0 to out[kShareSums] (D > 0, +∞ or NaN add nothing).
/// @param lanes  0: the widest the CPU runs; 2, 4 or 8 asks for that width (the tests run every width the CPU has), a
///               width the CPU lacks falls back to the widest it has below it
void sumWetShares(const VertexShares& shares, const double* D, std::size_t n, double* out, int lanes = 0);

/// Lanes sumWetShares uses on this CPU by default (8 AVX-512F, 4 AVX2, 2 otherwise).
int vertexKernelLanes();

}  // namespace buoyancy
