/// @file VertexHydrostatics.cpp
/// Exact-mesh hydrostatics through the per-vertex shares (declared in Hydrostatics.h; formulas in VertexShares.h):
/// the same water model and the same result as clippedHydrostatics to rounding (the water over each triangle is the
/// plane through its corners' heights; flat water is exact), at a fraction of its cost. Four passes:
///  1. each vertex: D_v = y_v − f(x_v, z_v) (body → world by the rows of R; on waves the height is interpolated from
///     the patch, several vertices per instruction (VertexPassKernels.h), and only counted for the vertices that can
///     be under water: y_v ≤ the highest value the patch can take);
///  2. each vertex with D_v ≤ 0: the shares D_v B_v, D_v T_v, D_v M_v, D_v² B_v, B_v, a_v summed (several vertices
///     per instruction: SSE2, AVX2 or AVX-512 chosen at run time, VertexPassKernels.h);
///  3. each triangle: all corners under water → its ∫ D² n_y cross term (A_t (Σ D_i)²); corners on both sides (or an
///     edge exactly on the water) → listed (several triangles per instruction, VertexPassKernels.h);
///  4. the straddling triangles listed in pass 3: the shares their wet corners added are taken back and their exact
///     wet parts added in closed form (the clip of BodyFrameSums.h without cutting polygons; several triangles per
///     instruction, VertexPassKernels.h).
/// Triangles entirely above the water cost one test each.

#include <BulletBuoyancy/integrals/BodyFrameSums.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/VertexPassKernels.h>
#include <BulletBuoyancy/integrals/VertexShares.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace buoyancy {
namespace {

/// Thread-local scratch (grows, never shrinks): D per vertex, and the world (x, z) and index of the vertices whose
/// water height is needed.
struct VertexScratch {
    std::vector<double> D, x, z, f;
    std::vector<std::int32_t> index;
    std::vector<std::int32_t> straddling;  ///< triangles with corners on both sides of the water
};

/// D of a vertex whose height was not interpolated (above every value the patch can take: dry), computed when a
/// straddling triangle needs it for the crossing point.
constexpr double kNotComputed = std::numeric_limits<double>::infinity();

}  // namespace

