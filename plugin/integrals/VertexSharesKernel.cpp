/// @file VertexSharesKernel.cpp
/// Pass 2 of the per-vertex exact-mesh hydrostatics, several vertices per instruction (VertexSharesKernel.h). Each
/// width compiles VertexSharesKernel.inl in its own namespace, force-inlined into a function built for its instruction
/// set (as the Gerstner kernels); a lane whose D is not ≤ 0 is masked to exact zeros, the vertices after the last full
/// vector are summed one by one.

#include "integrals/VertexSharesKernel.h"

#include "water/VectorMath.h"

#include <algorithm>

#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define BB_VERTEX_X86 1
#endif

// The wide vector types' ABI note is reported at the end of the file: ignored for the whole file (every such function
// is force-inlined into code built for its width).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace buoyancy {
namespace {

using namespace vmath;

namespace sse2 {
using V = v2d;
#include "integrals/VertexSharesKernel.inl"
}  // namespace sse2
#ifdef BB_VERTEX_X86
namespace avx2 {
using V = v4d;
#include "integrals/VertexSharesKernel.inl"
}  // namespace avx2
namespace avx512 {
using V = v8d;
#include "integrals/VertexSharesKernel.inl"
}  // namespace avx512
__attribute__((target("avx2"))) std::size_t sumWetSharesAvx2(const VertexShares& s, const double* D, std::size_t n,
                                                            double* out) {
    return avx2::sumWetShares(s, D, n, out);
}
__attribute__((target("avx512f"))) std::size_t sumWetSharesAvx512(const VertexShares& s, const double* D, std::size_t n,
                                                                 double* out) {
    return avx512::sumWetShares(s, D, n, out);
}
#endif

}  // namespace

int vertexKernelLanes() {
    static const int lanes = cpuLanes();
    return lanes;
}

void sumWetShares(const VertexShares& s, const double* D, std::size_t n, double* out, int lanes) {
    const int width = lanes <= 0 ? vertexKernelLanes() : std::min(lanes, vertexKernelLanes());
    std::size_t done = 0;
#ifdef BB_VERTEX_X86
    if (width >= 8)
        done = sumWetSharesAvx512(s, D, n, out);
    else if (width >= 4)
        done = sumWetSharesAvx2(s, D, n, out);
    else
#endif
        done = sse2::sumWetShares(s, D, n, out);
    // The last vertices one by one.
    for (std::size_t v = done; v < n; ++v) {
        const double d = D[v];
        if (!(d <= 0)) continue;
        const double b[3] = {s.bx[v], s.by[v], s.bz[v]};
        for (int k = 0; k < 3; ++k) {
            out[kFx + k] += d * b[k];
            out[kGx + k] += d * d * b[k];
            out[kBx + k] += b[k];
        }
        out[kTx] += d * s.tx[v];
        out[kTy] += d * s.ty[v];
        out[kTz] += d * s.tz[v];
        out[kArea] += s.area[v];
        for (int k = 0; k < 9; ++k) out[kM + k] += d * s.m[k][v];
    }
}

}  // namespace buoyancy
