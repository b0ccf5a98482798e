/// @file WaveOracle.cpp
/// Divergence-theorem reference for curved water (declared in WaveOracle.h).

#include "oracles/WaveOracle.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace buoyancy_test {
namespace {

/// Dunavant's 6-point rule, exact for polynomials of degree 4 over a triangle: barycentric points and weights
/// (the weights sum to 1; multiply by the area).
struct QuadraturePoint {
    double l0, l1, l2, w;
};
constexpr double kA = 0.445948490915965, kB = 0.108103018168070, kWa = 0.223381589678011;
constexpr double kC = 0.091576213509771, kD = 0.816847572980459, kWc = 0.109951743655322;
constexpr QuadraturePoint kRule[6] = {{kB, kA, kA, kWa}, {kA, kB, kA, kWa}, {kA, kA, kB, kWa},
                                      {kD, kC, kC, kWc}, {kC, kD, kC, kWc}, {kC, kC, kD, kWc}};

/// Running sums of ∮ (...) n_y dS: the integrand values at a point times the quadrature weight × A_y.
struct Sums {
    double V = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

class Integrator {
public:
    Integrator(const WaveHeightFunction& eta, const Eigen::Vector3d& r, const WaveOracleOptions& o)
        : m_eta(eta), m_r(r), m_o(o) {}

    /// Integrate the flat triangle (a, b, c) with the n_y-weighted area Ay (= its area vector's y component).
    void triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
        const double Ay = 0.5 * (b - a).cross(c - a).y();
        if (Ay == 0) return;  // vertical: n_y = 0, no contribution to any field
        const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        const int n = std::max(1, int(std::ceil(longest / m_o.maxEdge)));
        // Uniform split into n² sub-triangles: grid points a + (i/n)(b − a) + (j/n)(c − a).
        const Eigen::Vector3d eb = (b - a) / double(n), ec = (c - a) / double(n);
        const double subAy = Ay / double(n * n);
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                const Eigen::Vector3d p = a + double(i) * eb + double(j) * ec;
                piece(p, p + eb, p + ec, subAy, m_o.waterlineLevels);
                if (i + j + 1 < n) piece(p + eb, p + eb + ec, p + ec, subAy, m_o.waterlineLevels);
            }
    }

    Sums sums;

private:
    double depth(const Eigen::Vector3d& p) const { return p.y() - m_eta(p.x(), p.z()); }

    void piece(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double Ay, int levels) {
        if (levels > 0) {
            const double da = depth(a), db = depth(b), dc = depth(c);
            const bool mixed = std::min({da, db, dc}) < 0 && std::max({da, db, dc}) > 0;
            if (mixed) {
                const Eigen::Vector3d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
                piece(a, ab, ca, 0.25 * Ay, levels - 1);
                piece(ab, b, bc, 0.25 * Ay, levels - 1);
                piece(ca, bc, c, 0.25 * Ay, levels - 1);
                piece(ab, bc, ca, 0.25 * Ay, levels - 1);
                return;
            }
        }
        for (const QuadraturePoint& q : kRule) point(q.l0 * a + q.l1 * b + q.l2 * c, q.w * Ay);
    }

    void point(const Eigen::Vector3d& p, double w) {
        const double x = p.x(), y = p.y(), z = p.z();
        const double eta = m_eta(x, z);
        if (y >= eta) return;  // above the water every field is 0
        const double D = y - eta;                        // min(y − η, 0)
        const double M = 0.5 * (y * y - eta * eta);      // (min(y, η)² − η²) / 2
        sums.V += w * D;
        sums.first += w * Eigen::Vector3d(x * D, M, z * D);
        if (!m_o.forceAndTorque) return;
        const double s = m_o.gradientStep;
        const double ex = (m_eta(x + s, z) - m_eta(x - s, z)) / (2 * s);
        const double ez = (m_eta(x, z + s) - m_eta(x, z - s)) / (2 * s);
        // f = (−η_x, 1, −η_z): force = ∫ f dV; each component has no y, so its field is (0, f_k D, 0).
        sums.force += w * D * Eigen::Vector3d(-ex, 1.0, -ez);
        // torque = ∫ (p − r) × f dV; the y − r_y part multiplies M − r_y D (∫ (y − r_y) g dV, g free of y).
        const double dx = x - m_r.x(), dz = z - m_r.z();
        const double Yterm = M - m_r.y() * D;  // ∮ (y − r_y) D-like field
        sums.torque.x() += w * (Yterm * (-ez) - dz * D);
        sums.torque.y() += w * D * (dz * (-ex) - dx * (-ez));
        sums.torque.z() += w * (dx * D - Yterm * (-ex));
    }

