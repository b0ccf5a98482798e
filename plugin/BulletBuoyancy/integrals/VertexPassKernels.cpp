/// @file VertexPassKernels.cpp
/// The passes of the per-vertex exact-mesh hydrostatics, several vertices or triangles per instruction
/// (VertexPassKernels.h). Each width compiles VertexPassKernels.inl in its own namespace, force-inlined into a function
/// built for its instruction set (as the Gerstner and drag kernels); the vertices or triangles after the last full vector are
/// done one by one with the same operations.

#include <BulletBuoyancy/integrals/VertexPassKernels.h>

#include <BulletBuoyancy/geometry/VectorMath.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define BB_VERTEX_PASS_X86 1
#endif

// The wide vector types' ABI note is reported at the end of the file: ignored for the whole file (every such function
// is force-inlined into code built for its width).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace buoyancy {
namespace {

using namespace vmath;

namespace sse2 {
using V = v2d;
#include <BulletBuoyancy/integrals/VertexPassKernels.inl>
}  // namespace sse2
#ifdef BB_VERTEX_PASS_X86
namespace avx2 {
using V = v4d;
#include <BulletBuoyancy/integrals/VertexPassKernels.inl>
}  // namespace avx2
namespace avx512 {
using V = v8d;
#include <BulletBuoyancy/integrals/VertexPassKernels.inl>
}  // namespace avx512
__attribute__((target("avx2"))) std::size_t depthsAvx2(const VertexShares& s, const double R[9], const double t[3],
                                                      const WaterPatch::CellGrid& g, double high, double* D) {
    return avx2::depthsKernel(s, R, t, g, high, D);
}
__attribute__((target("avx512f"))) std::size_t depthsAvx512(const VertexShares& s, const double R[9],
                                                           const double t[3], const WaterPatch::CellGrid& g,
                                                           double high, double* D) {
    return avx512::depthsKernel(s, R, t, g, high, D);
}
__attribute__((target("avx2"))) std::size_t heightsAvx2(const WaterPatch::CellGrid& g, const double* x,
                                                       const double* z, std::size_t n, double* out) {
    return avx2::heightsKernel(g, x, z, n, out);
}
__attribute__((target("avx512f"))) std::size_t heightsAvx512(const WaterPatch::CellGrid& g, const double* x,
                                                            const double* z, std::size_t n, double* out) {
    return avx512::heightsKernel(g, x, z, n, out);
}
__attribute__((target("avx2"))) void straddlingAvx2(const VertexShares& s, const double* D, const std::int32_t* list,
                                                    std::size_t count, const double u[3], const double X[3],
                                                    const double Z[3], double xr, double zr, StraddlingSums& out) {
    avx2::straddlingKernel(s, D, list, count, u, X, Z, xr, zr, out);
}
__attribute__((target("avx512f"))) void straddlingAvx512(const VertexShares& s, const double* D,
                                                         const std::int32_t* list, std::size_t count, const double u[3],
                                                         const double X[3], const double Z[3], double xr, double zr,
                                                         StraddlingSums& out) {
    avx512::straddlingKernel(s, D, list, count, u, X, Z, xr, zr, out);
}
__attribute__((target("avx2"))) std::size_t sharesAvx2(const VertexShares& s, const double* D, std::size_t n,
                                                      double* out) {
    return avx2::sharesKernel(s, D, n, out);
}
__attribute__((target("avx512f"))) std::size_t sharesAvx512(const VertexShares& s, const double* D, std::size_t n,
                                                           double* out) {
    return avx512::sharesKernel(s, D, n, out);
}
__attribute__((target("avx2"))) std::size_t trianglesAvx2(const VertexShares& s, const double* D, double S[3],
                                                         std::int32_t* list, std::size_t& listed) {
    return avx2::trianglesKernel(s, D, S, list, listed);
}
__attribute__((target("avx512f"))) std::size_t trianglesAvx512(const VertexShares& s, const double* D, double S[3],
                                                              std::int32_t* list, std::size_t& listed) {
    return avx512::trianglesKernel(s, D, S, list, listed);
}
#endif

/// The interpolant at one point, with WaterPatch::height's operations (the points after the last full vector).
double interpolateOne(const WaterPatch::CellGrid& g, double x, double z) {
    const int last = g.nodes - 3;
    const double lo = 1.0, hi = double(g.nodes - 2);
    const double uc = std::min(std::max((x - g.x0) * g.invH, lo), hi);
    const double vc = std::min(std::max((z - g.z0) * g.invH, lo), hi);
    const int i = std::min(int(uc), last), j = std::min(int(vc), last);
    const double tu = uc - i, tv = vc - j;
    const double* C = g.coefficients + 16 * ((j - 1) * last + (i - 1));
    const double a0 = ((C[12] * tu + C[8]) * tu + C[4]) * tu + C[0];
    const double a1 = ((C[13] * tu + C[9]) * tu + C[5]) * tu + C[1];
    const double a2 = ((C[14] * tu + C[10]) * tu + C[6]) * tu + C[2];
    const double a3 = ((C[15] * tu + C[11]) * tu + C[7]) * tu + C[3];
    return ((a3 * tv + a2) * tv + a1) * tv + a0;
}

}  // namespace

