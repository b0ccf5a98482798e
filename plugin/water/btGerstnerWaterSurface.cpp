#include "water/btGerstnerWaterSurface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
constexpr double kResidualTolerance = 1e-9;  // m, horizontal residual of the inversion (issue 5 asks 1e-6)
constexpr double kTol2 = kResidualTolerance * kResidualTolerance;

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
        v.aw = v.a * v.omega;
        v.qaw = v.qa * v.omega;
        m_amplitudeSum += v.a;
        m_loop += v.qa * v.k;
        m_waves.push_back(v);
    }
    if (!(m_loop < 1.0)) {
        std::ostringstream os;
        os << "waves: sum of steepness*amplitude*k = " << m_loop
           << " >= 1: the Gerstner surface loops (no longer a height field); lower the steepness or amplitude";
        throw std::invalid_argument(os.str());
    }
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
// velocity), so the solve ends right after an evaluation and its results belong to the returned x₀. A Newton
// step that did not reduce the residual is replaced by the fixed-point step x₀ ← x + D(x₀) from the previous
// point, a contraction of factor Σ Q A k < 1 (|r'| ≤ Σ Q A k |r|), so the solve always converges.
template <bool Velocity>
int btGerstnerWaterSurface::solve(double x, double z, double t, double& x0, double& z0, double& ySum, double yRel,
                                  double* vel) const {
    const Wave* waves = m_waves.data();
    const std::size_t m = m_waves.size();
    const double depth = std::min(0.0, yRel);
    double px = x0, pz = z0, prx = 0, prz = 0, pr2 = std::numeric_limits<double>::infinity();
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
                vx += w.qaw * w.dx * c * e;
                vz += w.qaw * w.dz * c * e;
                vy += w.aw * s * e;
            }
        }
        ySum = ys;
        if (Velocity) {
            vel[0] = vx;
            vel[1] = vy;
            vel[2] = vz;
        }
        const double r2 = rx * rx + rz * rz;
        if (r2 <= kTol2 || it >= kMaxIterations) break;
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
        x0 -= (jzz * rx - jxz * rz) * inv;
        z0 -= (jxx * rz - jxz * rx) * inv;
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

void btGerstnerWaterSurface::heights(const double* x, const double* z, std::size_t n, double t,
                                     double* outHeight) const {
    for (std::size_t i = 0; i < n; ++i) {
        double x0 = x[i], z0 = z[i], ys = 0;
        solve<false>(x[i], z[i], t, x0, z0, ys, 0.0, nullptr);
        outHeight[i] = m_height + ys;
    }
}

void btGerstnerWaterSurface::velocities(const double* x, const double* y, const double* z, std::size_t n, double t,
                                        double* outVx, double* outVy, double* outVz) const {
    for (std::size_t i = 0; i < n; ++i) {
        double x0 = x[i], z0 = z[i], ys = 0, v[3];
        solve<true>(x[i], z[i], t, x0, z0, ys, y[i] - m_height, v);
        outVx[i] = v[0];
        outVy[i] = v[1];
        outVz[i] = v[2];
    }
}

namespace {
// The cache holds each point's horizontal displacement x − x₀ (a: x, b: z); a fresh one starts cold (0).
void prepare(btWaterQueryCache& cache, const btWaterSurface* owner, std::size_t n) {
    if (cache.owner == owner && cache.n == n && cache.a.size() >= n && cache.b.size() >= n) return;
    cache.a.assign(n, 0.0);
    cache.b.assign(n, 0.0);
    cache.owner = owner;
    cache.n = n;
}
// Keep only finite displacements, so one bad point never poisons the next warm start.
inline void store(double& slot, double d) { slot = std::isfinite(d) ? d : 0.0; }
}  // namespace

void btGerstnerWaterSurface::heightsCached(const double* x, const double* z, std::size_t n, double t,
                                           double* outHeight, btWaterQueryCache& cache) const {
    prepare(cache, this, n);
    double* dx = cache.a.data();
    double* dz = cache.b.data();
    for (std::size_t i = 0; i < n; ++i) {
        double x0 = x[i] - dx[i], z0 = z[i] - dz[i], ys = 0;
        solve<false>(x[i], z[i], t, x0, z0, ys, 0.0, nullptr);
        outHeight[i] = m_height + ys;
        store(dx[i], x[i] - x0);
        store(dz[i], z[i] - z0);
    }
}

void btGerstnerWaterSurface::velocitiesCached(const double* x, const double* y, const double* z, std::size_t n,
                                              double t, double* outVx, double* outVy, double* outVz,
                                              btWaterQueryCache& cache) const {
    prepare(cache, this, n);
    double* dx = cache.a.data();
    double* dz = cache.b.data();
    for (std::size_t i = 0; i < n; ++i) {
        double x0 = x[i] - dx[i], z0 = z[i] - dz[i], ys = 0, v[3];
        solve<true>(x[i], z[i], t, x0, z0, ys, y[i] - m_height, v);
        outVx[i] = v[0];
        outVy[i] = v[1];
        outVz[i] = v[2];
        store(dx[i], x[i] - x0);
        store(dz[i], z[i] - z0);
    }
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
