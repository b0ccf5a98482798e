/// @file ClippedHydrostatics.cpp
/// Exact-mesh hydrostatics (declared in Hydrostatics.h): every triangle of the posed mesh is clipped
/// against the water and the fields of DESIGN-NOTES 2.2 / pressure of 2.3 are integrated exactly over
/// the wetted pieces. Exact for flat water (the integrands are polynomials of degree ≤ 2 over each flat
/// piece, integrated with the edge-midpoint rule, exact for quadratics). On waves the water over each
/// triangle is replaced by the plane through its corners' heights: an approximation, not exact.

#include "integrals/Hydrostatics.h"
#include "integrals/WaterPatch.h"
#include "water/btWaterSurface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

/// Thread-local scratch: posed vertices and their water heights (grows, never shrinks).
struct ClipScratch {
    std::vector<Eigen::Vector3d> world;
    std::vector<double> x, z, f;
};

/// A vertex of a clipped piece, relative to the reference point: position p' and water height f'.
struct PieceVertex {
    Eigen::Vector3d p;
    double f;
};

/// Running (plain double) integrals: V, ∫p', Σ d A (force / ρg), Σ ∫ d p' × n (torque / ρg), Σ A^y, area.
struct Integrals {
    double V = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    Eigen::Vector3d dA = Eigen::Vector3d::Zero();
    Eigen::Vector3d dpxA = Eigen::Vector3d::Zero();
    double Ay = 0;
    double area = 0;

    /// Exact integrals over the flat triangle (a, b, c), wetted everywhere (y ≤ f), f linear over it.
    void addTriangle(const PieceVertex& a, const PieceVertex& b, const PieceVertex& c) {
        const Eigen::Vector3d A = 0.5 * (b.p - a.p).cross(c.p - a.p);  // area × outward normal
        // Edge midpoints: the quadrature ∫ φ dS = |S|/3 Σ φ(m_k) is exact for φ of degree ≤ 2.
        // Each field is (polynomial) × n, so ∫ φ n dS = A/3 Σ φ(m_k).
        const PieceVertex* v[3] = {&a, &b, &c};
        double sd = 0, sdy = 0;  // Σ d, Σ d (y' + f')/2
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
        V += A.y() * sd;            // ∫ (y − f) n_y
        first.x() += A.y() * sdp.x();  // ∫ x'(y − f) n_y
        first.y() += A.y() * sdy;      // ∫ (y'² − f'²)/2 n_y
        first.z() += A.y() * sdp.z();  // ∫ z'(y − f) n_y
        dA += sd * A;               // ∫ (y − f) n     → F = ρg ∫ (y − f) n = −∫ P n
        dpxA += sdp.cross(A);       // ∫ (y − f) p' × n → τ = ρg ∫ (y − f) p' × n
        Ay += A.y();
        area += A.norm();
    }
};

}  // namespace

HydrostaticsResult clippedHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference) {
    return clippedHydrostatics(mesh, pose, water, time, fluidDensity, gravity, torqueReference, nullptr);
}