int vertexKernelLanes() {
    static const int lanes = cpuLanes();
    return lanes;
}

namespace {
/// The width to run: the widest the CPU has (lanes ≤ 0), or the one asked for, capped at the widest.
int widthFor(int lanes) { return lanes <= 0 ? vertexKernelLanes() : std::min(lanes, vertexKernelLanes()); }
}  // namespace

void sumWetShares(const VertexShares& s, const double* D, std::size_t n, double* out, int lanes) {
    const int width = widthFor(lanes);
    std::size_t done = 0;
#ifdef BB_VERTEX_PASS_X86
    if (width >= 8)
        done = sharesAvx512(s, D, n, out);
    else if (width >= 4)
        done = sharesAvx2(s, D, n, out);
    else
#endif
        done = sse2::sharesKernel(s, D, n, out);
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

void interpolatePatchHeights(const WaterPatch::CellGrid& g, const double* x, const double* z, std::size_t n,
                             double* out, int lanes) {
    const int width = widthFor(lanes);
    std::size_t done = 0;
#ifdef BB_VERTEX_PASS_X86
    if (width >= 8)
        done = heightsAvx512(g, x, z, n, out);
    else if (width >= 4)
        done = heightsAvx2(g, x, z, n, out);
    else
#endif
        done = sse2::heightsKernel(g, x, z, n, out);
    for (std::size_t k = done; k < n; ++k) out[k] = interpolateOne(g, x[k], z[k]);
}

bool vertexDepthsOnPatch(const VertexShares& s, const double R[9], const double t[3], const WaterPatch::CellGrid& g,
                         double waterHigh, double* D, int lanes) {
    const int width = widthFor(lanes);
    std::size_t done = 0;
#ifdef BB_VERTEX_PASS_X86
    if (width >= 8)
        done = depthsAvx512(s, R, t, g, waterHigh, D);
    else if (width >= 4)
        done = depthsAvx2(s, R, t, g, waterHigh, D);
    else
#endif
        done = sse2::depthsKernel(s, R, t, g, waterHigh, D);
    if (done == SIZE_MAX) return false;
    // The last vertices one by one.
    for (std::size_t v = done; v < s.vertexCount(); ++v) {
        const double qx = s.qx[v], qy = s.qy[v], qz = s.qz[v];
        const double y = R[3] * qx + R[4] * qy + R[5] * qz + t[1];
        const double x = R[0] * qx + R[1] * qy + R[2] * qz + t[0];
        const double z = R[6] * qx + R[7] * qy + R[8] * qz + t[2];
        const double f = interpolateOne(g, x, z);
        if (!std::isfinite(f)) return false;
        D[v] = y > waterHigh ? std::numeric_limits<double>::infinity() : y - f;
    }
    return true;
}

std::size_t sumWetTriangles(const VertexShares& s, const double* D, double S[3], std::int32_t* straddling, int lanes) {
    const int width = widthFor(lanes);
    std::size_t listed = 0, done = 0;
#ifdef BB_VERTEX_PASS_X86
    if (width >= 8)
        done = trianglesAvx512(s, D, S, straddling, listed);
    else if (width >= 4)
        done = trianglesAvx2(s, D, S, straddling, listed);
    else
#endif
        done = sse2::trianglesKernel(s, D, S, straddling, listed);
    for (std::size_t tr = done; tr < s.triangleCount(); ++tr) {
        const double d0 = D[s.corner[0][tr]], d1 = D[s.corner[1][tr]], d2 = D[s.corner[2][tr]];
        const int wet = int(d0 <= 0) + int(d1 <= 0) + int(d2 <= 0);
        const int onWater = int(d0 == 0) + int(d1 == 0) + int(d2 == 0);
        if (wet == 3 && onWater != 2) {
            const double sum = d0 + d1 + d2, s2 = sum * sum;
            S[0] += s2 * s.ax[tr];
            S[1] += s2 * s.ay[tr];
            S[2] += s2 * s.az[tr];
        } else if (wet > 0) {
            straddling[listed++] = std::int32_t(tr);
        }
    }
    return listed;
}

void sumStraddlingTriangles(const VertexShares& s, const double* D, const std::int32_t* list, std::size_t count,
                            const double u[3], const double X[3], const double Z[3], double xr, double zr,
                            StraddlingSums& out, int lanes) {
    const int width = widthFor(lanes);
#ifdef BB_VERTEX_PASS_X86
    if (width >= 8)
        straddlingAvx512(s, D, list, count, u, X, Z, xr, zr, out);
    else if (width >= 4)
        straddlingAvx2(s, D, list, count, u, X, Z, xr, zr, out);
    else
#endif
        sse2::straddlingKernel(s, D, list, count, u, X, Z, xr, zr, out);
}

}  // namespace buoyancy
