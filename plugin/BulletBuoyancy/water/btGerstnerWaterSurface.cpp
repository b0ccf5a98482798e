#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

// No fused multiply-add anywhere in this file: the AVX-512 kernel must round like the SSE2 one (see Kernel).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#define BB_NO_CONTRACT
#else
#define BB_NO_CONTRACT __attribute__((optimize("fp-contract=off")))
#endif

#include <BulletBuoyancy/geometry/VectorMath.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <typeinfo>
#include <string>

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
/// Error of heights and velocities the inversion leaves, relative to Σ A and Σ A ω (asks 1e-12).
constexpr double kRelativeAccuracy = 1e-14;
/// Rounding noise of a Newton step per metre of |x| (a few ulps; divided by 1 − Σ Q A k for the Jacobian).
constexpr double kRoundingFloor = 8e-16;
/// Largest phase change |k d·Δx₀| a Newton step of the vector path turns sin θ, cos θ through by rotation (the
/// series in rotateSinCos are then exact to < 6e-18); a larger step evaluates them again.
constexpr double kRotateMax = 0.05;
/// Phase changes up to this use the shorter series of rotateSinCosTiny (exact to < 1e-17).
constexpr double kRotateTiny = 1e-3;
/// Longest gap between two cached calls, in units of the gap before it, that still extrapolates the displacement.
constexpr double kMaxExtrapolation = 4.0;
/// Newton steps the vector path takes before a point goes to the scalar solve (never reached in practice).
constexpr int kFastIterations = 16;
/// Waves whose per-call scratch lives on the stack (more: one heap buffer per call, never per point).
constexpr std::size_t kStackWaves = 16;

[[noreturn]] void bad(std::size_t i, const char* field, const std::string& what) {
    throw std::invalid_argument("waves[" + std::to_string(i) + "]." + field + ": " + what);
}
}  // namespace

btGerstnerWaterSurface::btGerstnerWaterSurface(const std::vector<btGerstnerWave>& waves, double height, double gravity)
    : m_height(height) {
    if (!std::isfinite(height)) throw std::invalid_argument("height: must be a finite number");
    if (!std::isfinite(gravity) || !(gravity > 0)) throw std::invalid_argument("gravity: must be a finite number > 0");
    for (std::size_t i = 0; i < waves.size(); ++i) {
        const btGerstnerWave& w = waves[i];
        if (!std::isfinite(w.amplitude) || w.amplitude < 0) bad(i, "amplitude", "must be a finite number >= 0");
        if (!std::isfinite(w.wavelength) || !(w.wavelength > 0)) bad(i, "wavelength", "must be a finite number > 0");
        if (!std::isfinite(w.steepness) || w.steepness < 0) bad(i, "steepness", "must be a finite number >= 0");
        if (!std::isfinite(w.phase)) bad(i, "phase", "must be a finite number");
        const double len = std::hypot(w.directionX, w.directionZ);
        if (!std::isfinite(len) || !(len > 0)) bad(i, "direction", "must be a finite, non-zero [dx, dz]");
        Wave v;
        v.a = w.amplitude;
        v.k = kTwoPi / w.wavelength;
        v.omega = std::sqrt(gravity * v.k);  // deep-water dispersion ω² = g k
        v.dx = w.directionX / len;
        v.dz = w.directionZ / len;
        v.qa = w.steepness * w.amplitude;
        v.phase = w.phase;
        v.kdx = v.k * v.dx;
        v.kdz = v.k * v.dz;
        v.qadx = v.qa * v.dx;
        v.qadz = v.qa * v.dz;
        v.jxx = v.qa * v.k * v.dx * v.dx;
        v.jxz = v.qa * v.k * v.dx * v.dz;
        v.jzz = v.qa * v.k * v.dz * v.dz;
        v.qak2 = v.qa * v.k * v.k;
        v.qawdx = v.qa * v.omega * v.dx;
        v.qawdz = v.qa * v.omega * v.dz;
        v.aw = v.a * v.omega;
        v.qaw = v.qa * v.omega;
        m_amplitudeSum += v.a;
        if (v.a > 0 && (m_shortestWavelength == 0 || w.wavelength < m_shortestWavelength))
            m_shortestWavelength = w.wavelength;
        m_loop += v.qa * v.k;
        m_waves.push_back(v);
    }
    if (!(m_loop < 1.0)) {
        std::ostringstream os;
        os << "waves: sum of steepness*amplitude*k = " << m_loop
           << " >= 1: the Gerstner surface loops (no longer a height field); lower the steepness or amplitude";
        throw std::invalid_argument(os.str());
    }
    // Stopping rule: after a Newton step δ from a point where the waves were evaluated exactly, the
    // rest position is off by ≤ κ|δ|², κ = ½ Σ Q A k² / (1 − Σ Q A k) (second-order Taylor remainder of the
    // horizontal map through the inverse Jacobian); heights and velocities then move by ≤ k_max κ|δ|² of Σ A and
    // Σ A ω. So steps ≤ sqrt(kRelativeAccuracy / (κ k_max)) end the solve (that last step is still applied).
    double kMax = 0, curvature = 0;
    for (const Wave& w : m_waves) {
        kMax = std::max(kMax, w.k);
        curvature += w.qa * w.k * w.k;
    }
    const double kappa = 0.5 * curvature / (1.0 - m_loop);
    if (kMax > 0) {
        m_tolStep = 1e-3 / kMax;  // also keeps the last step's phase change inside kRotateTiny
        if (kappa > 0) m_tolStep = std::min(m_tolStep, std::sqrt(kRelativeAccuracy / (kappa * kMax)));
    }
    // The batch queries end with one Chebyshev step δ = δN − ½ J⁻¹ F''[δN, δN] (F = x₀ − D(x₀) − x, δN the
    // Newton step): by Taylor's theorem its error is ≤ g (c₃/6 + g c₂²/2) |δN|³ (g = ‖J⁻¹‖ ≤ 1/(1 − Σ Q A k),
    // c₂ = ‖F''‖ ≤ Σ Q A k², c₃ = ‖F'''‖ ≤ Σ Q A k³), taken twice for margin.
    double c3 = 0;
    for (const Wave& w : m_waves) c3 += w.qa * w.k * w.k * w.k;
    const double g = 1.0 / (1.0 - m_loop), cheb = 2.0 * g * (c3 / 6.0 + g * curvature * curvature);
    if (kMax > 0) {
        m_tolFinish = 1e-3 / kMax;
        if (cheb > 0) m_tolFinish = std::min(m_tolFinish, std::cbrt(kRelativeAccuracy / (cheb * kMax)));
    }
    m_noise = kRoundingFloor / (1.0 - m_loop);
    m_lanes = buoyancy::vmath::cpuLanes();
}