HydrostaticsResult clippedHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference,
                                       const WaterPatch* patch) {
    if (!std::isfinite(fluidDensity) || fluidDensity < 0)
        throw std::invalid_argument("clippedHydrostatics: fluid density must be finite and ≥ 0, got " +
                                    std::to_string(fluidDensity));
    if (!std::isfinite(gravity)) throw std::invalid_argument("clippedHydrostatics: gravity is not finite");
    const std::size_t nv = mesh.vertices.size();
    if (mesh.triangles.empty() || nv == 0) return HydrostaticsResult{};

    thread_local ClipScratch s;
    if (s.world.size() < nv) {
        s.world.resize(nv);
        s.x.resize(nv);
        s.z.resize(nv);
        s.f.resize(nv);
    }
    double minX = std::numeric_limits<double>::infinity(), minY = minX, minZ = minX;
    double maxX = -minX, maxZ = -minX;
    for (std::size_t i = 0; i < nv; ++i) {
        const Eigen::Vector3d w = pose * mesh.vertices[i];
        if (!w.allFinite())
            throw std::invalid_argument("clippedHydrostatics: vertex " + std::to_string(i) +
                                        " is not finite after the pose (non-finite vertex or pose)");
        s.world[i] = w;
        s.x[i] = w.x();
        s.z[i] = w.z();
        minX = std::min(minX, w.x());
        maxX = std::max(maxX, w.x());
        minY = std::min(minY, w.y());
        minZ = std::min(minZ, w.z());
        maxZ = std::max(maxZ, w.z());
    }
    double hMin = 0, hMax = 0;
    water.heightBounds(minX, minZ, maxX, maxZ, time, hMin, hMax);
    if (minY >= hMax) return HydrostaticsResult{};  // entirely above the water (DESIGN-NOTES 2.5)

    double flatH = 0;
    if (water.isFlat(time, flatH))
        std::fill(s.f.begin(), s.f.begin() + nv, flatH);
    else if (patch)
        patch->heights(s.x.data(), s.z.data(), nv, s.f.data());  // interpolated (DESIGN-NOTES 2.5)
    else
        water.heights(s.x.data(), s.z.data(), nv, time, s.f.data());  // heights at the corners, one batch
    for (std::size_t i = 0; i < nv; ++i)
        if (!std::isfinite(s.f[i]))
            throw std::runtime_error("clippedHydrostatics: the water surface returned a non-finite height at x=" +
                                     std::to_string(s.x[i]) + ", z=" + std::to_string(s.z[i]));

    const Eigen::Vector3d& r = torqueReference;
    Integrals I;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        PieceVertex in[3];
        double d[3];
        for (int k = 0; k < 3; ++k) {
            const int idx = tri[k];
            if (idx < 0 || std::size_t(idx) >= nv)
                throw std::invalid_argument("clippedHydrostatics: triangle " + std::to_string(t) +
                                            " has vertex index " + std::to_string(idx) + " out of range");
            in[k].p = s.world[idx] - r;
            in[k].f = s.f[idx] - r.y();
            d[k] = in[k].p.y() - in[k].f;
        }
        if (d[0] >= 0 && d[1] >= 0 && d[2] >= 0) continue;  // dry (or touching)
        if (d[0] <= 0 && d[1] <= 0 && d[2] <= 0) {
            I.addTriangle(in[0], in[1], in[2]);
            continue;
        }
        // Sutherland–Hodgman against d = y − f ≤ 0, f linear over the triangle (plane through the corners).
        PieceVertex poly[4];
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            const int k1 = (k + 1) % 3;
            if (d[k] <= 0) poly[n++] = in[k];
            if ((d[k] < 0 && d[k1] > 0) || (d[k] > 0 && d[k1] < 0)) {
                const double u = d[k] / (d[k] - d[k1]);
                PieceVertex x;
                x.p = in[k].p + u * (in[k1].p - in[k].p);
                x.f = in[k].f + u * (in[k1].f - in[k].f);
                poly[n++] = x;
            }
        }
        for (int k = 1; k + 1 < n; ++k) I.addTriangle(poly[0], poly[k], poly[k + 1]);
    }

    const double rg = fluidDensity * gravity;
    HydrostaticsResult res;
    res.submerged_volume = I.V;
    if (I.V != 0) res.centre_of_buoyancy = r + I.first / I.V;
    res.force = rg * I.dA;
    res.torque = rg * I.dpxA;
    res.waterline_area = -I.Ay;  // = cap area for a closed mesh in flat water (∮ n_y = 0)
    res.wetted_area = I.area;
    if (!std::isfinite(res.submerged_volume) || !res.force.allFinite() || !res.torque.allFinite() ||
        !res.centre_of_buoyancy.allFinite())
        throw std::runtime_error("clippedHydrostatics: non-finite result (non-finite pose, vertices or water heights)");
    return res;
}

}  // namespace buoyancy
