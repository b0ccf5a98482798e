/// @file CurvedHydrostatics.cpp
/// Exact-mesh hydrostatics on curved water (declared in Hydrostatics.h; design.md 2.5 "water curved over a
/// triangle"). The water over each triangle that can be wet is modelled by the quadratic through its heights at the
/// three corners and the three edge midpoints (the P2 interpolant), sampled from the surface (or the body's patch).
/// Over a wet piece the integrands of design.md 2.2–2.3 are then polynomials in the barycentric coordinates:
/// (y − f) of degree 2, x(y − f) and (y − f) p of degree 3, (y² − f²)/2 of degree 4, integrated exactly by
/// Dunavant's 6-point rule of degree 4. The error left is the water's third-order part over the triangle
/// (≈ f''' h³ of a triangle of size h), so triangles larger than the cube root of (tolerance / f''') are split
/// 1:4 first, with fresh heights at the new midpoints, level by level (each level's heights in one batch query).
/// A triangle the waterline crosses is cut into its four P2 sub-triangles, each clipped against the plane through
/// its corners' exact depths; the pieces keep the quadratic water, so only the waterline's position is linear: an
/// error of second order in its misplacement (the integrand vanishes on it).

#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/integrals/WetTriangleIntegrals.h>
#include <BulletBuoyancy/mesh/MeshEdges.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace buoyancy {
namespace {

/// Dunavant's 6-point rule (degree 4): barycentric points (l0, l1, l2) and weights summing to 1.
struct QuadraturePoint {
    double l0, l1, l2, w;
};
constexpr double kQa = 0.445948490915965, kQb = 0.108103018168070, kQwa = 0.223381589678011;
constexpr double kQc = 0.091576213509771, kQd = 0.816847572980459, kQwc = 0.109951743655322;
constexpr QuadraturePoint kRule[6] = {{kQb, kQa, kQa, kQwa}, {kQa, kQb, kQa, kQwa}, {kQa, kQa, kQb, kQwa},
                                      {kQd, kQc, kQc, kQwc}, {kQc, kQd, kQc, kQwc}, {kQc, kQc, kQd, kQwc}};

/// Splits of a triangle at most (4^kMaxLevels sub-triangles).
constexpr int kMaxLevels = 4;

/// A triangle of the water model: corners 0–2 and the midpoints of its sides 0–1, 1–2, 2–0 (world positions relative
/// to the reference point), the water height at each (relative to the reference point's y).
struct Patch6 {
    Eigen::Vector3d p[6];
    double f[6];
    int level;
};

/// The P2 interpolant of the water over t at barycentric (l0, l1, l2).
inline double quadraticWater(const Patch6& t, double l0, double l1, double l2) {
    return t.f[0] * l0 * (2 * l0 - 1) + t.f[1] * l1 * (2 * l1 - 1) + t.f[2] * l2 * (2 * l2 - 1) +
           4.0 * (t.f[3] * l0 * l1 + t.f[4] * l1 * l2 + t.f[5] * l2 * l0);
}

/// A point of a piece in the barycentric coordinates of its Patch6, and its depth y − f there.
struct BaryPoint {
    double l[3];
    double d;
};

/// Add the piece (a, b, c) of t (barycentric corners) with the quadratic water of t.
void addPiece(const Patch6& t, const BaryPoint& a, const BaryPoint& b, const BaryPoint& c, WetIntegrals& I) {
    const auto at = [&](const double l[3]) { return Eigen::Vector3d(l[0] * t.p[0] + l[1] * t.p[1] + l[2] * t.p[2]); };
    const Eigen::Vector3d pa = at(a.l), pb = at(b.l), pc = at(c.l);
    const Eigen::Vector3d A = 0.5 * (pb - pa).cross(pc - pa);  // area × outward normal
    double sd = 0, sdy = 0;
    Eigen::Vector3d sdp = Eigen::Vector3d::Zero();
    for (const QuadraturePoint& q : kRule) {
        const double l0 = q.l0 * a.l[0] + q.l1 * b.l[0] + q.l2 * c.l[0];
        const double l1 = q.l0 * a.l[1] + q.l1 * b.l[1] + q.l2 * c.l[1];
        const double l2 = q.l0 * a.l[2] + q.l1 * b.l[2] + q.l2 * c.l[2];
        const Eigen::Vector3d p = q.l0 * pa + q.l1 * pb + q.l2 * pc;
        const double f = quadraticWater(t, l0, l1, l2);
        const double d = p.y() - f;
        sd += q.w * d;
        sdy += q.w * d * 0.5 * (p.y() + f);
        sdp += q.w * d * p;
    }
    I.V += A.y() * sd;
    I.first.x() += A.y() * sdp.x();
    I.first.y() += A.y() * sdy;
    I.first.z() += A.y() * sdp.z();
    I.dA += sd * A;
    I.dpxA += sdp.cross(A);
    I.Ay += A.y();
    I.area += A.norm();
}

/// Integrate one triangle of the water model (no further split).
void integrate(const Patch6& t, WetIntegrals& I) {
    double D[6];
    bool wet = true;
    for (int k = 0; k < 6; ++k) {
        D[k] = t.p[k].y() - t.f[k];
        if (D[k] > 0) wet = false;
    }
    static constexpr double kCorner[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
    const auto node = [&](int k) {
        BaryPoint b;
        b.l[0] = kCorner[k][0];
        b.l[1] = kCorner[k][1];
        b.l[2] = kCorner[k][2];
        b.d = D[k];
        return b;
    };
    if (wet) {
        addPiece(t, node(0), node(1), node(2), I);
        return;
    }
    // The four P2 sub-triangles (same orientation as t), each clipped against its corners' depths.
    static constexpr int kSub[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
    for (const auto& s : kSub) {
        const BaryPoint in[3] = {node(s[0]), node(s[1]), node(s[2])};
        if (in[0].d >= 0 && in[1].d >= 0 && in[2].d >= 0) continue;
        BaryPoint poly[4];
        bool onWater[4];
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            const int k1 = (k + 1) % 3;
            if (in[k].d <= 0) {
                onWater[n] = in[k].d == 0;
                poly[n++] = in[k];
            }
            if ((in[k].d < 0 && in[k1].d > 0) || (in[k].d > 0 && in[k1].d < 0)) {
                const double u = in[k].d / (in[k].d - in[k1].d);
                BaryPoint x;
                for (int j = 0; j < 3; ++j) x.l[j] = in[k].l[j] + u * (in[k1].l[j] - in[k].l[j]);
                x.d = 0;
                onWater[n] = true;
                poly[n++] = x;
            }
        }
        for (int k = 1; k + 1 < n; ++k) addPiece(t, poly[0], poly[k], poly[k + 1], I);
        for (int k = 0; k < n; ++k) {
            const int k1 = (k + 1) % n;
            if (!(onWater[k] && onWater[k1])) continue;
            const auto xz = [&](const BaryPoint& b, double& x, double& z) {
                x = b.l[0] * t.p[0].x() + b.l[1] * t.p[1].x() + b.l[2] * t.p[2].x();
                z = b.l[0] * t.p[0].z() + b.l[1] * t.p[1].z() + b.l[2] * t.p[2].z();
            };
            double xe, ze, xn, zn;
            xz(poly[k], xe, ze);
            xz(poly[k1], xn, zn);
            I.waterline.add(xe, ze, xn, zn);
        }
    }
}

inline double longestSide(const Patch6& t) {
    return std::sqrt(std::max({(t.p[1] - t.p[0]).squaredNorm(), (t.p[2] - t.p[1]).squaredNorm(),
                               (t.p[0] - t.p[2]).squaredNorm()}));
}

/// A convex planar polygon (world points): a triangle cut by vertical lattice planes has at most 3 + 2 + 2 corners.
struct CutPolygon {
    static constexpr int kCapacity = 10;
    Eigen::Vector3d v[kCapacity];
    int n = 0;
    CutPolygon() {
        for (Eigen::Vector3d& p : v) p.setZero();
    }
};

/// Split `in` by the vertical plane p[axis] = c into the part with p[axis] ≤ c and the part with p[axis] ≥ c (corners
/// in the same order, so the same orientation).
void splitPolygon(const CutPolygon& in, int axis, double c, CutPolygon& below, CutPolygon& above) {
    below.n = above.n = 0;
    for (int k = 0; k < in.n; ++k) {
        const Eigen::Vector3d& a = in.v[k];
        const Eigen::Vector3d& b = in.v[(k + 1) % in.n];
        const double da = a[axis] - c, db = b[axis] - c;
        if (da <= 0 && below.n < CutPolygon::kCapacity) below.v[below.n++] = a;
        if (da >= 0 && above.n < CutPolygon::kCapacity) above.v[above.n++] = a;
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            Eigen::Vector3d x = a + (da / (da - db)) * (b - a);
            x[axis] = c;
            if (below.n < CutPolygon::kCapacity) below.v[below.n++] = x;
            if (above.n < CutPolygon::kCapacity) above.v[above.n++] = x;
        }
    }
}

/// Cut `poly` along every lattice line x = origin + k·spacing (axis 0) or z = … (axis 2) strictly inside its extent;
/// calls emit(piece) for each piece, in order along the axis.
template <class Emit>
void cutAlong(const CutPolygon& poly, int axis, double origin, double spacing, Emit&& emit) {
    double lo = poly.v[0][axis], hi = lo;
    for (int k = 1; k < poly.n; ++k) {
        lo = std::min(lo, poly.v[k][axis]);
        hi = std::max(hi, poly.v[k][axis]);
    }
    const double first = std::floor((lo - origin) / spacing) + 1.0, last = std::ceil((hi - origin) / spacing) - 1.0;
    CutPolygon rest = poly, below, above;
    for (double k = first; k <= last; k += 1.0) {
        const double c = origin + k * spacing;
        if (!(c > lo && c < hi)) continue;
        splitPolygon(rest, axis, c, below, above);
        if (below.n >= 3) emit(below);
        rest = above;
        if (rest.n < 3) return;
    }
    emit(rest);
}

/// Thread-local scratch (grows, never shrinks).
struct CurvedScratch {
    std::vector<Eigen::Vector3d> world;  ///< posed vertices, world
    std::vector<char> vertexNeeded, edgeNeeded;
    std::vector<int> vertexSlot, edgeSlot;
    std::vector<double> qx, qz, qf;      ///< one batch of query points and their heights
    std::vector<Patch6> current, next;
    std::vector<std::size_t> pieceCell;  ///< lattice water: each piece's cell (index of its lower-left node)
    std::vector<int> nodeSlot;           ///< lattice water: each node's query slot (−1: not needed)
};

/// Largest table of lattice nodes under one body (beyond it, six height queries per piece instead).
constexpr double kMaxLatticeNodes = 1 << 22;

}  // namespace