void btGerstnerWaterSurface::setSimdLanes(int lanes) {
    const int cpu = buoyancy::vmath::cpuLanes();
    const int wanted = lanes >= 8 && cpu >= 8 ? 8 : (lanes >= 4 && cpu >= 4 ? 4 : 2);
    if (wanted != m_lanes) touchRevision();
    m_lanes = wanted;
}

std::unique_ptr<btWaterSurface> btGerstnerWaterSurface::cloneForQueriesAhead() const {
    if (typeid(*this) != typeid(btGerstnerWaterSurface)) return nullptr;
    return std::make_unique<btGerstnerWaterSurface>(*this);
}

double btGerstnerWaterSurface::pointTolerance(double x, double z) const {
    return std::max(m_tolStep, m_noise * std::max(std::abs(x), std::abs(z)));
}

void btGerstnerWaterSurface::surfacePoint(double x0, double z0, double t, double& outX, double& outY,
                                          double& outZ) const {
    double x = x0, y = m_height, z = z0;
    for (const Wave& w : m_waves) {
        const double th = w.k * (w.dx * x0 + w.dz * z0) - w.omega * t + w.phase;
        const double s = std::sin(th), c = std::cos(th);
        x -= w.qa * w.dx * s;
        z -= w.qa * w.dz * s;
        y += w.a * c;
    }
    outX = x;
    outY = y;
    outZ = z;
}