    const WaveHeightFunction& m_eta;
    Eigen::Vector3d m_r;
    WaveOracleOptions m_o;
};

}  // namespace

WaveOracleResult waveOracle(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris,
                            const WaveHeightFunction& eta, const Eigen::Vector3d& torqueReference,
                            const WaveOracleOptions& options) {
    Integrator I(eta, torqueReference, options);
    for (const Eigen::Vector3i& t : tris) {
        const Eigen::Vector3d &a = verts[std::size_t(t[0])], &b = verts[std::size_t(t[1])], &c = verts[std::size_t(t[2])];
        if (std::min({a.y(), b.y(), c.y()}) > options.waterMax) continue;  // dry everywhere
        if (!(options.kinkSpacing > 0)) {
            I.triangle(a, b, c);
            continue;
        }
        // Clip the triangle to every lattice cell its footprint's box meets (Sutherland–Hodgman against the cell's
        // four sides), then integrate the fan of each clipped polygon.
        const double s = options.kinkSpacing;
        const double minX = std::min({a.x(), b.x(), c.x()}), maxX = std::max({a.x(), b.x(), c.x()});
        const double minZ = std::min({a.z(), b.z(), c.z()}), maxZ = std::max({a.z(), b.z(), c.z()});
        const long long i0 = (long long)std::floor((minX - options.kinkOriginX) / s);
        const long long i1 = (long long)std::floor((maxX - options.kinkOriginX) / s);
        const long long j0 = (long long)std::floor((minZ - options.kinkOriginZ) / s);
        const long long j1 = (long long)std::floor((maxZ - options.kinkOriginZ) / s);
        for (long long i = i0; i <= i1; ++i)
            for (long long j = j0; j <= j1; ++j) {
                std::vector<Eigen::Vector3d> poly = {a, b, c};
                const double cx0 = options.kinkOriginX + double(i) * s, cz0 = options.kinkOriginZ + double(j) * s;
                // Half-planes sign·(p[axis] − bound) ≥ 0 bounding the cell.
                const struct {
                    int axis;
                    double bound, sign;
                } sides[4] = {{0, cx0, 1.0}, {0, cx0 + s, -1.0}, {2, cz0, 1.0}, {2, cz0 + s, -1.0}};
                for (const auto& side : sides) {
                    std::vector<Eigen::Vector3d> out;
                    for (std::size_t k = 0; k < poly.size(); ++k) {
                        const Eigen::Vector3d& p = poly[k];
                        const Eigen::Vector3d& q = poly[(k + 1) % poly.size()];
                        const double dp = side.sign * (p[side.axis] - side.bound);
                        const double dq = side.sign * (q[side.axis] - side.bound);
                        if (dp >= 0) out.push_back(p);
                        if ((dp >= 0) != (dq >= 0)) out.push_back(p + (dp / (dp - dq)) * (q - p));
                    }
                    poly.swap(out);
                    if (poly.size() < 3) break;
                }
                for (std::size_t k = 1; k + 1 < poly.size(); ++k) I.triangle(poly[0], poly[k], poly[k + 1]);
            }
    }
    WaveOracleResult r;
    r.volume = I.sums.V;
    r.firstMoment = I.sums.first;
    r.force = I.sums.force;
    r.torque = I.sums.torque;
    return r;
}

double bilinearBoxVolume(const WaveHeightFunction& eta, double ox, double oz, double s, double x0, double x1, double z0,
                         double z1, double yBottom) {
    double V = 0;
    for (long long i = (long long)std::floor((x0 - ox) / s); ox + double(i) * s < x1; ++i)
        for (long long j = (long long)std::floor((z0 - oz) / s); oz + double(j) * s < z1; ++j) {
            const double xa = std::max(x0, ox + double(i) * s), xb = std::min(x1, ox + double(i + 1) * s);
            const double za = std::max(z0, oz + double(j) * s), zb = std::min(z1, oz + double(j + 1) * s);
            if (xb <= xa || zb <= za) continue;
            V += (xb - xa) * (zb - za) * (eta(0.5 * (xa + xb), 0.5 * (za + zb)) - yBottom);
        }
    return V;
}

double airyBoxVolume(double a, double k, double phase, double x0, double x1, double yBottom, double lengthZ) {
    return lengthZ * ((a / k) * (std::sin(k * x1 + phase) - std::sin(k * x0 + phase)) - yBottom * (x1 - x0));
}

}  // namespace buoyancy_test
