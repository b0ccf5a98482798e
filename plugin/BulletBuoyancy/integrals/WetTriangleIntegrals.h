#pragma once
/// @file WetTriangleIntegrals.h
/// The exact per-triangle hydrostatic integrals shared by the exact-mesh methods (ClippedHydrostatics.cpp:
/// every triangle; TreeHydrostatics.cpp: the triangles of the tree leaves that straddle the waterline).
/// Fields of design.md 2.2 and pressure of 2.3, integrated over flat wetted pieces, positions relative to
/// a reference point.

#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

/// A vertex of a clipped piece, relative to the reference point: position p' and water height f' over it, m.
struct PieceVertex {
    Eigen::Vector3d p;
    double f;
};

/// The waterline's segments summed into the waterplane's area moments (Green's theorem: each moment of the region a
/// closed polygon encloses is a sum over its edges). A segment goes from E to N along the boundary of the wetted
/// part of a triangle, counter-clockwise about its outward normal (wet side on the left), so the lid that closes the
/// submerged volume is bounded by N → E, counter-clockwise seen from above; with c = z_N x_E − x_N z_E:
///   A = ½ Σ c,  ∫x = ⅙ Σ (x_N + x_E) c,  ∫x² = 1/12 Σ (x_N² + x_N x_E + x_E²) c,
///   ∫xz = 1/24 Σ (2 x_N z_N + x_N z_E + x_E z_N + 2 x_E z_E) c   (z alike),
/// exact for the projected polygon whatever the origin (coordinates relative to the reference point here).
struct WaterlineSums {
    double area2 = 0, x6 = 0, z6 = 0, xx12 = 0, xz24 = 0, zz12 = 0;

    /// Add the segment E → N (world horizontal coordinates relative to the reference point, m).
    void add(double xe, double ze, double xn, double zn) {
        const double c = zn * xe - xn * ze;
        area2 += c;
        x6 += (xn + xe) * c;
        z6 += (zn + ze) * c;
        xx12 += (xn * xn + xn * xe + xe * xe) * c;
        zz12 += (zn * zn + zn * ze + ze * ze) * c;
        xz24 += (2.0 * xn * zn + xn * ze + xe * zn + 2.0 * xe * ze) * c;
    }
    /// Add another set of sums.
    void add(const WaterlineSums& o) {
        area2 += o.area2;
        x6 += o.x6;
        z6 += o.z6;
        xx12 += o.xx12;
        xz24 += o.xz24;
        zz12 += o.zz12;
    }
    /// The moments; valid when the segments' enclosed area matches the waterline area −∫_wet n_y (`waterlineArea`,
    /// m²) to 1e-6 of the larger, or both are 0 (a segment lost to a corner exactly on the water breaks the loop).
    WaterplaneMoments moments(double waterlineArea) const {
        WaterplaneMoments m;
        m.x = x6 / 6.0;
        m.z = z6 / 6.0;
        m.xx = xx12 / 12.0;
        m.xz = xz24 / 24.0;
        m.zz = zz12 / 12.0;
        const double area = 0.5 * area2;
        m.valid = std::isfinite(area) && std::isfinite(m.xx + m.xz + m.zz + m.x + m.z) &&
                  std::abs(area - waterlineArea) <= 1e-6 * std::max(std::abs(area), std::abs(waterlineArea)) + 1e-12;
        return m;
    }
};

/// Running (plain double) integrals over wetted pieces, positions relative to a reference point r:
/// V = ∫ (y − f) n_y, first = (∫ x'(y − f) n_y, ∫ (y'² − f'²)/2 n_y, ∫ z'(y − f) n_y),
/// dA = ∫ (y − f) n (force / ρg), dpxA = ∫ (y − f) p' × n (torque / ρg), Ay = Σ A^y, area = wetted area.
struct WetIntegrals {
    double V = 0;                                      ///< m³
    Eigen::Vector3d first = Eigen::Vector3d::Zero();   ///< m⁴
    Eigen::Vector3d dA = Eigen::Vector3d::Zero();      ///< m³
    Eigen::Vector3d dpxA = Eigen::Vector3d::Zero();    ///< m⁴
    double Ay = 0;                                     ///< m²
    double area = 0;                                   ///< m²
    WaterlineSums waterline;                           ///< the waterline's segments (waterplane moments)