// Newton's method on r(x₀) = x₀ − D(x₀) − x with D(x₀) = Σ Q A d sin θ and the symmetric 2×2 Jacobian
// J = I − Σ Q A k cos θ d dᵀ (det J ≥ (1 − Σ Q A k)² > 0). Each loop evaluates the waves once at the current
// x₀ (one sin/cos pair per wave, which also gives the height Σ A cos θ and, with Velocity, the orbital
// velocity), so the solve ends right after an evaluation and its results belong to the returned x₀: once a
// Newton step is ≤ the point's tolerance it is applied and the waves are evaluated one last time. A Newton
// step that did not reduce the residual is replaced by the fixed-point step x₀ ← x + D(x₀) from the previous
// point, a contraction of factor Σ Q A k < 1 (|r'| ≤ Σ Q A k |r|), so the solve always converges.
template <bool Velocity>
int btGerstnerWaterSurface::solve(double x, double z, double t, double& x0, double& z0, double& ySum, double yRel,
                                  double* vel) const {
    const Wave* waves = m_waves.data();
    const std::size_t m = m_waves.size();
    const double depth = std::min(0.0, yRel);
    const double tol = pointTolerance(x, z), tol2 = tol * tol;
    double px = x0, pz = z0, prx = 0, prz = 0, pr2 = std::numeric_limits<double>::infinity();
    bool last = false;
    int it = 0;
    for (;; ++it) {
        double rx = x0 - x, rz = z0 - z, jxx = 1, jxz = 0, jzz = 1, ys = 0, vx = 0, vy = 0, vz = 0;
        for (std::size_t i = 0; i < m; ++i) {
            const Wave& w = waves[i];
            const double th = w.kdx * x0 + w.kdz * z0 + (w.phase - w.omega * t);
            const double s = std::sin(th), c = std::cos(th);
            rx -= w.qadx * s;
            rz -= w.qadz * s;
            jxx -= w.jxx * c;
            jxz -= w.jxz * c;
            jzz -= w.jzz * c;
            ys += w.a * c;
            if (Velocity) {
                // ∂/∂t of the parametric surface (∂θ/∂t = −ω), scaled by the decay below the mean level.
                const double e = depth < 0 ? std::exp(w.k * depth) : 1.0;
                vx += w.qawdx * c * e;
                vz += w.qawdz * c * e;
                vy += w.aw * s * e;
            }
        }
        ySum = ys;
        if (Velocity) {
            vel[0] = vx;
            vel[1] = vy;
            vel[2] = vz;
        }
        if (last || it >= kMaxIterations) break;
        const double r2 = rx * rx + rz * rz;
        if (!(r2 < pr2)) {
            // The Newton step from (px, pz) did not reduce the residual: the fixed-point step from there instead.
            x0 = px - prx;
            z0 = pz - prz;
            pr2 = std::numeric_limits<double>::infinity();
            continue;
        }
        px = x0;
        pz = z0;
        prx = rx;
        prz = rz;
        pr2 = r2;
        const double inv = 1.0 / (jxx * jzz - jxz * jxz);
        const double sx = (jzz * rx - jxz * rz) * inv, sz = (jxx * rz - jxz * rx) * inv;
        last = sx * sx + sz * sz <= tol2;
        x0 -= sx;
        z0 -= sz;
    }
    return it;
}

void btGerstnerWaterSurface::restPosition(double x, double z, double t, double& outX0, double& outZ0,
                                          int* outIterations) const {
    double x0 = x, z0 = z, ys = 0;
    const int it = m_loop > 0 ? solve<false>(x, z, t, x0, z0, ys, 0.0, nullptr) : 0;
    outX0 = x0;
    outZ0 = z0;
    if (outIterations) *outIterations = it;
}

// v4d/v8d by value: only inlined into code compiled for AVX2/AVX-512 (see VectorMath.h).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace {
using namespace buoyancy::vmath;

/// sin φ and cos φ for |φ| ≤ kRotateMax: Taylor to φ⁷ and φ⁸ (remainders ≤ φ⁹/9! < 6e-18, φ¹⁰/10! < 3e-20).
template <class V>
BB_VM_INLINE void rotateSinCos(const V& p, V& s, V& c) {
    const V z = p * p;
    s = p - p * z * (invFactorial<V>(3) - z * (invFactorial<V>(5) - z * invFactorial<V>(7)));
    c = invFactorial<V>(0) -
        z * (invFactorial<V>(2) - z * (invFactorial<V>(4) - z * (invFactorial<V>(6) - z * invFactorial<V>(8))));
}

