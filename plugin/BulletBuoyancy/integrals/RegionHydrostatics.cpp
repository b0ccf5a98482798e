/// @file RegionHydrostatics.cpp
/// Exact-mesh hydrostatics of a body in several bounded water regions (declared in Hydrostatics.h, design.md 2.9):
/// each triangle is cut to each region's convex set, and the part inside is clipped against that region's water and
/// integrated exactly (WetTriangleIntegrals.h) with that region's density.

#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/WetTriangleIntegrals.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

/// Thread-local scratch: posed vertices and one region's water heights at them (grows, never shrinks).
struct RegionScratch {
    std::vector<Eigen::Vector3d> world;
    std::vector<double> x, z, f;
};

/// A triangle cut by at most WaterRegion::kMaxPlanes planes has at most 3 + kMaxPlanes corners.
constexpr int kMaxCorners = 3 + WaterRegion::kMaxPlanes;

/// Keep the part of the convex polygon `in` (n corners) with normal · p' ≤ offset', where p' = p + r (the pieces'
/// positions are relative to the reference point r); the water height f is interpolated linearly along the cut edges,
/// which keeps it the plane through the triangle's corner heights. Returns the new corner count.
int clipToPlane(const PieceVertex* in, int n, const Eigen::Vector3d& normal, double offset, PieceVertex* out) {
    int m = 0;
    for (int k = 0; k < n; ++k) {
        const PieceVertex& a = in[k];
        const PieceVertex& b = in[(k + 1) % n];
        const double da = normal.dot(a.p) - offset, db = normal.dot(b.p) - offset;
        if (da <= 0) out[m++] = a;
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            const double u = da / (da - db);
            PieceVertex x;
            x.p = a.p + u * (b.p - a.p);
            x.f = a.f + u * (b.f - a.f);
            out[m++] = x;
        }
    }
    return m;
}

}  // namespace

HydrostaticsResult regionHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose, const WaterRegion* regions,
                                      std::size_t count, double time, double gravity,
                                      const Eigen::Vector3d& torqueReference) {
    if (!std::isfinite(gravity)) throw std::invalid_argument("regionHydrostatics: gravity is not finite");
    for (std::size_t i = 0; i < count; ++i) {
        const double rho = regions[i].fluidDensity;
        if (!std::isfinite(rho) || rho < 0)
            throw std::invalid_argument("regionHydrostatics: region " + std::to_string(i) +
                                        ": fluid density must be finite and >= 0, got " + std::to_string(rho));
        if (!regions[i].water) throw std::invalid_argument("regionHydrostatics: region " + std::to_string(i) + ": no water");
        if (regions[i].planeCount < 0 || regions[i].planeCount > WaterRegion::kMaxPlanes)
            throw std::invalid_argument("regionHydrostatics: region " + std::to_string(i) + ": bad plane count");
    }
    const std::size_t nv = mesh.vertices.size();
    HydrostaticsResult out;
    if (mesh.triangles.empty() || nv == 0 || count == 0) return out;

    thread_local RegionScratch s;
    if (s.world.size() < nv) {
        s.world.resize(nv);
        s.x.resize(nv);
        s.z.resize(nv);
        s.f.resize(nv);
    }
    const Eigen::Vector3d& r = torqueReference;
    double minX = std::numeric_limits<double>::infinity(), minY = minX, minZ = minX;
    double maxX = -minX, maxZ = -minX;
    for (std::size_t i = 0; i < nv; ++i) {
        const Eigen::Vector3d w = pose * mesh.vertices[i];
        if (!w.allFinite())
            throw std::invalid_argument("regionHydrostatics: vertex " + std::to_string(i) +
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

    // Sums over the regions: the geometric fields as they are, the pressure fields scaled by each region's ρ g.
    double volume = 0, waterlineY = 0, wetted = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero(), force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    WaterlineSums waterline;
    for (std::size_t ri = 0; ri < count; ++ri) {
        const WaterRegion& region = regions[ri];
        // Planes relative to the reference point: normal · (p' + r) ≤ offset ⇔ normal · p' ≤ offset − normal · r.
        double offset[WaterRegion::kMaxPlanes];
        for (int k = 0; k < region.planeCount; ++k) offset[k] = region.offset[k] - region.normal[k].dot(r);
        double hMin = 0, hMax = 0;
        region.water->heightBounds(minX, minZ, maxX, maxZ, time, hMin, hMax);
        if (minY >= hMax) continue;  // entirely above this water
        double flatH = 0;
        if (region.water->isFlat(time, flatH))
            std::fill(s.f.begin(), s.f.begin() + nv, flatH);
        else
            region.water->heights(s.x.data(), s.z.data(), nv, time, s.f.data());
        for (std::size_t i = 0; i < nv; ++i)
            if (!std::isfinite(s.f[i]))
                throw std::runtime_error("regionHydrostatics: the water surface returned a non-finite height at x=" +
                                         std::to_string(s.x[i]) + ", z=" + std::to_string(s.z[i]));
        WetIntegrals I;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            const Eigen::Vector3i& tri = mesh.triangles[t];
            PieceVertex a[kMaxCorners], b[kMaxCorners];
            bool dry = true;
            for (int k = 0; k < 3; ++k) {
                const int idx = tri[k];
                if (idx < 0 || std::size_t(idx) >= nv)
                    throw std::invalid_argument("regionHydrostatics: triangle " + std::to_string(t) +
                                                " has vertex index " + std::to_string(idx) + " out of range");
                a[k].p = s.world[idx] - r;
                a[k].f = s.f[idx] - r.y();
                if (a[k].p.y() < a[k].f) dry = false;
            }
            if (dry) continue;  // above this water everywhere (the cuts below keep f the corners' plane)
            int n = 3;
            PieceVertex* in = a;
            PieceVertex* cut = b;
            for (int k = 0; k < region.planeCount && n >= 3; ++k) {
                n = clipToPlane(in, n, region.normal[k], offset[k], cut);
                std::swap(in, cut);
            }
            // The convex piece inside the region, as a fan of triangles, each clipped against the water.
            for (int k = 1; k + 1 < n; ++k) {
                const PieceVertex fan[3] = {in[0], in[k], in[k + 1]};
                I.addClippedTriangle(fan);
            }
        }
        const double rg = region.fluidDensity * gravity;
        volume += I.V;
        first += I.first;
        force += rg * I.dA;
        torque += rg * I.dpxA;
        waterlineY += I.Ay;
        wetted += I.area;
        waterline.add(I.waterline);
    }
    out.submerged_volume = volume;
    if (volume != 0) out.centre_of_buoyancy = r + first / volume;
    out.force = force;
    out.torque = torque;
    out.waterline_area = -waterlineY;
    out.wetted_area = wetted;
    // Valid only when the waterline's segments close (a body inside one region); a cut waterline leaves them open.
    out.waterplane = waterline.moments(out.waterline_area);
    if (!std::isfinite(out.submerged_volume) || !out.force.allFinite() || !out.torque.allFinite() ||
        !out.centre_of_buoyancy.allFinite())
        throw std::runtime_error("regionHydrostatics: non-finite result (non-finite pose, vertices or water heights)");
    return out;
}

}  // namespace buoyancy
