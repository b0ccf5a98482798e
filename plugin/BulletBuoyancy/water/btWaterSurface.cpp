#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <atomic>
#include <cmath>

std::uint64_t btWaterSurface::nextRevision() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

void btWaterSurface::velocities(const double*, const double*, const double*, std::size_t n, double, double* outVx,
                                double* outVy, double* outVz) const {
    for (std::size_t i = 0; i < n; ++i) outVx[i] = outVy[i] = outVz[i] = 0.0;
}

void btWaterSurface::accelerations(const double* x, const double* y, const double* z, std::size_t n, double t,
                                   double* outAx, double* outAy, double* outAz) const {
    // design.md 2.7, "The water's acceleration": ∂u/∂t ≈ (u(t + h) − u(t − h)) / 2h at fixed points, in chunks of
    // kChunk points on the stack (no allocation).
    constexpr std::size_t kChunk = 32;
    const double h = kAccelerationTimeStep;
    double px[kChunk], py[kChunk], pz[kChunk], mx[kChunk], my[kChunk], mz[kChunk];
    for (std::size_t start = 0; start < n; start += kChunk) {
        const std::size_t m = std::min(kChunk, n - start);
        velocities(x + start, y + start, z + start, m, t + h, px, py, pz);
        velocities(x + start, y + start, z + start, m, t - h, mx, my, mz);
        for (std::size_t i = 0; i < m; ++i) {
            outAx[start + i] = (px[i] - mx[i]) / (2.0 * h);
            outAy[start + i] = (py[i] - my[i]) / (2.0 * h);
            outAz[start + i] = (pz[i] - mz[i]) / (2.0 * h);
        }
    }
}

double btWaterSurface::heightThirdDerivativeScale(double t) const {
    const double lambda = shortestWavelength();
    if (!(lambda > 0)) return 0.0;
    double lo = 0, hi = 0;
    heightBounds(0.0, 0.0, 0.0, 0.0, t, lo, hi);
    const double k = 2.0 * 3.14159265358979323846 / lambda;
    const double s = 0.5 * (hi - lo) * k * k * k;
    return std::isfinite(s) ? s : 0.0;
}

void btFlatWaterSurface::heights(const double*, const double*, std::size_t n, double, double* outHeight) const {
    for (std::size_t i = 0; i < n; ++i) outHeight[i] = m_height;
}

void btFlatWaterSurface::velocities(const double*, const double*, const double*, std::size_t n, double,
                                    double* outVx, double* outVy, double* outVz) const {
    for (std::size_t i = 0; i < n; ++i) {
        outVx[i] = m_currentX;
        outVy[i] = 0.0;
        outVz[i] = m_currentZ;
    }
}

void btFlatWaterSurface::accelerations(const double*, const double*, const double*, std::size_t n, double,
                                       double* outAx, double* outAy, double* outAz) const {
    for (std::size_t i = 0; i < n; ++i) outAx[i] = outAy[i] = outAz[i] = 0.0;
}

void btFlatWaterSurface::heightBounds(double, double, double, double, double, double& outMin, double& outMax) const {
    outMin = outMax = m_height;
}

bool btFlatWaterSurface::isFlat(double, double& outHeight) const {
    outHeight = m_height;
    return true;
}

bool btWaterSurface::describeForDevice(double, btWaterDeviceDescription& out) const {
    out.kind = btWaterDeviceDescription::Kind::None;
    out.reason = "water: surface type not evaluated on the device (flat, Gerstner, grid and non-choppy FFT are); its "
                 "bodies use the CPU path";
    return false;
}

bool btFlatWaterSurface::describeForDevice(double, btWaterDeviceDescription& out) const {
    out.kind = btWaterDeviceDescription::Kind::Flat;
    out.reason.clear();
    out.level = m_height;
    out.currentX = m_currentX;
    out.currentZ = m_currentZ;
    return true;
}