/// sin φ and cos φ for |φ| ≤ kRotateTiny: φ − φ³/6 and 1 − φ²/2 + φ⁴/24 (remainders < 1e-17, < 2e-21).
template <class V>
BB_VM_INLINE void rotateSinCosTiny(const V& p, V& s, V& c) {
    const V z = p * p;
    s = p - p * z * invFactorial<V>(3);
    c = invFactorial<V>(0) - z * (invFactorial<V>(2) - z * invFactorial<V>(4));
}

/// (s, c) turned through the angle whose sine and cosine are (sp, cp): sin(θ + φ), cos(θ + φ).
template <class V>
BB_VM_INLINE void turn(V& s, V& c, const V& sp, const V& cp) {
    const V s1 = s * cp + c * sp;
    c = c * cp - s * sp;
    s = s1;
}

/// Lanes i … i + N − 1 of p; past the end (index ≥ n) the last point again.
template <class V>
BB_VM_INLINE V gather(const double* p, std::size_t i, std::size_t n) {
    if (i + Traits<V>::N <= n) return load<V>(p + i);
    V v = V{};
    for (int l = 0; l < Traits<V>::N; ++l) v[l] = p[i + l < n ? i + l : n - 1];
    return v;
}

/// The first `count` lanes of v to p[i …].
template <class V>
BB_VM_INLINE void scatter(double* p, std::size_t i, int count, const V& v) {
    if (count == Traits<V>::N) {
        store<V>(p + i, v);
        return;
    }
    for (int l = 0; l < count; ++l) p[i + std::size_t(l)] = v[l];
}

// Keep only finite displacements, so one bad point never poisons the next warm start.
inline double finiteOr0(double d) { return std::isfinite(d) ? d : 0.0; }

/// One batch query's arguments (see btGerstnerWaterSurface::batch).
struct BatchQuery {
    const double *x, *y, *z;
    std::size_t n;
    double t;
    double* const* disp;
    double rho;
    bool shift;
    double *outH, *outVx, *outVy, *outVz;
};
}  // namespace

