/// @file DragKernel.cpp
/// The drag sum over the clusters, several per instruction (DragKernel.h). Per lane the formulas of
/// SampleFormulas.h: the wet fraction bb_drag_wet_ramp, the two-point rule of bb_drag_cluster_accumulate (the cluster
/// split into two halves at ± R C g / sqrt(gᵀ C g), g = Rᵀ(n × ω)), and bb_drag_accumulate at each point. A cluster
/// without a spread along n × ω takes both halves at its centre, which is the single-point sum of the scalar formula
/// split in two equal parts (every term is linear in the area vector and the area). Branches become masks; a lane
/// whose divisor is zero divides by 1 and is masked out, so no lane raises a floating-point exception the scalar
/// code would not. Clusters beyond the last full vector go through the scalar formulas.

#include <BulletBuoyancy/integrals/DragKernel.h>

#include <BulletBuoyancy/geometry/SampleFormulas.h>
#include <BulletBuoyancy/geometry/VectorMath.h>

#include <algorithm>
#include <cmath>

#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#include <immintrin.h>
#define BB_DRAG_X86 1
#endif

// GCC reports the wide vector types' ABI at the end of the file, whatever is pushed and popped: ignored for the whole
// file (every such function is force-inlined into code built for its width).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace buoyancy {
namespace {

using namespace vmath;

/// Lane-wise square root, one lane at a time: the widths whose instruction needs a target region this compiler cannot
/// give (Clang: a target on these always-inline helpers would clash with the untargeted vmath helpers they call, as
/// the Gerstner kernels' do not; the wide code is still generated where they are inlined, in runAvx2 / runAvx512).
template <class V>
BB_VM_INLINE V sqrtLanes(const V& x) {
    V r = x;
    for (int l = 0; l < Traits<V>::N; ++l) r[l] = std::sqrt(x[l]);
    return r;
}

#ifdef BB_DRAG_X86
#define BB_DRAG_SQRT(x) (v2d) _mm_sqrt_pd((__m128d)(x))  // SSE2: every x86-64
#else
#define BB_DRAG_SQRT(x) sqrtLanes<v2d>(x)
#endif
namespace sse2 {
using V = v2d;
#include <BulletBuoyancy/integrals/DragKernelBody.inl>
}  // namespace sse2
#undef BB_DRAG_SQRT
#ifdef BB_DRAG_X86
#if defined(__clang__)
#define BB_DRAG_SQRT(x) sqrtLanes<v4d>(x)
#else  // GCC: the region gives every function below the target, so the intrinsic can be inlined into them
#pragma GCC push_options
#pragma GCC target("avx2")
#define BB_DRAG_SQRT(x) (v4d) _mm256_sqrt_pd((__m256d)(x))
#endif
namespace avx2 {
using V = v4d;
#include <BulletBuoyancy/integrals/DragKernelBody.inl>
}  // namespace avx2
#undef BB_DRAG_SQRT
#if !defined(__clang__)
#pragma GCC pop_options
#endif
#if defined(__clang__)
#define BB_DRAG_SQRT(x) sqrtLanes<v8d>(x)
#else
#pragma GCC push_options
#pragma GCC target("avx512f")
#define BB_DRAG_SQRT(x) (v8d) _mm512_maskz_sqrt_pd(__mmask8(0xff), (__m512d)(x))
#endif
namespace avx512 {
using V = v8d;
#include <BulletBuoyancy/integrals/DragKernelBody.inl>
}  // namespace avx512
#undef BB_DRAG_SQRT
#if !defined(__clang__)
#pragma GCC pop_options
#endif
#endif

std::size_t runSse2(const DragClusterBatch& c, const DragMotion& m, double part[BB_DRAG_TERMS]) { return sse2::run(c, m, part); }
#ifdef BB_DRAG_X86
__attribute__((target("avx2"))) std::size_t runAvx2(const DragClusterBatch& c, const DragMotion& m, double part[BB_DRAG_TERMS]) {
    return avx2::run(c, m, part);
}
__attribute__((target("avx512f"))) std::size_t runAvx512(const DragClusterBatch& c, const DragMotion& m,
                                                        double part[BB_DRAG_TERMS]) {
    return avx512::run(c, m, part);
}
__attribute__((target("avx2"))) std::size_t poseAvx2(const DragClusters& c, const double R[9], const double t[3],
                                                    const DragClusterPose& o) {
    return avx2::pose(c, R, t, o);
}
__attribute__((target("avx512f"))) std::size_t poseAvx512(const DragClusters& c, const double R[9], const double t[3],
                                                         const DragClusterPose& o) {
    return avx512::pose(c, R, t, o);
}
#endif

}  // namespace

