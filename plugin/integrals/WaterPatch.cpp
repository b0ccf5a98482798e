/// @file WaterPatch.cpp
/// Per-body grid of water heights with Catmull-Rom interpolation (declared in WaterPatch.h).

#include "integrals/WaterPatch.h"

#include "water/btWaterSurface.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

void WaterPatch::build(const btWaterSurface& water, double cx, double cz, double r, double time, int nodes,
                       btWaterQueryCache& cache) {
    if (nodes < 5 || nodes > 64)
        throw std::invalid_argument("WaterPatch: nodes must be in 5..64 (got " + std::to_string(nodes) + ")");
    if (!std::isfinite(cx) || !std::isfinite(cz) || !std::isfinite(r) || !(r > 0))
        throw std::invalid_argument("WaterPatch: non-finite footprint or radius <= 0");
    m_m = nodes;
    m_h = 2.0 * r / double(nodes - 4);
    m_invH = 1.0 / m_h;
    // Anchor node 1 on the world lattice k·h at or below cx − r: the same body drifting keeps its nodes.
    m_x0 = (std::floor((cx - r) * m_invH) - 1.0) * m_h;
    m_z0 = (std::floor((cz - r) * m_invH) - 1.0) * m_h;
    const std::size_t n = std::size_t(nodes) * std::size_t(nodes);
    if (m_f.size() != n) {
        m_qx.resize(n);
        m_qz.resize(n);
        m_f.resize(n);
    }
    for (int j = 0; j < nodes; ++j)
        for (int i = 0; i < nodes; ++i) {
            m_qx[std::size_t(j) * nodes + i] = m_x0 + i * m_h;
            m_qz[std::size_t(j) * nodes + i] = m_z0 + j * m_h;
        }
    water.heightsCached(m_qx.data(), m_qz.data(), n, time, m_f.data(), cache);
    m_min = m_f[0];
    m_max = m_f[0];
    m_finite = true;
    for (double f : m_f) {
        if (!std::isfinite(f)) m_finite = false;
        m_min = std::min(m_min, f);
        m_max = std::max(m_max, f);
    }
}

namespace {
/// Catmull-Rom weights for the 4 nodes around parameter t ∈ [0, 1] (exact for quadratics).
inline void catmullRom(double t, double w[4]) {
    const double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
}
}  // namespace

double WaterPatch::height(double x, double z) const {
    const double u = (x - m_x0) * m_invH, v = (z - m_z0) * m_invH;
    // Cells 1..M−3 have both neighbours; clamp outside points to the border cells.
    const double lo = 1.0, hi = double(m_m - 2);
    const double uc = std::min(std::max(u, lo), hi), vc = std::min(std::max(v, lo), hi);
    int i = std::min(int(uc), m_m - 3), j = std::min(int(vc), m_m - 3);
    double wu[4], wv[4];
    catmullRom(uc - i, wu);
    catmullRom(vc - j, wv);
    const double* f = m_f.data() + std::size_t(j - 1) * m_m + (i - 1);
    double s = 0;
    for (int b = 0; b < 4; ++b, f += m_m) s += wv[b] * (wu[0] * f[0] + wu[1] * f[1] + wu[2] * f[2] + wu[3] * f[3]);
    return s;
}

void WaterPatch::heights(const double* x, const double* z, std::size_t n, double* outHeight) const {
    for (std::size_t k = 0; k < n; ++k) outHeight[k] = height(x[k], z[k]);
}

}  // namespace buoyancy