// The vector path of the batch queries, N points per SIMD vector (VectorMath.h). It is the Newton iteration of
// solve() with three changes. (1) The waves are evaluated with sin/cos once, at the start guess; after that each
// step Δx₀ turns every wave's (sin θ, cos θ) through its phase change φ = k d·Δx₀ by the angle-sum formulas
// (rotateSinCos / rotateSinCosTiny), exact to rounding, so the residual, Jacobian, height and velocity of each
// iterate cost a few multiplications per wave; steps with |φ| > kRotateMax (cold starts) evaluate sin/cos
// again. (2) A Newton step δN ≤ finishTolerance() ends the solve as the Chebyshev step δN − ½ J⁻¹ F''[δN, δN]
// (F'' [u, u] = Σ Q A k² sin θ (d·u)² d), whose error is ≤ 1e-14 of the amplitudes (see the constructor).
// (3) Every decision is taken per lane, so a point's result does not depend on the points beside it, nor on N.
// A lane whose Newton step does not reduce the residual (steep waves far from the solution), or that has not
// converged after kFastIterations steps, or is not finite, is handed to solve() (fixed-point safeguard).
struct btGerstnerWaterSurface::Kernel {
    template <class V, bool Velocity>
    static BB_VM_INLINE void run(const btGerstnerWaterSurface& surface, const BatchQuery& q) {
        constexpr int N = Traits<V>::N;
        typedef Mask<V> M;
        const std::size_t m = surface.m_waves.size(), n = q.n;
        const Wave* W = surface.m_waves.data();
        // Per-call scratch: sin θ, cos θ, φ of the current points per wave.
        alignas(64) V scStack[3 * kStackWaves];
        // More waves: a heap buffer aligned by hand to sizeof(V) (the AVX code stores with aligned moves, but
        // outside the AVX functions GCC reports alignof(v8d) as 16, so neither new nor std::vector would do).
        std::vector<double> scHeap;
        V* S = scStack;
        if (m > kStackWaves) {
            scHeap.resize((3 * m + 1) * N);
            void* p = scHeap.data();
            std::size_t space = scHeap.size() * sizeof(double);
            S = static_cast<V*>(std::align(sizeof(V), 3 * m * sizeof(V), p, space));
        }
        V* C = S + m;
        V* P = C + m;
        const M none = M{};
        const V zero = V{}, inf = splat<V>(std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < n; i += N) {
            const int count = int(std::min<std::size_t>(N, n - i));
            const V X = gather<V>(q.x, i, n), Z = gather<V>(q.z, i, n);
            V GX = X, GZ = Z;  // start guess
            if (q.disp) {
                const V dx = gather<V>(q.disp[0], i, n), dz = gather<V>(q.disp[1], i, n);
                GX = X - (dx + q.rho * (dx - gather<V>(q.disp[2], i, n)));
                GZ = Z - (dz + q.rho * (dz - gather<V>(q.disp[3], i, n)));
            }
            const V floor = surface.m_noise * max(abs(X), abs(Z));
            const V tolF = max(splat<V>(surface.m_tolFinish), floor), tolF2 = tolF * tolF;
            V X0 = GX, Z0 = GZ;
            for (std::size_t w = 0; w < m; ++w)
                sincos<V>(W[w].kdx * X0 + W[w].kdz * Z0 + (W[w].phase - W[w].omega * q.t), S[w], C[w]);
            M done = none, fail = none;
            V pr2 = inf;
            for (int it = 0;; ++it) {
                V rx = X0 - X, rz = Z0 - Z, jxx = splat<V>(1.0), jxz = zero, jzz = splat<V>(1.0);
                for (std::size_t w = 0; w < m; ++w) {
                    rx -= W[w].qadx * S[w];
                    rz -= W[w].qadz * S[w];
                    jxx -= W[w].jxx * C[w];
                    jxz -= W[w].jxz * C[w];
                    jzz -= W[w].jzz * C[w];
                }
                const V r2 = rx * rx + rz * rz;
                const V inv = 1.0 / (jxx * jzz - jxz * jxz);
                // x₀ ← x₀ − (sx, sz): the Newton step J⁻¹ r (J symmetric 2×2)
                V sx = (jzz * rx - jxz * rz) * inv, sz = (jxx * rz - jxz * rx) * inv;
                const M finish = mask<V>(sx * sx + sz * sz <= tolF2);
                fail |= ~done & ~finish & ~mask<V>(r2 < pr2);  // no descent (or NaN): the scalar solve takes the lane
                M active = ~done & ~fail;
                if (it >= kFastIterations) {
                    fail |= active;
                    active = none;
                }
                if (!any(active)) break;
                pr2 = r2;
                const M ending = active & finish;
                if (any(ending)) {
                    // Chebyshev: add ½ J⁻¹ F''[s, s] to the step (F'' is even in s).
                    V gx = zero, gz = zero;
                    for (std::size_t w = 0; w < m; ++w) {
                        const V u = W[w].dx * sx + W[w].dz * sz, qq = W[w].qak2 * S[w] * u * u;
                        gx += qq * W[w].dx;
                        gz += qq * W[w].dz;
                    }
                    sx = select<V>(ending, sx + 0.5 * (jzz * gx - jxz * gz) * inv, sx);
                    sz = select<V>(ending, sz + 0.5 * (jxx * gz - jxz * gx) * inv, sz);
                }
                sx = select<V>(active, sx, zero);
                sz = select<V>(active, sz, zero);
                X0 -= sx;
                Z0 -= sz;
                // sin θ, cos θ at the new x₀: rotate by φ = −k d·s, or evaluate again where |φ| is large. Inactive
                // lanes have φ = 0, which every rotation leaves exactly as they are.
                V big = zero;
                for (std::size_t w = 0; w < m; ++w) {
                    P[w] = -(W[w].kdx * sx + W[w].kdz * sz);
                    big = max(big, abs(P[w]));
                }
                const M tiny = mask<V>(big <= kRotateTiny), rotate = mask<V>(big <= kRotateMax);
                const bool anyTiny = any(tiny & active), anyLong = any(rotate & ~tiny), anyFull = any(~rotate);
                for (std::size_t w = 0; w < m; ++w) {
                    V s = S[w], c = C[w];
                    if (anyTiny) {
                        V sp, cp, s1 = S[w], c1 = C[w];
                        rotateSinCosTiny(P[w], sp, cp);
                        turn(s1, c1, sp, cp);
                        s = select<V>(tiny, s1, s);
                        c = select<V>(tiny, c1, c);
                    }
                    if (anyLong) {
                        V sp, cp, s1 = S[w], c1 = C[w];
                        rotateSinCos(P[w], sp, cp);
                        turn(s1, c1, sp, cp);
                        s = select<V>(rotate & ~tiny, s1, s);
                        c = select<V>(rotate & ~tiny, c1, c);
                    }
                    if (anyFull) {
                        V fs, fc;
                        sincos<V>(W[w].kdx * X0 + W[w].kdz * Z0 + (W[w].phase - W[w].omega * q.t), fs, fc);
                        s = select<V>(rotate, s, fs);
                        c = select<V>(rotate, c, fc);
                    }
                    S[w] = s;
                    C[w] = c;
                }
                done |= ending;
                if (!any(~done & ~fail)) break;
            }
            // Height Σ A cos θ and orbital velocity (see solve) at the converged x₀.
            if (q.outH) {
                V ys = zero;
                for (std::size_t w = 0; w < m; ++w) ys += W[w].a * C[w];
                scatter<V>(q.outH, i, count, surface.m_height + ys);
            }
            if (Velocity) {
                const V depth = min(gather<V>(q.y, i, n) - surface.m_height, zero);
                const bool decays = any(mask<V>(depth < 0.0));
                V vx = zero, vy = zero, vz = zero;
                for (std::size_t w = 0; w < m; ++w) {
                    const V e = decays ? buoyancy::vmath::exp<V>(W[w].k * depth) : splat<V>(1.0);  // e^0 = 1 exactly
                    vx += W[w].qawdx * C[w] * e;
                    vz += W[w].qawdz * C[w] * e;
                    vy += W[w].aw * S[w] * e;
                }
                scatter<V>(q.outVx, i, count, vx);
                scatter<V>(q.outVy, i, count, vy);
                scatter<V>(q.outVz, i, count, vz);
            }
            if (any(fail)) {
                for (int l = 0; l < count; ++l) {
                    if (!fail[l]) continue;
                    const std::size_t k = i + std::size_t(l);
                    double x0 = GX[l], z0 = GZ[l], ySum = 0, v[3] = {0, 0, 0};
                    surface.solve<Velocity>(q.x[k], q.z[k], q.t, x0, z0, ySum, Velocity ? q.y[k] - surface.m_height : 0.0,
                                            v);
                    if (q.outH) q.outH[k] = surface.m_height + ySum;
                    if (Velocity) {
                        q.outVx[k] = v[0];
                        q.outVy[k] = v[1];
                        q.outVz[k] = v[2];
                    }
                    X0[l] = x0;
                    Z0[l] = z0;
                }
            }
            if (q.disp) {
                const V dx = X - X0, dz = Z - Z0;
                for (int l = 0; l < count; ++l) {
                    const std::size_t k = i + std::size_t(l);
                    if (q.shift) {
                        q.disp[2][k] = q.disp[0][k];
                        q.disp[3][k] = q.disp[1][k];
                    }
                    q.disp[0][k] = finiteOr0(dx[l]);
                    q.disp[1][k] = finiteOr0(dz[l]);
                }
            }
        }
    }
    // One entry per instruction set. GCC compiles each with its target's instructions (run is force-inlined),
    // never fusing a multiplication and an addition (AVX-512 has FMA; GCC would contract by default): every
    // width rounds exactly like SSE2.
    template <bool Velocity>
    BB_NO_CONTRACT static void sse2(const btGerstnerWaterSurface& s, const BatchQuery& q) {
        run<v2d, Velocity>(s, q);
    }
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
    template <bool Velocity>
    __attribute__((target("avx2"))) BB_NO_CONTRACT static void avx2(const btGerstnerWaterSurface& s,
                                                                    const BatchQuery& q) {
        run<v4d, Velocity>(s, q);
    }
    template <bool Velocity>
    __attribute__((target("avx512f"))) BB_NO_CONTRACT static void avx512(const btGerstnerWaterSurface& s,
                                                                         const BatchQuery& q) {
        run<v8d, Velocity>(s, q);
    }
#endif
};

