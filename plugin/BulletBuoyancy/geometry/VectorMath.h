#pragma once
/// @file VectorMath.h
/// Double-precision SIMD vectors of 2, 4 or 8 lanes and the lane-wise sin/cos and exp of the batch Gerstner
/// queries (btGerstnerWaterSurface.cpp). GCC/Clang vector extensions: the baseline x86-64 build gets SSE2
/// code for v2d; v4d and v8d become AVX2 / AVX-512 code inside functions compiled with the matching target
/// attribute (runtime dispatch, the library's flags stay baseline). Every function is lane-wise — no lane reads
/// another — and the operations are plain IEEE additions and multiplications (no fused multiply-add: ISO C++
/// mode does not contract), so a lane computes bit for bit the same value at every width and next to any other
/// point. Everything is force-inlined, so the callers' target attribute decides the instructions.
///
/// Accuracy (double, measured against long double on 10⁶ random arguments): sincos ≤ 2.1e-16 absolute for
/// |x| ≤ kSinCosFastLimit (Cody–Waite reduction by π/2 in three parts, then the Taylor series of sin and cos on
/// |r| ≤ π/4 to degree 15/16, truncation < 5e-17); larger or non-finite lanes go to std::sin/std::cos. exp ≤ ~2 ulp
/// on [−708, 709] (reduction by ln 2, Taylor to degree 13 on |r| ≤ ln2/2, truncation < 5e-18); other lanes go to
/// std::exp.

#include <cmath>
#include <cstdint>
#include <cstring>

#if !defined(__GNUC__) && !defined(__clang__)
#error "plugin/BulletBuoyancy/geometry/VectorMath.h needs the GCC/Clang vector extensions"
#endif

/// Force-inline (the caller's target attribute then applies to the inlined code).
#define BB_VM_INLINE inline __attribute__((always_inline))