HydrostaticsResult curvedHydrostatics(const TriangleMesh& mesh, const MeshEdges& edges, const Eigen::Isometry3d& pose,
                                      const btWaterSurface& water, double time, double fluidDensity, double gravity,
                                      const Eigen::Vector3d& torqueReference, double thickness, const WaterPatch* patch) {
    if (!std::isfinite(fluidDensity) || fluidDensity < 0)
        throw std::invalid_argument("curvedHydrostatics: fluid density must be finite and ≥ 0, got " +
                                    std::to_string(fluidDensity));
    if (!std::isfinite(gravity)) throw std::invalid_argument("curvedHydrostatics: gravity is not finite");
    const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
    if (nt == 0 || nv == 0) return HydrostaticsResult{};
    if (edges.triangleEdges.size() != nt)
        throw std::invalid_argument("curvedHydrostatics: the edges were built for another mesh");
    thread_local CurvedScratch s;
    if (s.world.size() < nv) {
        s.world.resize(nv);
        s.vertexNeeded.resize(nv);
        s.vertexSlot.resize(nv);
    }
    const std::size_t ne = edges.edges.size();
    if (s.edgeNeeded.size() < ne) {
        s.edgeNeeded.resize(ne);
        s.edgeSlot.resize(ne);
    }
    double minX = std::numeric_limits<double>::infinity(), minY = minX, minZ = minX;
    double maxX = -minX, maxZ = -minX;
    for (std::size_t i = 0; i < nv; ++i) {
        const Eigen::Vector3d w = pose * mesh.vertices[i];
        if (!w.allFinite())
            throw std::invalid_argument("curvedHydrostatics: vertex " + std::to_string(i) +
                                        " is not finite after the pose (non-finite vertex or pose)");
        s.world[i] = w;
        minX = std::min(minX, w.x());
        maxX = std::max(maxX, w.x());
        minY = std::min(minY, w.y());
        minZ = std::min(minZ, w.z());
        maxZ = std::max(maxZ, w.z());
    }
    double hMin = 0, hMax = 0;
    water.heightBounds(minX, minZ, maxX, maxZ, time, hMin, hMax);
    if (minY >= hMax) return HydrostaticsResult{};  // entirely above the water (design.md 2.5)

    const Eigen::Vector3d& r = torqueReference;
    WetIntegrals I;

    // Water bilinear over a lattice of cells (a grid, an FFT ocean without choppiness): cut every triangle that can
    // be wet along the lattice lines; over each piece the water is then exactly quadratic (a + b x + c z + d x z along
    // the piece's plane), so the P2 model through its six heights is the water itself (design.md 2.5). The heights
    // come from the surface (a patch's interpolation would not be bilinear).
    btWaterLattice lattice;
    if (water.bilinearLattice(time, lattice)) {
        if (!(std::isfinite(lattice.originX) && std::isfinite(lattice.originZ) && lattice.spacingX > 0 &&
              lattice.spacingZ > 0 && std::isfinite(lattice.spacingX) && std::isfinite(lattice.spacingZ)))
            throw std::runtime_error("curvedHydrostatics: the water surface reported a lattice with a non-positive or "
                                     "non-finite spacing");
        // The lattice nodes under the triangles that can be wet: i0..i1 along x, j0..j1 along z.
        double bx0 = std::numeric_limits<double>::infinity(), bz0 = bx0, bx1 = -bx0, bz1 = -bx0;
        for (std::size_t t = 0; t < nt; ++t) {
            const Eigen::Vector3i& tri = mesh.triangles[t];
            for (int k = 0; k < 3; ++k)
                if (tri[k] < 0 || std::size_t(tri[k]) >= nv)
                    throw std::invalid_argument("curvedHydrostatics: triangle " + std::to_string(t) +
                                                " has vertex index " + std::to_string(tri[k]) + " out of range");
            const Eigen::Vector3d &a = s.world[std::size_t(tri[0])], &b = s.world[std::size_t(tri[1])],
                                  &c = s.world[std::size_t(tri[2])];
            if (std::min({a.y(), b.y(), c.y()}) >= hMax) continue;
            bx0 = std::min({bx0, a.x(), b.x(), c.x()});
            bx1 = std::max({bx1, a.x(), b.x(), c.x()});
            bz0 = std::min({bz0, a.z(), b.z(), c.z()});
            bz1 = std::max({bz1, a.z(), b.z(), c.z()});
        }
        if (!(bx0 <= bx1)) return I.result(fluidDensity * gravity, r, "curvedHydrostatics");  // nothing can be wet
        const double i0 = std::floor((bx0 - lattice.originX) / lattice.spacingX);
        const double j0 = std::floor((bz0 - lattice.originZ) / lattice.spacingZ);
        const double ni = std::floor((bx1 - lattice.originX) / lattice.spacingX) - i0 + 2.0;  // nodes along x
        const double nj = std::floor((bz1 - lattice.originZ) / lattice.spacingZ) - j0 + 2.0;
        // Heights at the nodes (one query each, then the bilinear formula) unless the body covers so many cells that
        // a table of its nodes would be large: then six queries per piece.
        const bool byNodes = ni * nj <= double(kMaxLatticeNodes);
        const std::size_t nodeCount = byNodes ? std::size_t(ni * nj) : 0;
        const std::size_t rowLength = byNodes ? std::size_t(ni) : 0;
        s.current.clear();
        s.pieceCell.clear();
        s.qx.clear();
        s.qz.clear();
        if (byNodes) s.nodeSlot.assign(nodeCount, -1);
        const auto addPieceTriangle = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          std::size_t cell) {
            Patch6 p{};
            p.level = 0;
            p.p[0] = a - r;
            p.p[1] = b - r;
            p.p[2] = c - r;
            p.p[3] = 0.5 * (a + b) - r;
            p.p[4] = 0.5 * (b + c) - r;
            p.p[5] = 0.5 * (c + a) - r;
            if (!byNodes)
                for (int k = 0; k < 6; ++k) {
                    const Eigen::Vector3d w = p.p[k] + r;
                    s.qx.push_back(w.x());
                    s.qz.push_back(w.z());
                }
            s.current.push_back(p);
            s.pieceCell.push_back(cell);
        };
        for (std::size_t t = 0; t < nt; ++t) {
            const Eigen::Vector3i& tri = mesh.triangles[t];
            const Eigen::Vector3d &a = s.world[std::size_t(tri[0])], &b = s.world[std::size_t(tri[1])],
                                  &c = s.world[std::size_t(tri[2])];
            if (std::min({a.y(), b.y(), c.y()}) >= hMax) continue;
            CutPolygon poly;
            poly.v[0] = a;
            poly.v[1] = b;
            poly.v[2] = c;
            poly.n = 3;
            cutAlong(poly, 0, lattice.originX, lattice.spacingX, [&](const CutPolygon& strip) {
                cutAlong(strip, 2, lattice.originZ, lattice.spacingZ, [&](const CutPolygon& piece) {
                    // The piece's cell: the one holding its centroid (a piece lies inside one cell).
                    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
                    for (int k = 0; k < piece.n; ++k) centre += piece.v[k];
                    centre /= double(piece.n);
                    std::size_t cell = 0;
                    if (byNodes) {
                        const double ci = std::clamp(std::floor((centre.x() - lattice.originX) / lattice.spacingX) - i0,
                                                     0.0, ni - 2.0);
                        const double cj = std::clamp(std::floor((centre.z() - lattice.originZ) / lattice.spacingZ) - j0,
                                                     0.0, nj - 2.0);
                        cell = std::size_t(cj) * rowLength + std::size_t(ci);
                        for (const std::size_t node : {cell, cell + 1, cell + rowLength, cell + rowLength + 1})
                            if (s.nodeSlot[node] < 0) {
                                s.nodeSlot[node] = int(s.qx.size());
                                s.qx.push_back(lattice.originX + (i0 + double(node % rowLength)) * lattice.spacingX);
                                s.qz.push_back(lattice.originZ + (j0 + double(node / rowLength)) * lattice.spacingZ);
                            }
                    }
                    for (int k = 1; k + 1 < piece.n; ++k) addPieceTriangle(piece.v[0], piece.v[k], piece.v[k + 1], cell);
                });
            });
        }
        s.qf.resize(s.qx.size());
        water.heights(s.qx.data(), s.qz.data(), s.qx.size(), time, s.qf.data());
        for (std::size_t i = 0; i < s.qf.size(); ++i)
            if (!std::isfinite(s.qf[i]))
                throw std::runtime_error("curvedHydrostatics: the water surface returned a non-finite height at x=" +
                                         std::to_string(s.qx[i]) + ", z=" + std::to_string(s.qz[i]));
        for (std::size_t i = 0; i < s.current.size(); ++i) {
            Patch6& p = s.current[i];
            if (byNodes) {
                // The bilinear water of the piece's cell from its corner heights.
                const std::size_t cell = s.pieceCell[i];
                const double h00 = s.qf[std::size_t(s.nodeSlot[cell])], h10 = s.qf[std::size_t(s.nodeSlot[cell + 1])];
                const double h01 = s.qf[std::size_t(s.nodeSlot[cell + rowLength])];
                const double h11 = s.qf[std::size_t(s.nodeSlot[cell + rowLength + 1])];
                const double cx = lattice.originX + (i0 + double(cell % rowLength)) * lattice.spacingX;
                const double cz = lattice.originZ + (j0 + double(cell / rowLength)) * lattice.spacingZ;
                for (int k = 0; k < 6; ++k) {
                    const double u = (p.p[k].x() + r.x() - cx) / lattice.spacingX;
                    const double v = (p.p[k].z() + r.z() - cz) / lattice.spacingZ;
                    p.f[k] = (1 - v) * ((1 - u) * h00 + u * h10) + v * ((1 - u) * h01 + u * h11) - r.y();
                }
            } else {
                for (int k = 0; k < 6; ++k) p.f[k] = s.qf[6 * i + std::size_t(k)] - r.y();
            }
            bool wetNode = false;
            for (int k = 0; k < 6; ++k)
                if (p.p[k].y() < p.f[k]) wetNode = true;
            if (wetNode) integrate(p, I);
        }
        return I.result(fluidDensity * gravity, r, "curvedHydrostatics");
    }

    // Split triangles longer than the side h at which the third-order part of the water over them, ≈ K₃ h³, reaches
    // the tolerance (kCurvedWaterTolerance × the body's mean thickness V / A: the volume it can add is ≲ that × the
    // wet area). The scale K₃ is the patch's when the heights come from it, else the surface's.
    const double K3 = patch ? patch->thirdDerivativeBound() : water.heightThirdDerivativeScale(time);
    const double tolerance = kCurvedWaterTolerance * std::max(thickness, 0.0);
    const double maxSide = K3 > 0 && tolerance > 0 ? std::cbrt(tolerance / K3) : std::numeric_limits<double>::infinity();

    // Level 0: every triangle with a corner below the highest water; heights at its corners and side midpoints.
    std::fill(s.vertexNeeded.begin(), s.vertexNeeded.begin() + nv, 0);
    std::fill(s.edgeNeeded.begin(), s.edgeNeeded.begin() + ne, 0);
    for (std::size_t t = 0; t < nt; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] < 0 || std::size_t(tri[k]) >= nv)
                throw std::invalid_argument("curvedHydrostatics: triangle " + std::to_string(t) + " has vertex index " +
                                            std::to_string(tri[k]) + " out of range");
        if (std::min({s.world[tri[0]].y(), s.world[tri[1]].y(), s.world[tri[2]].y()}) >= hMax) continue;
        for (int k = 0; k < 3; ++k) {
            s.vertexNeeded[std::size_t(tri[k])] = 1;
            s.edgeNeeded[std::size_t(edges.triangleEdges[t][k])] = 1;
        }
    }
    s.qx.clear();
    s.qz.clear();
    for (std::size_t i = 0; i < nv; ++i)
        if (s.vertexNeeded[i]) {
            s.vertexSlot[i] = int(s.qx.size());
            s.qx.push_back(s.world[i].x());
            s.qz.push_back(s.world[i].z());
        }
    for (std::size_t e = 0; e < ne; ++e)
        if (s.edgeNeeded[e]) {
            s.edgeSlot[e] = int(s.qx.size());
            const Eigen::Vector3d m = 0.5 * (s.world[std::size_t(edges.edges[e][0])] + s.world[std::size_t(edges.edges[e][1])]);
            s.qx.push_back(m.x());
            s.qz.push_back(m.z());
        }
    const auto query = [&]() {
        s.qf.resize(s.qx.size());
        if (patch)
            patch->heights(s.qx.data(), s.qz.data(), s.qx.size(), s.qf.data());
        else
            water.heights(s.qx.data(), s.qz.data(), s.qx.size(), time, s.qf.data());
        for (std::size_t i = 0; i < s.qf.size(); ++i)
            if (!std::isfinite(s.qf[i]))
                throw std::runtime_error("curvedHydrostatics: the water surface returned a non-finite height at x=" +
                                         std::to_string(s.qx[i]) + ", z=" + std::to_string(s.qz[i]));
    };
    query();

    s.current.clear();
    for (std::size_t t = 0; t < nt; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        if (!s.vertexNeeded[std::size_t(tri[0])] || !s.edgeNeeded[std::size_t(edges.triangleEdges[t][0])]) continue;
        if (std::min({s.world[tri[0]].y(), s.world[tri[1]].y(), s.world[tri[2]].y()}) >= hMax) continue;
        Patch6 p;
        p.level = 0;
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = std::size_t(tri[k]);
            p.p[k] = s.world[v] - r;
            p.f[k] = s.qf[std::size_t(s.vertexSlot[v])] - r.y();
            const std::size_t e = std::size_t(edges.triangleEdges[t][k]);
            const std::size_t v1 = std::size_t(tri[(k + 1) % 3]);
            p.p[3 + k] = 0.5 * (s.world[v] + s.world[v1]) - r;
            p.f[3 + k] = s.qf[std::size_t(s.edgeSlot[e])] - r.y();
        }
        s.current.push_back(p);
    }

    const double top = hMax - r.y();
    for (int level = 0; !s.current.empty(); ++level) {
        s.next.clear();
        s.qx.clear();
        s.qz.clear();
        for (const Patch6& t : s.current) {
            double minD = std::numeric_limits<double>::infinity(), maxD = -minD;
            for (int k = 0; k < 6; ++k) {
                const double d = t.p[k].y() - t.f[k];
                minD = std::min(minD, d);
                maxD = std::max(maxD, d);
            }
            const double side = longestSide(t);
            if (level < kMaxLevels && side > maxSide && std::min({t.p[0].y(), t.p[1].y(), t.p[2].y()}) < top) {
                // Children (corners in t's node numbering; same orientation), and the midpoints of their sides.
                static constexpr int kChild[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
                for (const auto& c : kChild) {
                    Patch6 ch;
                    ch.level = level + 1;
                    for (int k = 0; k < 3; ++k) {
                        ch.p[k] = t.p[c[k]];
                        ch.f[k] = t.f[c[k]];
                        ch.p[3 + k] = 0.5 * (t.p[c[k]] + t.p[c[(k + 1) % 3]]);
                        const Eigen::Vector3d w = ch.p[3 + k] + r;
                        s.qx.push_back(w.x());
                        s.qz.push_back(w.z());
                    }
                    s.next.push_back(ch);
                }
                continue;
            }
            if (minD >= 0) continue;  // dry at every node
            integrate(t, I);
        }
        if (s.next.empty()) break;
        query();
        for (std::size_t i = 0; i < s.next.size(); ++i)
            for (int k = 0; k < 3; ++k) s.next[i].f[3 + k] = s.qf[3 * i + std::size_t(k)] - r.y();
        std::swap(s.current, s.next);
    }
    return I.result(fluidDensity * gravity, r, "curvedHydrostatics");
}

}  // namespace buoyancy