template <bool Velocity>
void btGerstnerWaterSurface::batch(const double* x, const double* y, const double* z, std::size_t n, double t,
                                   double* const* disp, double rho, bool shift, double* outH, double* outVx,
                                   double* outVy, double* outVz) const {
    const BatchQuery q{x, y, z, n, t, disp, rho, shift, outH, outVx, outVy, outVz};
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
    if (m_lanes == 8) return Kernel::avx512<Velocity>(*this, q);
    if (m_lanes == 4) return Kernel::avx2<Velocity>(*this, q);
#endif
    Kernel::sse2<Velocity>(*this, q);
}

void btGerstnerWaterSurface::warmStart(btWaterQueryCache& cache, std::size_t n, double t, double* disp[4],
                                       double& rho, bool& shift) const {
    // Layout: a = [x displacements (n) | previous (n) | t₁ | t₂ | calls recorded (0, 1, 2)], b = [z displacements
    // (n) | previous (n)]; a fresh cache starts cold (displacement 0) without times (no NaN markers: the CI's
    // floating-point trap run would stop at the first comparison with one).
    if (cache.owner != this || cache.n != n || cache.a.size() < 2 * n + 3 || cache.b.size() < 2 * n) {
        cache.a.assign(2 * n + 3, 0.0);
        cache.b.assign(2 * n, 0.0);
        cache.owner = this;
        cache.n = n;
    }
    double& t1 = cache.a[2 * n];      // time of the last call
    double& t2 = cache.a[2 * n + 1];  // time of the one before
    double& calls = cache.a[2 * n + 2];
    disp[0] = cache.a.data();
    disp[1] = cache.b.data();
    disp[2] = cache.a.data() + n;
    disp[3] = cache.b.data() + n;
    // Same time as the last call (heights then velocities at the same points): start from its solution.
    shift = calls == 0 || !(t == t1);
    rho = 0;
    if (shift && calls >= 2 && t > t1 && t1 > t2) {
        const double r = (t - t1) / (t1 - t2);  // linear extrapolation of the displacement in time
        if (r <= kMaxExtrapolation) rho = r;
    }
    if (shift) {
        t2 = t1;
        t1 = t;
        calls = std::min(calls + 1, 2.0);
    }
}