// Returning v4d/v8d is only an ABI question for out-of-line calls, and every function here is inlined into code
// compiled for the matching instruction set: GCC's warning about it does not apply. (Arguments are passed by
// reference for the same reason: GCC notes a by-value 64-byte argument even when it is inlined.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace buoyancy {
namespace vmath {

typedef double v2d __attribute__((vector_size(16)));  ///< 2 doubles (SSE2)
typedef double v4d __attribute__((vector_size(32)));  ///< 4 doubles (AVX2)
typedef double v8d __attribute__((vector_size(64)));  ///< 8 doubles (AVX-512)

/// Widest SIMD this CPU runs, in doubles: 8 (AVX-512F), 4 (AVX2) or 2 (SSE2; every x86-64, and the only width
/// elsewhere). The batch kernels (Gerstner queries, drag, the per-vertex shares) dispatch on it at run time.
inline int cpuLanes() {
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f")) return 8;
    if (__builtin_cpu_supports("avx2")) return 4;
#endif
    return 2;
}

/// Lane count and mask type (64-bit unsigned lanes, all ones where true) of a vector type.
template <class V>
struct Traits;
template <>
struct Traits<v2d> {
    enum { N = 2 };
    typedef std::uint64_t U __attribute__((vector_size(16)));
};
template <>
struct Traits<v4d> {
    enum { N = 4 };
    typedef std::uint64_t U __attribute__((vector_size(32)));
};
template <>
struct Traits<v8d> {
    enum { N = 8 };
    typedef std::uint64_t U __attribute__((vector_size(64)));
};
template <class V>
using Mask = typename Traits<V>::U;

/// Every lane = a.
template <class V>
BB_VM_INLINE V splat(double a) {
    return V{} + a;
}
/// N consecutive doubles from p (any alignment).
template <class V>
BB_VM_INLINE V load(const double* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
/// N consecutive doubles to p (any alignment).
template <class V>
BB_VM_INLINE void store(double* p, const V& v) {
    std::memcpy(p, &v, sizeof v);
}
/// Bit pattern of each lane.
template <class V>
BB_VM_INLINE Mask<V> bits(const V& v) {
    return (Mask<V>)v;
}
/// Lanes from a bit pattern.
template <class V>
BB_VM_INLINE V fromBits(const Mask<V>& u) {
    return (V)u;
}
/// Mask of a lane-wise comparison result.
template <class V, class M>
BB_VM_INLINE Mask<V> mask(const M& m) {
    return (Mask<V>)m;
}
/// Lane-wise m ? a : b.
template <class V>
BB_VM_INLINE V select(const Mask<V>& m, const V& a, const V& b) {
    return fromBits<V>((m & bits(a)) | (~m & bits(b)));
}
/// |v| per lane.
template <class V>
BB_VM_INLINE V abs(const V& v) {
    return fromBits<V>(bits(v) & (Mask<V>{} + 0x7fffffffffffffffULL));
}
/// Lane-wise max (a NaN in a gives b).
template <class V>
BB_VM_INLINE V max(const V& a, const V& b) {
    return select<V>(mask<V>(a > b), a, b);
}
/// Lane-wise min (a NaN in a gives b).
template <class V>
BB_VM_INLINE V min(const V& a, const V& b) {
    return select<V>(mask<V>(a < b), a, b);
}
/// The lanes of m OR-ed (or AND-ed, And = true) together, by halving the vector: log₂ N shuffles and ORs instead of N
/// lane extractions (the wide masks' tests sit in the vertex and triangle passes' inner loops).
template <bool And, class M>
BB_VM_INLINE std::uint64_t reduceLanes(const M& m) {
    constexpr unsigned N = sizeof(M) / 8;
    if constexpr (N == 8) {
        typedef std::uint64_t H __attribute__((vector_size(32)));
        const H lo = __builtin_shufflevector(m, m, 0, 1, 2, 3), hi = __builtin_shufflevector(m, m, 4, 5, 6, 7);
        return reduceLanes<And>(And ? H(lo & hi) : H(lo | hi));
    } else if constexpr (N == 4) {
        typedef std::uint64_t H __attribute__((vector_size(16)));
        const H lo = __builtin_shufflevector(m, m, 0, 1), hi = __builtin_shufflevector(m, m, 2, 3);
        return reduceLanes<And>(And ? H(lo & hi) : H(lo | hi));
    } else {
        static_assert(N == 2, "2, 4 or 8 lanes");
        return And ? (m[0] & m[1]) : (m[0] | m[1]);
    }
}
/// True when any lane of m is set.
template <class M>
BB_VM_INLINE bool any(const M& m) {
    return reduceLanes<false>(m) != 0;
}
/// True when every lane of m is set.
template <class M>
BB_VM_INLINE bool all(const M& m) {
    return reduceLanes<true>(m) == ~std::uint64_t(0);
}

/// 1/j! for j = 0 … 16 (the Taylor coefficients below).
constexpr double kInvFactorial[17] = {1.0,
                                      1.0,
                                      0.5,
                                      1.6666666666666666667e-01,
                                      4.1666666666666666667e-02,
                                      8.3333333333333333333e-03,
                                      1.3888888888888888889e-03,
                                      1.9841269841269841270e-04,
                                      2.4801587301587301587e-05,
                                      2.7557319223985890653e-06,
                                      2.7557319223985890653e-07,
                                      2.5052108385441718775e-08,
                                      2.0876756987868098979e-09,
                                      1.6059043836821614599e-10,
                                      1.1470745597729724714e-11,
                                      7.6471637318198164759e-13,
                                      4.7794773323873852974e-14};
/// 1/j! in every lane.
template <class V>
BB_VM_INLINE V invFactorial(int j) {
    return splat<V>(kInvFactorial[j]);
}

/// Arguments up to this magnitude take the vector path of sincos (the quotient n = round(2x/π) stays below 2^20,
/// so n times the 33-bit leading parts of π/2 is exact).
constexpr double kSinCosFastLimit = 1.0e6;
/// 1.5·2^52: x + it − it rounds x to an integer (|x| < 2^51), whose low bits are then in the mantissa of x + it.
constexpr double kRoundMagic = 6755399441055744.0;

/// sin and cos of r for |r| ≤ π/4 (and beyond, less accurately): Taylor series, sin to r^15, cos to r^16
/// (the next terms are < 5e-17 and < 3e-18 at π/4), Horner with alternating signs.
template <class V>
BB_VM_INLINE void sincosCore(const V& r, V& s, V& c) {
    const V z = r * r;
    // sin r = r − r z (1/3! − z (1/5! − z (… − z/15!)))
    V u = invFactorial<V>(15);
    for (int j = 13; j >= 3; j -= 2) u = invFactorial<V>(j) - z * u;
    s = r - r * z * u;
    // cos r = 1 − z (1/2! − z (1/4! − z (… − z/16!)))
    V v = invFactorial<V>(16);
    for (int j = 14; j >= 2; j -= 2) v = invFactorial<V>(j) - z * v;
    c = invFactorial<V>(0) - z * v;
}

/// sin and cos of every lane of x (see the file comment for the accuracy).
template <class V>
BB_VM_INLINE void sincos(const V& x, V& s, V& c) {
    // Lanes beyond the fast range or not finite (NaN compares false, so it stays on the fast path and gives NaN).
    if (any(mask<V>(abs(x) > kSinCosFastLimit))) {
        for (int l = 0; l < Traits<V>::N; ++l) {
            s[l] = std::sin(x[l]);
            c[l] = std::cos(x[l]);
        }
        return;
    }
    // n = round(x · 2/π): the low mantissa bits of q hold n (mod 2^51, two's complement).
    const V q = x * 0.63661977236758134308 + kRoundMagic;
    const V n = q - kRoundMagic;
    // r = x − n π/2 with π/2 = a + b + c (a, b have 33 significant bits: n·a and n·b are exact).
    V r = x - n * 1.57079632673412561417e+00;  // a = 0x3FF921FB54400000
    r = r - n * 6.07710050630396597660e-11;    // b = 0x3DD0B4611A600000
    r = r - n * 2.02226624879595063154e-21;    // c = π/2 − a − b
    V sr, cr;
    sincosCore(r, sr, cr);
    // Quadrant n mod 4: sin x = (sr, cr, −sr, −cr)[n], cos x = (cr, −sr, −cr, sr)[n].
    const Mask<V> qi = bits(q);
    const Mask<V> odd = mask<V>((qi & 1) != 0);
    const V s0 = select<V>(odd, cr, sr), c0 = select<V>(odd, sr, cr);
    s = fromBits<V>(bits(s0) ^ ((qi & 2) << 62));
    c = fromBits<V>(bits(c0) ^ (((qi + 1) & 2) << 62));
}

/// e^x for every lane (lanes outside [−708, 709] or NaN: std::exp).
template <class V>
BB_VM_INLINE V exp(const V& x) {
    if (!all(mask<V>(x >= -708.0) & mask<V>(x <= 709.0))) {
        V e;
        for (int l = 0; l < Traits<V>::N; ++l) e[l] = std::exp(x[l]);
        return e;
    }
    const V q = x * 1.44269504088896340736 + kRoundMagic;  // n = round(x / ln 2)
    const V n = q - kRoundMagic;
    // r = x − n ln 2 with ln 2 = a + b (a = 0x3FE62E42FEE00000 has 32 significant bits: n·a is exact), |r| ≤ ln2/2
    const V r = (x - n * 6.93147180369123816490e-01) - n * 1.90821492927058770002e-10;
    // e^r = Σ_{j ≤ 13} r^j / j!
    V p = invFactorial<V>(13);
    for (int j = 12; j >= 0; --j) p = p * r + invFactorial<V>(j);
    // 2^n from the exponent field (n ∈ [−1022, 1023] on this range).
    const Mask<V> ni = bits(q) - bits(splat<V>(kRoundMagic));
    return p * fromBits<V>((ni + 1023) << 52);
}

}  // namespace vmath
}  // namespace buoyancy

#pragma GCC diagnostic pop
