#include <BulletBuoyancy/water/btRiverSurface.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace {
constexpr double kMinSegment = 1e-6;  ///< shortest centreline segment, m
}  // namespace

btRiverSurface::btRiverSurface(const btRiverSettings& settings) : m_s(settings) {
    if (!std::isfinite(m_s.height)) throw std::invalid_argument("height: must be finite");
    if (!std::isfinite(m_s.width) || !(m_s.width > 0))
        throw std::invalid_argument("width: must be a finite number > 0 (m), got " + std::to_string(m_s.width));
    if (!std::isfinite(m_s.surfaceSpeed) || !(m_s.surfaceSpeed >= 0))
        throw std::invalid_argument("surfaceSpeed: must be a finite number >= 0 (m/s; the flow runs from the first "
                                    "centreline point to the last), got " + std::to_string(m_s.surfaceSpeed));
    const std::vector<btRiverPoint>& c = m_s.centreline;
    if (c.size() < 2)
        throw std::invalid_argument("centreline: needs at least 2 points, got " + std::to_string(c.size()));
    for (std::size_t i = 0; i < c.size(); ++i)
        if (!std::isfinite(c[i].x) || !std::isfinite(c[i].z))
            throw std::invalid_argument("centreline[" + std::to_string(i) + "]: must be finite");
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
        const double dx = c[k + 1].x - c[k].x, dz = c[k + 1].z - c[k].z;
        const double len = std::hypot(dx, dz);
        if (!(len >= kMinSegment))
            throw std::invalid_argument("centreline[" + std::to_string(k + 1) + "]: repeats centreline[" +
                                        std::to_string(k) + "] (consecutive points must be at least 1e-6 m apart)");
        m_tx.push_back(dx / len);
        m_tz.push_back(dz / len);
        m_length.push_back(len);
    }
}

double btRiverSurface::segmentDistance(std::size_t k, double x, double z) const {
    const btRiverPoint& a = m_s.centreline[k];
    const double px = x - a.x, pz = z - a.z;
    double s = px * m_tx[k] + pz * m_tz[k];  // the foot's arc length along the segment, m
    const std::size_t last = m_length.size() - 1;
    if (k > 0 && s < 0) s = 0;                         // the first segment continues upstream as a ray
    if (k < last && s > m_length[k]) s = m_length[k];  // the last one downstream
    return std::hypot(px - s * m_tx[k], pz - s * m_tz[k]);
}

double btRiverSurface::nearestSegment(double x, double z, std::size_t& outSegment) const {
    double d = std::numeric_limits<double>::infinity();
    outSegment = 0;
    for (std::size_t k = 0; k < m_length.size(); ++k) {
        const double dk = segmentDistance(k, x, z);
        if (dk < d) {
            d = dk;
            outSegment = k;
        }
    }
    return d;
}

double btRiverSurface::distanceToCentreline(double x, double z) const {
    std::size_t k = 0;
    return nearestSegment(x, z, k);
}

double btRiverSurface::speedAtDistance(double d) const {
    // The parabolic profile across the channel (design.md 2.8 "Rivers"): u_max on the centreline, 0 at the banks.
    const double q = 2.0 * std::abs(d) / m_s.width;
    return q < 1.0 ? m_s.surfaceSpeed * (1.0 - q * q) : 0.0;
}

void btRiverSurface::flowDirection(double x, double z, double& outX, double& outZ) const {
    std::size_t nearest = 0;
    const double d = nearestSegment(x, z, nearest);
    blendedTangent(x, z, d, nearest, outX, outZ);
}

void btRiverSurface::blendedTangent(double x, double z, double d, std::size_t nearest, double& outX,
                                    double& outZ) const {
    const std::size_t segments = m_length.size();
    // Tangents weighted by ω_k = (1 − (d_k − d)/b)², b = w/2 (design.md 2.8): continuous in (x, z), with a continuous
    // first derivative where a segment's weight reaches 0.
    const double b = 0.5 * m_s.width;
    double sx = 0, sz = 0;
    for (std::size_t k = 0; k < segments; ++k) {
        const double e = (segmentDistance(k, x, z) - d) / b;
        if (!(e < 1.0)) continue;
        const double omega = (1.0 - e) * (1.0 - e);
        sx += omega * m_tx[k];
        sz += omega * m_tz[k];
    }
    const double norm = std::hypot(sx, sz);
    if (norm > 1e-12) {
        outX = sx / norm;
        outZ = sz / norm;
    } else {  // tangents cancelling (a hairpin's opposite arms equally near): the nearest segment's
        outX = m_tx[nearest];
        outZ = m_tz[nearest];
    }
}

void btRiverSurface::heights(const double*, const double*, std::size_t n, double, double* outHeight) const {
    for (std::size_t i = 0; i < n; ++i) outHeight[i] = m_s.height;
}

void btRiverSurface::velocities(const double* x, const double*, const double* z, std::size_t n, double,
                                double* outVx, double* outVy, double* outVz) const {
    for (std::size_t i = 0; i < n; ++i) {
        outVy[i] = 0.0;
        std::size_t nearest = 0;
        const double d = nearestSegment(x[i], z[i], nearest);
        const double u = speedAtDistance(d);
        if (!(u > 0)) {  // on a bank or outside the channel: still water
            outVx[i] = outVz[i] = 0.0;
            continue;
        }
        double tx = 0, tz = 0;
        blendedTangent(x[i], z[i], d, nearest, tx, tz);
        outVx[i] = u * tx;
        outVz[i] = u * tz;
    }
}

void btRiverSurface::heightBounds(double, double, double, double, double, double& outMin, double& outMax) const {
    outMin = outMax = m_s.height;
}

bool btRiverSurface::isFlat(double, double& outHeight) const {
    outHeight = m_s.height;
    return true;
}
