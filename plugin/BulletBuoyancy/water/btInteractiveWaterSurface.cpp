#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

btInteractiveWaterSurface::btInteractiveWaterSurface(double sizeX, double sizeZ, int resolution, double waveSpeed,
                                                     double damping, double height, double centreX, double centreZ)
    : m_c(waveSpeed), m_gamma(damping), m_h(height) {
    if (!std::isfinite(sizeX) || !(sizeX > 0) || !std::isfinite(sizeZ) || !(sizeZ > 0))
        throw std::invalid_argument("size: must be two finite numbers > 0");
    if (resolution < 4 || resolution > 4096) throw std::invalid_argument("resolution: must be in [4, 4096]");
    if (!std::isfinite(waveSpeed) || !(waveSpeed > 0)) throw std::invalid_argument("wave_speed: must be > 0");
    if (!std::isfinite(damping) || damping < 0) throw std::invalid_argument("damping: must be >= 0");
    if (!std::isfinite(height)) throw std::invalid_argument("height: must be finite");
    if (!std::isfinite(centreX) || !std::isfinite(centreZ)) throw std::invalid_argument("centre: must be finite");
    m_nx = resolution;
    m_dx = sizeX / resolution;
    m_nz = std::max(4, int(std::lround(sizeZ / m_dx)));
    if (double(m_nx) * m_nz > 16.0e6) throw std::invalid_argument("resolution: more than 16 million cells");
    m_minX = centreX - 0.5 * m_nx * m_dx;
    m_minZ = centreZ - 0.5 * m_nz * m_dx;
    reset();
}

void btInteractiveWaterSurface::reset() {
    const std::size_t n = std::size_t(m_nx) * m_nz;
    m_eta.assign(n, m_h);
    m_vel.assign(n, 0.0);
    m_lap.assign(n, 0.0);
    m_offset = 0.0;
    m_min = m_max = m_h;
}

void btInteractiveWaterSurface::heights(const double* x, const double* z, std::size_t n, double,
                                        double* outHeight) const {
    for (std::size_t k = 0; k < n; ++k) {
        const double u = std::clamp((x[k] - m_minX) / m_dx - 0.5, 0.0, double(m_nx - 1));
        const double v = std::clamp((z[k] - m_minZ) / m_dx - 0.5, 0.0, double(m_nz - 1));
        const int i0 = std::min(int(u), m_nx - 2), j0 = std::min(int(v), m_nz - 2);
        const double a = u - i0, b = v - j0;
        const double* r0 = &m_eta[std::size_t(j0) * m_nx + i0];
        const double* r1 = r0 + m_nx;
        outHeight[k] = (1 - b) * ((1 - a) * r0[0] + a * r0[1]) + b * ((1 - a) * r1[0] + a * r1[1]) + m_offset;
    }
}

void btInteractiveWaterSurface::velocities(const double* x, const double*, const double* z, std::size_t n, double,
                                           double* outVx, double* outVy, double* outVz) const {
    for (std::size_t k = 0; k < n; ++k) {
        const int i = std::clamp(int(std::floor((x[k] - m_minX) / m_dx)), 0, m_nx - 1);
        const int j = std::clamp(int(std::floor((z[k] - m_minZ) / m_dx)), 0, m_nz - 1);
        outVx[k] = 0.0;
        outVy[k] = m_vel[std::size_t(j) * m_nx + i];
        outVz[k] = 0.0;
    }
}

void btInteractiveWaterSurface::heightBounds(double, double, double, double, double, double& outMin,
                                             double& outMax) const {
    outMin = m_min;
    outMax = m_max;
}

void btInteractiveWaterSurface::updateRange() {
    const auto mm = std::minmax_element(m_eta.begin(), m_eta.end());
    m_min = *mm.first + m_offset;
    m_max = *mm.second + m_offset;
}