double btGerstnerWaterSurface::heightThirdDerivativeScale(double) const {
    double s = 0;
    for (const Wave& w : m_waves) s += w.a * w.k * w.k * w.k;
    const double j = 1.0 - m_loop;
    return s / (j * j);
}

void btGerstnerWaterSurface::heights(const double* x, const double* z, std::size_t n, double t,
                                     double* outHeight) const {
    batch<false>(x, nullptr, z, n, t, nullptr, 0.0, false, outHeight, nullptr, nullptr, nullptr);
}

void btGerstnerWaterSurface::velocities(const double* x, const double* y, const double* z, std::size_t n, double t,
                                        double* outVx, double* outVy, double* outVz) const {
    batch<true>(x, y, z, n, t, nullptr, 0.0, false, nullptr, outVx, outVy, outVz);
}

void btGerstnerWaterSurface::accelerations(const double* x, const double* y, const double* z, std::size_t n, double t,
                                           double* outAx, double* outAy, double* outAz) const {
    // design.md 2.7, "The water's acceleration": the acceleration of the trochoidal wave's particle that is at
    // (x, y, z). Its rest position (x₀, z₀) and rest height y₀ solve, with e_i = e^{k_i min(0, y₀ − h)},
    //     x = x₀ − Σ Q A e d sin θ,   y = y₀ + Σ A e cos θ   (Newton's method, 3×3),
    // and it moves on its orbit at ω: a = Σ (Q A ω² e d sin θ, −A ω² e cos θ), pointing to the orbit's centre. At the
    // surface (y₀ = h) it is the surface particle's; below, the particle's own decay and phase (not the ones of the
    // surface particle above, as velocities() takes them): along a closed orbit the acceleration has no mean, so a
    // body carried by the water does not drift in depth.
    const std::size_t m = m_waves.size();
    for (std::size_t p = 0; p < n; ++p) {
        double x0 = x[p], z0 = z[p], y0 = std::min(y[p], m_height);
        // Stop at a step of 1e-10 m, or a few ulps of the coordinates far from the origin; the acceleration is the
        // one before that last step (off by ≤ k tol of A ω²).
        const double tol = std::max(1e-10, 4e-15 * (std::abs(x[p]) + std::abs(y[p]) + std::abs(z[p])));
        double ax = 0, ay = 0, az = 0;
        for (int it = 0;; ++it) {
            // Residual F = (x₀ − Σ Q A e d_x sin θ − x, y₀ + Σ A e cos θ − y, z₀ − Σ Q A e d_z sin θ − z), its
            // Jacobian J (rows F, columns x₀, y₀, z₀), and the acceleration at the current estimate.
            const double depth = std::min(0.0, y0 - m_height);
            const bool below = depth < 0;
            double fx = x0 - x[p], fy = y0 - y[p], fz = z0 - z[p];
            double jxx = 1, jxy = 0, jxz = 0, jyx = 0, jyy = 1, jyz = 0, jzx = 0, jzy = 0, jzz = 1;
            ax = ay = az = 0;
            for (std::size_t i = 0; i < m; ++i) {
                const Wave& w = m_waves[i];
                const double th = w.kdx * x0 + w.kdz * z0 + (w.phase - w.omega * t);
                const double sn = std::sin(th), cs = std::cos(th);
                const double e = below ? std::exp(w.k * depth) : 1.0, de = below ? w.k * e : 0.0;  // e, ∂e/∂y₀
                fx -= w.qadx * e * sn;
                fz -= w.qadz * e * sn;
                fy += w.a * e * cs;
                jxx -= w.qadx * e * cs * w.kdx;
                jxz -= w.qadx * e * cs * w.kdz;
                jxy -= w.qadx * de * sn;
                jzx -= w.qadz * e * cs * w.kdx;
                jzz -= w.qadz * e * cs * w.kdz;
                jzy -= w.qadz * de * sn;
                jyx -= w.a * e * sn * w.kdx;
                jyz -= w.a * e * sn * w.kdz;
                jyy += w.a * de * cs;
                ax += w.qawdx * w.omega * e * sn;
                az += w.qawdz * w.omega * e * sn;
                ay -= w.aw * w.omega * e * cs;
            }
            if (it >= kMaxIterations) break;
            // Newton step J s = F by Cramer's rule; the fixed-point step (s = F) where J is nearly singular.
            const double c0 = jyy * jzz - jyz * jzy, c1 = jyz * jzx - jyx * jzz, c2 = jyx * jzy - jyy * jzx;
            const double det = jxx * c0 + jxy * c1 + jxz * c2;
            double sx = fx, sy = fy, sz = fz;
            if (std::abs(det) > 1e-6) {
                sx = (fx * c0 + jxy * (fz * jyz - fy * jzz) + jxz * (fy * jzy - fz * jyy)) / det;
                sy = (jxx * (fy * jzz - fz * jyz) + fx * c1 + jxz * (fz * jyx - fy * jzx)) / det;
                sz = (jxx * (jyy * fz - jzy * fy) + jxy * (jzx * fy - jyx * fz) + fx * c2) / det;
            }
            x0 -= sx;
            y0 -= sy;
            z0 -= sz;
            if (!(sx * sx + sy * sy + sz * sz > tol * tol)) break;
        }
        outAx[p] = ax;
        outAy[p] = ay;
        outAz[p] = az;
    }
}

