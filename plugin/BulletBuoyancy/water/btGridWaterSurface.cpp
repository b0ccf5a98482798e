#include <BulletBuoyancy/water/btGridWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace {
void checkField(const std::vector<double>& f, std::size_t n, const char* name) {
    if (f.size() != n)
        throw std::invalid_argument(std::string(name) + ": expected " + std::to_string(n) + " values, got " +
                                    std::to_string(f.size()));
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(f[i])) throw std::invalid_argument(std::string(name) + ": value " + std::to_string(i) + " is not finite");
}
}  // namespace

btGridWaterSurface::btGridWaterSurface(int nx, int nz, double spacing, double originX, double originZ,
                                       std::vector<double> heights, bool periodic)
    : m_nx(nx), m_nz(nz), m_spacing(spacing), m_originX(originX), m_originZ(originZ), m_periodic(periodic) {
    if (nx < 2 || nz < 2) throw std::invalid_argument("grid: needs at least 2x2 samples");
    if (!std::isfinite(spacing) || !(spacing > 0)) throw std::invalid_argument("spacing: must be a finite number > 0");
    if (!std::isfinite(originX) || !std::isfinite(originZ)) throw std::invalid_argument("origin: must be finite");
    checkField(heights, std::size_t(nx) * std::size_t(nz), "heights");
    m_h = std::move(heights);
    updateRange();
}

void btGridWaterSurface::setHeights(const std::vector<double>& heights) {
    checkField(heights, m_h.size(), "heights");
    m_h = heights;
    updateRange();
}

void btGridWaterSurface::setVelocities(std::vector<double> vx, std::vector<double> vy, std::vector<double> vz) {
    if (vx.empty() && vy.empty() && vz.empty()) {
        m_vx.clear();
        m_vy.clear();
        m_vz.clear();
        return;
    }
    checkField(vx, m_h.size(), "velocities.x");
    checkField(vy, m_h.size(), "velocities.y");
    checkField(vz, m_h.size(), "velocities.z");
    m_vx = std::move(vx);
    m_vy = std::move(vy);
    m_vz = std::move(vz);
}

void btGridWaterSurface::updateRange() {
    const auto mm = std::minmax_element(m_h.begin(), m_h.end());
    m_min = *mm.first;
    m_max = *mm.second;
}

int btGridWaterSurface::wrap(long long i, int n) const {
    if (m_periodic) {
        long long r = i % n;
        return int(r < 0 ? r + n : r);
    }
    return int(std::clamp<long long>(i, 0, n - 1));
}

double btGridWaterSurface::sample(const std::vector<double>& f, double x, double z) const {
    double u = (x - m_originX) / m_spacing, v = (z - m_originZ) / m_spacing;
    if (!m_periodic) {  // clamp the coordinates so edge values hold outside
        u = std::clamp(u, 0.0, double(m_nx - 1));
        v = std::clamp(v, 0.0, double(m_nz - 1));
    }
    const double fu = std::floor(u), fv = std::floor(v);
    const double a = u - fu, b = v - fv;
    const long long iu = (long long)fu, iv = (long long)fv;
    const int i0 = wrap(iu, m_nx), i1 = wrap(iu + 1, m_nx), j0 = wrap(iv, m_nz), j1 = wrap(iv + 1, m_nz);
    const double h00 = f[std::size_t(j0) * m_nx + i0], h10 = f[std::size_t(j0) * m_nx + i1];
    const double h01 = f[std::size_t(j1) * m_nx + i0], h11 = f[std::size_t(j1) * m_nx + i1];
    return (1 - b) * ((1 - a) * h00 + a * h10) + b * ((1 - a) * h01 + a * h11);
}

void btGridWaterSurface::heights(const double* x, const double* z, std::size_t n, double, double* outHeight) const {
    for (std::size_t i = 0; i < n; ++i) outHeight[i] = sample(m_h, x[i], z[i]);
}

void btGridWaterSurface::velocities(const double* x, const double*, const double* z, std::size_t n, double,
                                    double* outVx, double* outVy, double* outVz) const {
    const bool has = !m_vx.empty();
    for (std::size_t i = 0; i < n; ++i) {
        outVx[i] = has ? sample(m_vx, x[i], z[i]) : 0.0;
        outVy[i] = has ? sample(m_vy, x[i], z[i]) : 0.0;
        outVz[i] = has ? sample(m_vz, x[i], z[i]) : 0.0;
    }
}

void btGridWaterSurface::heightBounds(double minX, double minZ, double maxX, double maxZ, double, double& outMin,
                                      double& outMax) const {
    outMin = m_min;
    outMax = m_max;
    if (!(minX <= maxX) || !(minZ <= maxZ)) return;
    double u0 = std::floor((minX - m_originX) / m_spacing), u1 = std::ceil((maxX - m_originX) / m_spacing);
    double v0 = std::floor((minZ - m_originZ) / m_spacing), v1 = std::ceil((maxZ - m_originZ) / m_spacing);
    if (!m_periodic) {
        u0 = std::clamp(u0, 0.0, double(m_nx - 1));
        u1 = std::clamp(u1, 0.0, double(m_nx - 1));
        v0 = std::clamp(v0, 0.0, double(m_nz - 1));
        v1 = std::clamp(v1, 0.0, double(m_nz - 1));
    }
    if (u1 - u0 + 1 >= m_nx && v1 - v0 + 1 >= m_nz) return;  // covers the whole grid
    if ((u1 - u0 + 1) * (v1 - v0 + 1) > 65536.0) return;       // large region: the global range is cheaper
    double lo = m_max, hi = m_min;
    for (long long j = (long long)v0; j <= (long long)v1; ++j) {
        const int jj = wrap(j, m_nz);
        for (long long i = (long long)u0; i <= (long long)u1; ++i) {
            const double h = m_h[std::size_t(jj) * m_nx + wrap(i, m_nx)];
            lo = std::min(lo, h);
            hi = std::max(hi, h);
        }
    }
    outMin = lo;
    outMax = hi;
}

bool btGridWaterSurface::describeForDevice(double, btWaterDeviceDescription& out) const {
    out.kind = btWaterDeviceDescription::Kind::HeightGrid;
    out.reason.clear();
    out.sizeX = m_nx;
    out.sizeZ = m_nz;
    out.spacing = m_spacing;
    out.originX = m_originX;
    out.originZ = m_originZ;
    out.periodic = m_periodic;
    out.heights.assign(m_h.begin(), m_h.end());
    out.velocityX.assign(m_vx.begin(), m_vx.end());
    out.velocityY.assign(m_vy.begin(), m_vy.end());
    out.velocityZ.assign(m_vz.begin(), m_vz.end());
    out.velocityOnDevice = true;
    return true;
}