HydrostaticsResult vertexHydrostatics(const VertexShares& shares, const Eigen::Isometry3d& pose,
                                      const btWaterSurface& water, double time, double fluidDensity, double gravity,
                                      const Eigen::Vector3d& torqueReference, const WaterPatch* patch) {
    checkBodyFrameArguments("vertexHydrostatics", fluidDensity, gravity, pose, torqueReference);
    const std::size_t nv = shares.vertexCount(), nt = shares.triangleCount();
    if (nv == 0 || nt == 0) return HydrostaticsResult{};
    double flatH = 0;
    const bool flat = water.isFlat(time, flatH);
    if (flat && !std::isfinite(flatH)) throw std::runtime_error("vertexHydrostatics: the flat water height is not finite");

    thread_local VertexScratch sc;
    if (sc.D.size() < nv) {
        sc.D.resize(nv);
        sc.x.resize(nv);
        sc.z.resize(nv);
        sc.f.resize(nv);
        sc.index.resize(nv);
    }
    if (sc.straddling.size() < nt) sc.straddling.resize(nt);
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d t = pose.translation();
    const Eigen::Vector3d& r = torqueReference;
    const Eigen::Vector3d u = R.row(1).transpose();  // world up in the body frame
    const Eigen::Vector3d X = R.row(0).transpose(), Z = R.row(2).transpose();  // world x and z, body frame
    const Eigen::Vector3d qr = R.transpose() * (r - t);
    const double r00 = R(0, 0), r01 = R(0, 1), r02 = R(0, 2), r10 = R(1, 0), r11 = R(1, 1), r12 = R(1, 2);
    const double r20 = R(2, 0), r21 = R(2, 1), r22 = R(2, 2);
    const double* qx = shares.qx.data();
    const double* qy = shares.qy.data();
    const double* qz = shares.qz.data();
    double* D = sc.D.data();

    // Pass 1: D per vertex.
    // Every value of the patch's interpolant lies within [minNode − ½ spread, maxNode + ½ spread] (the Catmull-Rom
    // overshoot, TreeHydrostatics.cpp): a vertex above that is dry without its height. Without a patch (exact queries)
    // every vertex is queried, as clippedHydrostatics does.
    const double waterHigh = flat ? flatH
                             : patch ? patch->maxNode() + 0.5 * (patch->maxNode() - patch->minNode())
                                     : std::numeric_limits<double>::infinity();
    if (patch && !flat) {
        // On a patch: the transform and the interpolation fused, several vertices per instruction
        // (VertexPassKernels.h; bit for bit patch->height at each vertex up to the fused multiply-adds).
        const double Rm[9] = {r00, r01, r02, r10, r11, r12, r20, r21, r22};
        const double tv[3] = {t.x(), t.y(), t.z()};
        if (!vertexDepthsOnPatch(shares, Rm, tv, patch->cellGrid(), waterHigh, D))
            throw std::runtime_error("vertexHydrostatics: the water patch interpolated a non-finite height");
    } else {
        std::size_t nq = 0;
        for (std::size_t v = 0; v < nv; ++v) {
            const double y = r10 * qx[v] + r11 * qy[v] + r12 * qz[v] + t.y();
            if (flat) {
                D[v] = y - flatH;
            } else if (y > waterHigh) {
                D[v] = kNotComputed;
            } else {
                D[v] = y;
                sc.x[nq] = r00 * qx[v] + r01 * qy[v] + r02 * qz[v] + t.x();
                sc.z[nq] = r20 * qx[v] + r21 * qy[v] + r22 * qz[v] + t.z();
                sc.index[nq++] = std::int32_t(v);
            }
        }
        if (nq > 0) {
            water.heights(sc.x.data(), sc.z.data(), nq, time, sc.f.data());  // exact queries, one batch
            for (std::size_t k = 0; k < nq; ++k) {
                if (!std::isfinite(sc.f[k]))
                    throw std::runtime_error("vertexHydrostatics: the water surface returned a non-finite height at x=" +
                                             std::to_string(sc.x[k]) + ", z=" + std::to_string(sc.z[k]));
                D[sc.index[k]] -= sc.f[k];
            }
        }
    }

    // Pass 2: the shares of the vertices under water (D ≤ 0), body frame, moments about the body origin.
    double sums[kShareSums] = {};
    sumWetShares(shares, D, nv, sums);  // VertexPassKernels.h
    const double Fx = sums[kFx], Fy = sums[kFy], Fz = sums[kFz], Tx = sums[kTx], Ty = sums[kTy], Tz = sums[kTz];
    const double Gx = sums[kGx], Gy = sums[kGy], Gz = sums[kGz], Bx = sums[kBx], By = sums[kBy], Bz = sums[kBz];
    const double area = sums[kArea];
    const double* M = sums + kM;

    // Pass 3: triangles. Entirely wet: the (Σ D)² part of ∫ D² n_y. Straddling: listed for pass 4. Kept apart so that
    // this loop, which sees every triangle, carries few values.
    double S[3] = {0, 0, 0};  // Σ_wet A_t (Σ D_i)²
    const std::int32_t* c0 = shares.corner[0].data();
    const std::int32_t* c1 = shares.corner[1].data();
    const std::int32_t* c2 = shares.corner[2].data();
    const std::int32_t* straddling = sc.straddling.data();
    // Wet with an edge exactly on the water (two corners at D = 0, the third below): listed like the straddling ones,
    // so that the edge reaches the waterplane moments (BodyFrameSums.h); the sums are the same. Several triangles per
    // instruction (VertexPassKernels.h).
    const std::size_t ns = sumWetTriangles(shares, D, S, sc.straddling.data());
    const double Sx = S[0], Sy = S[1], Sz = S[2];
    // Pass 4: the listed triangles, in closed form. The shares pass 2 added for a listed triangle's wet corners are
    // taken back, and its wet part is added. That part is cut off by one waterline segment E₊E₋, where E₊ and E₋ are the
    // points with D = 0 on the two edges from the triangle's lone corner L (the one corner on its side of the water: the
    // only dry one, or the only wet one; with no dry corner, the one below the two on the water), E₊ on L → L+1 and E₋
    // on L → L−1 (winding order). The lone triangle (L, E₊, E₋) lies in the triangle's plane (area vector t₊ t₋ A_t)
    // with D = 0 at E₊ and E₋, so addBodyTriangle's edge-midpoint sums reduce to (body frame, about the origin)
    //   ∫ D n = D_L A/3,  ∫ D q × n = m × A,  ∫ q D n_y = (A·u) m,  ∫ D² n_y = (A·u) D_L²/6,  m = D_L (2 q_L + E₊ + E₋)/12;
    // the wet part is the lone triangle when L is wet, the whole triangle minus it when L is dry (the same clip as
    // addClippedBodyTriangle, without cutting a polygon; the waterline segment is the wet part's edge on the water).
    // Several triangles per instruction (VertexPassKernels.h), after the missing depths of their dry corners.
    for (std::size_t k = 0; k < ns; ++k) {
        const std::size_t tr = std::size_t(straddling[k]);
        for (const std::int32_t v : {c0[tr], c1[tr], c2[tr]}) {
            if (D[v] != kNotComputed) continue;  // dry corner without its height: needed for the crossing point
            const double x = r00 * qx[v] + r01 * qy[v] + r02 * qz[v] + t.x();
            const double z = r20 * qx[v] + r21 * qy[v] + r22 * qz[v] + t.z();
            const double y = r10 * qx[v] + r11 * qy[v] + r12 * qz[v] + t.y();
            D[v] = y - patch->height(x, z);  // (> 0: above every value of the interpolant)
        }
    }
    StraddlingSums p;
    const double uv[3] = {u.x(), u.y(), u.z()}, Xv[3] = {X.x(), X.y(), X.z()}, Zv[3] = {Z.x(), Z.y(), Z.z()};
    sumStraddlingTriangles(shares, D, straddling, ns, uv, Xv, Zv, X.dot(qr), Z.dot(qr), p);
    const Eigen::Vector3d pF(p.F[0], p.F[1], p.F[2]), pT(p.T[0], p.T[1], p.T[2]), pQ(p.Q[0], p.Q[1], p.Q[2]);
    const Eigen::Vector3d pB(p.B[0], p.B[1], p.B[2]);
    const double pD2 = p.D2, pArea = p.area;
    const WaterlineSums& waterline = p.waterline;

    // Assembly: the sums, moved to the reference point q_r.
    NodeSums acc;
    acc.waterline = waterline;
    const Eigen::Vector3d F = Eigen::Vector3d(Fx, Fy, Fz) + pF / 3.0;
    const double V = u.dot(F);
    Eigen::Matrix3d Mv;
    Mv << M[0], M[1], M[2], M[3], M[4], M[5], M[6], M[7], M[8];
    acc.F = F;
    acc.V = V;
    acc.T = Eigen::Vector3d(Tx, Ty, Tz) + pT / 12.0 - qr.cross(F);                     // ∫ D (q − q_r) × n
    acc.Q = Mv * u + pQ / 12.0 - qr * V;                                               // ∫ (q − q_r) D n_y
    acc.D2 = u.dot(Eigen::Vector3d(Gx, Gy, Gz)) / 4.0 + u.dot(Eigen::Vector3d(Sx, Sy, Sz)) / 12.0 + pD2 / 12.0;  // ∫ D² n_y
    acc.Ay = u.dot(Eigen::Vector3d(Bx, By, Bz) + pB / 3.0);
    acc.area = area + pArea / 3.0;
    return toWetIntegrals(acc, R).result(fluidDensity * gravity, r, "vertexHydrostatics");
}

}  // namespace buoyancy