int dragKernelLanes() {
    static const int lanes = cpuLanes();
    return lanes;
}

void accumulateClusterDrag(const DragClusterBatch& c, const DragMotion& m, double part[BB_DRAG_TERMS], int lanes) {
    std::size_t done = 0;
    const int width = lanes <= 0 ? dragKernelLanes() : std::min(lanes, dragKernelLanes());
#ifdef BB_DRAG_X86
    if (width >= 8)
        done = runAvx512(c, m, part);
    else if (width >= 4)
        done = runAvx2(c, m, part);
    else
#endif
        done = runSse2(c, m, part);
    // The last clusters one by one through the scalar formulas.
    namespace fm = formulas;
    for (std::size_t i = done; i < c.n; ++i) {
        const double wet = fm::bb_drag_wet_ramp(c.halfHeight[i], c.waterHeight[i] - c.y[i]);
        if (!(wet > 0)) continue;
        const double r[3] = {c.x[i] - m.com[0], c.y[i] - m.com[1], c.z[i] - m.com[2]};
        const double u[3] = {c.ux[i], c.uy[i], c.uz[i]};
        const double C[6] = {c.cxx[i], c.cxy[i], c.cxz[i], c.cyy[i], c.cyz[i], c.czz[i]};
        fm::bb_drag_cluster_accumulate(m.R, C, r, m.v, m.w, u, c.ax[i], c.ay[i], c.az[i], c.area[i], wet, m.kd, m.kf,
                                       m.kl, part);
    }
}

void poseDragClusters(const DragClusters& c, const double R[9], const double t[3], const DragClusterPose& o,
                      int lanes) {
    std::size_t done = 0;
    const int width = lanes <= 0 ? dragKernelLanes() : std::min(lanes, dragKernelLanes());
#ifdef BB_DRAG_X86
    if (width >= 8)
        done = poseAvx512(c, R, t, o);
    else if (width >= 4)
        done = poseAvx2(c, R, t, o);
    else
#endif
        done = sse2::pose(c, R, t, o);
    for (std::size_t i = done; i < c.size(); ++i) {  // the last clusters one by one, the same operations
        const double x = c.px[i], y = c.py[i], z = c.pz[i];
        o.x[i] = R[0] * x + R[1] * y + R[2] * z + t[0];
        o.y[i] = R[3] * x + R[4] * y + R[5] * z + t[1];
        o.z[i] = R[6] * x + R[7] * y + R[8] * z + t[2];
        const double ax = c.ax[i], ay = c.ay[i], az = c.az[i];
        o.ax[i] = R[0] * ax + R[1] * ay + R[2] * az;
        o.ay[i] = R[3] * ax + R[4] * ay + R[5] * az;
        o.az[i] = R[6] * ax + R[7] * ay + R[8] * az;
        const double vy = R[3] * (R[3] * c.cxx[i] + R[4] * c.cxy[i] + R[5] * c.cxz[i]) +
                          R[4] * (R[3] * c.cxy[i] + R[4] * c.cyy[i] + R[5] * c.cyz[i]) +
                          R[5] * (R[3] * c.cxz[i] + R[4] * c.cyz[i] + R[5] * c.czz[i]);
        o.halfHeight[i] = std::sqrt(3.0 * std::max(vy, 0.0));
    }
}

}  // namespace buoyancy