    /// Exact integrals over the flat triangle (a, b, c), wetted everywhere (y ≤ f), f linear over it.
    void addTriangle(const PieceVertex& a, const PieceVertex& b, const PieceVertex& c) {
        const Eigen::Vector3d A = 0.5 * (b.p - a.p).cross(c.p - a.p);  // area × outward normal
        // Edge midpoints: the quadrature ∫ φ dS = |S|/3 Σ φ(m_k) is exact for φ of degree ≤ 2.
        // Each field is (polynomial) × n, so ∫ φ n dS = A/3 Σ φ(m_k).
        const PieceVertex* v[3] = {&a, &b, &c};
        double sd = 0, sdy = 0;                         // Σ d, Σ d (y' + f')/2
        Eigen::Vector3d sdp = Eigen::Vector3d::Zero();  // Σ d p'
        for (int k = 0; k < 3; ++k) {
            const PieceVertex& u = *v[k];
            const PieceVertex& w = *v[(k + 1) % 3];
            const Eigen::Vector3d m = 0.5 * (u.p + w.p);
            const double fm = 0.5 * (u.f + w.f);
            const double d = m.y() - fm;  // y − f ≤ 0
            sd += d;
            sdy += d * 0.5 * (m.y() + fm);
            sdp += d * m;
        }
        sd /= 3.0;
        sdy /= 3.0;
        sdp /= 3.0;
        V += A.y() * sd;               // ∫ (y − f) n_y
        first.x() += A.y() * sdp.x();  // ∫ x'(y − f) n_y
        first.y() += A.y() * sdy;      // ∫ (y'² − f'²)/2 n_y
        first.z() += A.y() * sdp.z();  // ∫ z'(y − f) n_y
        dA += sd * A;                  // ∫ (y − f) n     → F = ρg ∫ (y − f) n = −∫ P n
        dpxA += sdp.cross(A);          // ∫ (y − f) p' × n → τ = ρg ∫ (y − f) p' × n
        Ay += A.y();
        area += A.norm();
    }

    /// Clip the triangle (in[0], in[1], in[2]) against y − f ≤ 0 (f linear over it: the plane through its
    /// corners' heights; Sutherland–Hodgman) and add the wetted part.
    void addClippedTriangle(const PieceVertex in[3]) {
        double d[3];
        for (int k = 0; k < 3; ++k) d[k] = in[k].p.y() - in[k].f;
        if (d[0] >= 0 && d[1] >= 0 && d[2] >= 0) return;  // dry (or touching)
        PieceVertex poly[4];
        bool onWater[4];  // the piece's corners on the waterline (D = 0): its edges between two are the waterline's
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            const int k1 = (k + 1) % 3;
            if (d[k] <= 0) {
                onWater[n] = d[k] == 0;
                poly[n++] = in[k];
            }
            if ((d[k] < 0 && d[k1] > 0) || (d[k] > 0 && d[k1] < 0)) {
                const double u = d[k] / (d[k] - d[k1]);
                PieceVertex x;
                x.p = in[k].p + u * (in[k1].p - in[k].p);
                x.f = in[k].f + u * (in[k1].f - in[k].f);
                onWater[n] = true;
                poly[n++] = x;
            }
        }
        for (int k = 1; k + 1 < n; ++k) addTriangle(poly[0], poly[k], poly[k + 1]);
        for (int k = 0; k < n; ++k) {
            const int k1 = (k + 1) % n;
            if (onWater[k] && onWater[k1]) waterline.add(poly[k].p.x(), poly[k].p.z(), poly[k1].p.x(), poly[k1].p.z());
        }
    }

    /// The result: volume, centre of buoyancy r + first / V, force ρg·dA, torque ρg·dpxA about r, waterline area
    /// −Σ A^y (the cap area for a closed mesh in flat water, ∮ n_y = 0), wetted area.
    /// @param rg  ρ g, N/m³   @param r  the reference point the integrals are relative to, world, m
    /// @param who  function name for the error message
    /// @throws std::runtime_error for a non-finite result (non-finite pose, vertices or water heights)
    HydrostaticsResult result(double rg, const Eigen::Vector3d& r, const char* who) const {
        HydrostaticsResult res;
        res.submerged_volume = V;
        if (V != 0) res.centre_of_buoyancy = r + first / V;
        res.force = rg * dA;
        res.torque = rg * dpxA;
        res.waterline_area = -Ay;
        res.wetted_area = area;
        res.waterplane = waterline.moments(res.waterline_area);
        if (!std::isfinite(res.submerged_volume) || !res.force.allFinite() || !res.torque.allFinite() ||
            !res.centre_of_buoyancy.allFinite())
            throw std::runtime_error(std::string(who) + ": non-finite result (non-finite pose, vertices or water heights)");
        return res;
    }
};

}  // namespace buoyancy
