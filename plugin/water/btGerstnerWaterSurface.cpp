#include "water/btGerstnerWaterSurface.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
constexpr double kResidualTolerance = 1e-9;  // m, horizontal residual of the inversion (issue 5 asks 1e-6)

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

void btGerstnerWaterSurface::restPosition(double x, double z, double t, double& outX0, double& outZ0,
                                          int* outIterations) const {
    double x0 = x, z0 = z;
    int it = 0;
    if (m_loop > 0) {
        for (; it < kMaxIterations; ++it) {
            // Residual r = (x0 − D(x0)) − x and Jacobian J = I − Σ Q A k cos θ d dᵀ (symmetric 2×2).
            double rx = x0 - x, rz = z0 - z, jxx = 1, jxz = 0, jzz = 1;
            for (const Wave& w : m_waves) {
                const double th = w.k * (w.dx * x0 + w.dz * z0) - w.omega * t + w.phase;
                const double s = std::sin(th), c = std::cos(th);
                rx -= w.qa * w.dx * s;
                rz -= w.qa * w.dz * s;
                const double f = w.qa * w.k * c;
                jxx -= f * w.dx * w.dx;
                jxz -= f * w.dx * w.dz;
                jzz -= f * w.dz * w.dz;
            }
            const double r = std::hypot(rx, rz);
            if (r <= kResidualTolerance) break;
            const double det = jxx * jzz - jxz * jxz;  // ≥ (1 − Σ Q A k)² > 0
            const double nx = x0 - (jzz * rx - jxz * rz) / det;
            const double nz = z0 - (jxx * rz - jxz * rx) / det;
            // Accept Newton's step if it reduces the residual, else take a fixed-point step x0 ← x + D(x0).
            double ex = nx - x, ez = nz - z;
            for (const Wave& w : m_waves) {
                const double s = std::sin(w.k * (w.dx * nx + w.dz * nz) - w.omega * t + w.phase);
                ex -= w.qa * w.dx * s;
                ez -= w.qa * w.dz * s;
            }
            if (std::hypot(ex, ez) < r) {
                x0 = nx;
                z0 = nz;
            } else {
                x0 -= rx;
                z0 -= rz;
            }
        }
    }
    outX0 = x0;
    outZ0 = z0;
    if (outIterations) *outIterations = it;
}

void btGerstnerWaterSurface::heights(const double* x, const double* z, std::size_t n, double t,
                                     double* outHeight) const {
    for (std::size_t i = 0; i < n; ++i) {
        double x0, z0;
        restPosition(x[i], z[i], t, x0, z0);
        double y = m_height;
        for (const Wave& w : m_waves) y += w.a * std::cos(w.k * (w.dx * x0 + w.dz * z0) - w.omega * t + w.phase);
        outHeight[i] = y;
    }
}

void btGerstnerWaterSurface::velocities(const double* x, const double* y, const double* z, std::size_t n, double t,
                                        double* outVx, double* outVy, double* outVz) const {
    for (std::size_t i = 0; i < n; ++i) {
        double x0, z0;
        restPosition(x[i], z[i], t, x0, z0);
        double vx = 0, vy = 0, vz = 0;
        for (const Wave& w : m_waves) {
            const double th = w.k * (w.dx * x0 + w.dz * z0) - w.omega * t + w.phase;
            const double decay = std::exp(std::min(0.0, w.k * (y[i] - m_height)));
            // ∂/∂t of the parametric surface: ∂θ/∂t = −ω.
            const double c = std::cos(th) * w.omega * decay;
            vx += w.qa * w.dx * c;
            vz += w.qa * w.dz * c;
            vy += w.a * std::sin(th) * w.omega * decay;
        }
        outVx[i] = vx;
        outVy[i] = vy;
        outVz[i] = vz;
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