void btInteractiveWaterSurface::addVolumeChange(double x, double z, double dV, double radius) {
    if (!std::isfinite(x) || !std::isfinite(z) || !std::isfinite(dV) || dV == 0) return;
    const int ci = int(std::floor((x - m_minX) / m_dx)), cj = int(std::floor((z - m_minZ) / m_dx));
    if (ci < 0 || cj < 0 || ci >= m_nx || cj >= m_nz) return;
    const double r = std::isfinite(radius) ? std::max(radius, 0.0) : 0.0;
    // Where the displaced water goes: up in a ring past a gap of two cells outside the footprint (radius r),
    // a band max(2 dx, r/2) wide; down uniformly over the whole grid (the open sea around it, an O(1) offset).
    // Nothing is taken from under the body, and nothing it reads is raised: every point it reads lies within
    // r, whose bilinear stencil reaches √2 dx further, short of the ring. (Taking the water from the cells
    // under the body made it read its own displacement twice and pumped a half-immersed sphere into a
    // growing heave at coarse grids; a ring adjacent to the footprint sat inside that stencil, and since its
    // height grows as 1/dx — the same volume in a thinner band — it lifted bodies at fine grids: 0.3 m at
    // 512², a creep at 256².) The band's width in metres keeps the pushed-up water resolution-independent.
    const double rIn = r + 2 * m_dx;
    const double rOut = rIn + std::max(2 * m_dx, 0.5 * r);
    const int span = int(std::ceil(rOut / m_dx)) + 1;
    m_ring.clear();
    for (int j = std::max(0, cj - span); j <= std::min(m_nz - 1, cj + span); ++j)
        for (int i = std::max(0, ci - span); i <= std::min(m_nx - 1, ci + span); ++i) {
            const double d = std::hypot(m_minX + (i + 0.5) * m_dx - x, m_minZ + (j + 0.5) * m_dx - z);
            if (d > rIn && d <= rOut) m_ring.push_back(j * m_nx + i);
        }
    if (m_ring.empty()) return;  // the ring lies outside the grid: the body covers it, nothing to move
    const double area = m_dx * m_dx;
    const double sink = dV / (area * double(m_eta.size()));
    m_offset -= sink;
    m_min -= sink;
    m_max -= sink;
    const double up = dV / (area * double(m_ring.size()));
    for (int id : m_ring) {
        double& e = m_eta[std::size_t(id)];
        e += up;
        // The range stays a bound (exact again after the next step).
        m_min = std::min(m_min, e + m_offset);
        m_max = std::max(m_max, e + m_offset);
    }
}

void btInteractiveWaterSurface::step(double dt) {
    if (!std::isfinite(dt) || dt < 0) throw std::invalid_argument("step: dt must be a finite number >= 0");
    if (dt == 0) return;
    const int steps = std::max(1, int(std::ceil(m_c * dt / (0.5 * m_dx))));
    const double h = dt / steps, c2 = m_c * m_c / (m_dx * m_dx);
    const int nx = m_nx, nz = m_nz;
    for (int s = 0; s < steps; ++s) {
        // 5-point Laplacian with zero-flux walls (a missing neighbour contributes nothing): Σ lap = 0.
        for (int j = 0; j < nz; ++j)
            for (int i = 0; i < nx; ++i) {
                const std::size_t id = std::size_t(j) * nx + i;
                const double e = m_eta[id];
                double l = 0;
                if (i > 0) l += m_eta[id - 1] - e;
                if (i + 1 < nx) l += m_eta[id + 1] - e;
                if (j > 0) l += m_eta[id - nx] - e;
                if (j + 1 < nz) l += m_eta[id + nx] - e;
                m_lap[id] = l;
            }
        const double keep = 1.0 / (1.0 + m_gamma * h);  // implicit damping: unconditionally stable
        for (std::size_t id = 0; id < m_eta.size(); ++id) {
            m_vel[id] = (m_vel[id] + h * c2 * m_lap[id]) * keep;
            m_eta[id] += h * m_vel[id];
        }
    }
    updateRange();
}

double btInteractiveWaterSurface::waterVolume() const {
    double s = 0, c = 0;  // Kahan sum
    for (double e : m_eta) {
        const double y = (e - m_h) - c;
        const double t = s + y;
        c = (t - s) - y;
        s = t;
    }
    return (s + m_offset * double(m_eta.size())) * m_dx * m_dx;
}

btInteractiveWaterSurface::Dynamic btInteractiveWaterSurface::dynamicState() const {
    Dynamic d;
    d.eta = m_eta;
    d.velocity = m_vel;
    d.offset = m_offset;
    d.min = m_min;
    d.max = m_max;
    return d;
}

void btInteractiveWaterSurface::setDynamicState(const Dynamic& d) {
    if (d.eta.size() != m_eta.size() || d.velocity.size() != m_vel.size())
        throw std::invalid_argument("btInteractiveWaterSurface: the saved grid has " + std::to_string(d.eta.size()) +
                                    " elevations and " + std::to_string(d.velocity.size()) + " velocities, this grid " +
                                    std::to_string(m_eta.size()) + " cells");
    m_eta = d.eta;
    m_vel = d.velocity;
    m_offset = d.offset;
    m_min = d.min;
    m_max = d.max;
}