void btGerstnerWaterSurface::heightsCached(const double* x, const double* z, std::size_t n, double t,
                                           double* outHeight, btWaterQueryCache& cache) const {
    double* disp[4];
    double rho;
    bool shift;
    warmStart(cache, n, t, disp, rho, shift);
    batch<false>(x, nullptr, z, n, t, disp, rho, shift, outHeight, nullptr, nullptr, nullptr);
}

void btGerstnerWaterSurface::velocitiesCached(const double* x, const double* y, const double* z, std::size_t n,
                                              double t, double* outVx, double* outVy, double* outVz,
                                              btWaterQueryCache& cache) const {
    double* disp[4];
    double rho;
    bool shift;
    warmStart(cache, n, t, disp, rho, shift);
    batch<true>(x, y, z, n, t, disp, rho, shift, nullptr, outVx, outVy, outVz);
}

void btGerstnerWaterSurface::heightBounds(double, double, double, double, double, double& outMin,
                                          double& outMax) const {
    outMin = m_height - m_amplitudeSum;
    outMax = m_height + m_amplitudeSum;
}

bool btGerstnerWaterSurface::isFlat(double, double& outHeight) const {
    outHeight = m_height;
    return !(m_amplitudeSum > 0);
}

bool btGerstnerWaterSurface::describeForDevice(double, btWaterDeviceDescription& out) const {
    out.kind = btWaterDeviceDescription::Kind::Gerstner;
    out.reason.clear();
    out.meanLevel = meanLevel();
    out.waveConstants = packedWaveConstants();
    out.maxIterations = kMaxIterations;
    return true;
}
