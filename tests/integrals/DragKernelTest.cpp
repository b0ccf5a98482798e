// The vector drag sum (plugin/BulletBuoyancy/integrals/DragKernel) against the scalar formulas it batches (SampleFormulas.h:
// bb_drag_wet_ramp + bb_drag_cluster_accumulate, cluster by cluster), at every SIMD width this CPU runs, with the
// cases the masks must get right: dry, partly wet, NaN water height, no vertical extent, zero area, no spread, every
// coefficient on or off, counts that leave a tail. And one physical check: a sphere's pressure drag is ½ρC_d πR²v².
#include <BulletBuoyancy/integrals/DragClusters.h>
#include <BulletBuoyancy/integrals/DragKernel.h>
#include <BulletBuoyancy/geometry/SampleFormulas.h>
#include "oracles/FloatingPointTraps.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

using namespace buoyancy;
using buoyancy_test::ScopedFpTrapsOff;

namespace {

/// Structure-of-arrays storage behind a DragClusterBatch.
struct Clusters {
    std::vector<double> x, y, z, ax, ay, az, area, cxx, cxy, cxz, cyy, cyz, czz, half, h, ux, uy, uz;
    void resize(std::size_t n) {
        for (auto* v : {&x, &y, &z, &ax, &ay, &az, &area, &cxx, &cxy, &cxz, &cyy, &cyz, &czz, &half, &h, &ux, &uy, &uz})
            v->assign(n, 0.0);
    }
    DragClusterBatch batch() const {
        DragClusterBatch b;
        b.n = x.size();
        b.x = x.data();
        b.y = y.data();
        b.z = z.data();
        b.ax = ax.data();
        b.ay = ay.data();
        b.az = az.data();
        b.area = area.data();
        b.cxx = cxx.data();
        b.cxy = cxy.data();
        b.cxz = cxz.data();
        b.cyy = cyy.data();
        b.cyz = cyz.data();
        b.czz = czz.data();
        b.halfHeight = half.data();
        b.waterHeight = h.data();
        b.ux = ux.data();
        b.uy = uy.data();
        b.uz = uz.data();
        return b;
    }
    /// Where poseDragClusters writes: the centres, area vectors and half heights of these arrays.
    DragClusterPose pose() {
        DragClusterPose o;
        o.x = x.data();
        o.y = y.data();
        o.z = z.data();
        o.ax = ax.data();
        o.ay = ay.data();
        o.az = az.data();
        o.halfHeight = half.data();
        return o;
    }
};

/// The scalar reference: the formulas one cluster at a time, as the action summed them before the batch.
void scalarDrag(const Clusters& c, const DragMotion& m, double part[BB_DRAG_TERMS]) {
    namespace fm = formulas;
    for (std::size_t i = 0; i < c.x.size(); ++i) {
        const double wet = fm::bb_drag_wet_ramp(c.half[i], c.h[i] - c.y[i]);
        if (!(wet > 0)) continue;
        const double r[3] = {c.x[i] - m.com[0], c.y[i] - m.com[1], c.z[i] - m.com[2]};
        const double u[3] = {c.ux[i], c.uy[i], c.uz[i]};
        const double C[6] = {c.cxx[i], c.cxy[i], c.cxz[i], c.cyy[i], c.cyz[i], c.czz[i]};
        fm::bb_drag_cluster_accumulate(m.R, C, r, m.v, m.w, u, c.ax[i], c.ay[i], c.az[i], c.area[i], wet, m.kd, m.kf, m.kl,
                                       part);
    }
}

Clusters randomClusters(std::mt19937& rng, std::size_t n) {
    std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
    Clusters c;
    c.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        c.x[i] = 2 * u(rng);
        c.y[i] = 0.5 * u(rng);
        c.z[i] = 2 * u(rng);
        c.ax[i] = 0.1 * u(rng);
        c.ay[i] = 0.1 * u(rng);
        c.az[i] = 0.1 * u(rng);
        c.area[i] = std::sqrt(c.ax[i] * c.ax[i] + c.ay[i] * c.ay[i] + c.az[i] * c.az[i]) * (1 + pos(rng));
        // A positive semi-definite spread: L Lᵀ with a random lower triangle.
        const double l00 = 0.2 * u(rng), l10 = 0.2 * u(rng), l11 = 0.2 * u(rng), l20 = 0.2 * u(rng),
                     l21 = 0.2 * u(rng), l22 = 0.2 * u(rng);
        c.cxx[i] = l00 * l00;
        c.cxy[i] = l00 * l10;
        c.cxz[i] = l00 * l20;
        c.cyy[i] = l10 * l10 + l11 * l11;
        c.cyz[i] = l10 * l20 + l11 * l21;
        c.czz[i] = l20 * l20 + l21 * l21 + l22 * l22;
        c.half[i] = 0.3 * pos(rng);
        c.h[i] = 0.4 * u(rng);
        c.ux[i] = 0.5 * u(rng);
        c.uy[i] = 0.2 * u(rng);
        c.uz[i] = 0.5 * u(rng);
        switch (i % 11) {  // the special cases, spread over the lanes
            case 1: c.half[i] = 0; break;                                          // no vertical extent
            case 3: c.ax[i] = c.ay[i] = c.az[i] = 0; break;                        // zero area vector
            case 5: c.cxx[i] = c.cxy[i] = c.cxz[i] = c.cyy[i] = c.cyz[i] = c.czz[i] = 0; break;  // no spread
            case 7: c.h[i] = std::nan(""); break;                                  // NaN water: dry
            case 9: c.h[i] = c.y[i] - c.half[i] - 0.1; break;                       // dry
            default: break;
        }
    }
    return c;
}

DragMotion randomMotion(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    DragMotion m;
    const double a = u(rng), b = u(rng), g = u(rng);
    // A rotation: Rz(g) Ry(b) Rx(a), row-major.
    const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b), cg = std::cos(g), sg = std::sin(g);
    const double R[9] = {cg * cb, cg * sb * sa - sg * ca, cg * sb * ca + sg * sa,
                         sg * cb, sg * sb * sa + cg * ca, sg * sb * ca - cg * sa,
                         -sb,     cb * sa,                cb * ca};
    for (int k = 0; k < 9; ++k) m.R[k] = R[k];
    for (int k = 0; k < 3; ++k) {
        m.com[k] = 0.3 * u(rng);
        m.v[k] = u(rng);
        m.w[k] = u(rng);
    }
    return m;
}

}  // namespace

TEST_CASE("drag kernel: every width the CPU runs matches the scalar formulas", "[integrals][drag]") {
    const ScopedFpTrapsOff nanOnPurpose;  // NaN water heights on purpose: comparing them raises FE_INVALID (FPE run)
    std::mt19937 rng(31);
    std::vector<int> widths = {2};
    if (dragKernelLanes() >= 4) widths.push_back(4);
    if (dragKernelLanes() >= 8) widths.push_back(8);
    INFO("CPU lanes " << dragKernelLanes());
    int compared = 0;
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(16), std::size_t(61), std::size_t(213)}) {
        const Clusters c = randomClusters(rng, n);
        for (int coefficients = 0; coefficients < 8; ++coefficients) {
            DragMotion m = randomMotion(rng);
            m.kd = (coefficients & 1) ? 500.0 : 0.0;
            m.kf = (coefficients & 2) ? 3.0 : 0.0;
            m.kl = (coefficients & 4) ? 300.0 : 0.0;
            double ref[BB_DRAG_TERMS] = {};
            scalarDrag(c, m, ref);
            // per group: force, torque, velocity, area, linear damping power
            const auto group = [](int k) { return k < 9 ? k / 3 : k - 6; };
            double scale[5] = {0, 0, 0, 0, 0};
            for (int k = 0; k < BB_DRAG_TERMS; ++k) scale[group(k)] += std::abs(ref[k]);
            for (int width : widths) {
                double part[BB_DRAG_TERMS] = {};
                accumulateClusterDrag(c.batch(), m, part, width);
                for (int k = 0; k < BB_DRAG_TERMS; ++k) {
                    INFO("n " << n << " coefficients " << coefficients << " width " << width << " term " << k << ": "
                              << part[k] << " scalar " << ref[k]);
                    REQUIRE(std::isfinite(part[k]));
                    CHECK(std::abs(part[k] - ref[k]) <= 1e-12 * (scale[group(k)] + 1e-300));
                }
                ++compared;
            }
        }
    }
    CHECK(compared >= 48);
}

TEST_CASE("drag kernel: a fully wet sphere of flat samples gets ½ ρ C_d π R² v²", "[integrals][drag]") {
    // Fine samples of a sphere (one per latitude-longitude cell, exact spherical-zone areas) as clusters without
    // spread: the front-facing projected areas sum to the silhouette πR² (design.md 2.6's oracle).
    const double R = 0.5, v = 1.3, rho = 1000, Cd = 0.8;
    const int nu = 96, nv = 48;
    Clusters c;
    c.resize(std::size_t(nu * nv));
    std::size_t i = 0;
    for (int b = 0; b < nv; ++b)
        for (int a = 0; a < nu; ++a, ++i) {
            const double t0 = M_PI * b / nv, t1 = M_PI * (b + 1) / nv, p = 2 * M_PI * (a + 0.5) / nu;
            const double area = 2 * M_PI * R * R * (std::cos(t0) - std::cos(t1)) / nu;
            const double t = 0.5 * (t0 + t1);
            const double n[3] = {std::sin(t) * std::cos(p), std::cos(t), std::sin(t) * std::sin(p)};
            c.x[i] = R * n[0];
            c.y[i] = R * n[1] - 10;  // deep under water at y = 0
            c.z[i] = R * n[2];
            c.ax[i] = area * n[0];
            c.ay[i] = area * n[1];
            c.az[i] = area * n[2];
            c.area[i] = area;
            c.half[i] = 0.01;
        }
    DragMotion m;
    m.com[1] = -10;
    m.v[0] = v;
    m.kd = 0.5 * rho * Cd;
    double part[BB_DRAG_TERMS] = {};
    accumulateClusterDrag(c.batch(), m, part);
    const double expected = 0.5 * rho * Cd * M_PI * R * R * v * v;
    // The midpoint normals' projections sum to the silhouette up to the discretisation (O(1/nv²)).
    CHECK(part[0] == Approx(-expected).epsilon(2e-3));
    CHECK(std::abs(part[1]) < 1e-9 * expected);
    CHECK(std::abs(part[2]) < 1e-9 * expected);
    CHECK(part[9] == Approx(4 * M_PI * R * R).epsilon(1e-12));  // every sample wet: the whole area
    CHECK(part[10] == 0);  // no linear damping: no linear power

    SECTION("linear damping alone: force and power over the sphere's ∮ n_x² dA = 4πR²/3") {
        // F_x = −ρ b v ∮ n_x² dA and its power F_x v, from every sample (front and back).
        DragMotion l = m;
        l.kd = 0;
        const double b = 0.3;
        l.kl = rho * b;
        double lin[BB_DRAG_TERMS] = {};
        accumulateClusterDrag(c.batch(), l, lin);
        const double force = rho * b * v * 4 * M_PI * R * R / 3;
        CHECK(lin[0] == Approx(-force).epsilon(2e-3));
        CHECK(lin[10] == Approx(-force * v).epsilon(2e-3));
    }
}

/// n body-frame clusters: centres in [−1, 1]³, area vectors with components in ±areaScale and areas 1–2 × their
/// length, covariances G Gᵀ of random G with entries in ±spread (positive semidefinite), none (a flat point) where
/// flat(i).
template <class Flat>
DragClusters randomClusters(std::size_t n, std::mt19937& rng, double areaScale, double spread, const Flat& flat) {
    std::uniform_real_distribution<double> u(-1, 1);
    DragClusters c;
    for (auto* v : {&c.px, &c.py, &c.pz, &c.ax, &c.ay, &c.az, &c.area, &c.cxx, &c.cxy, &c.cxz, &c.cyy, &c.cyz, &c.czz})
        v->resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        c.px[i] = u(rng);
        c.py[i] = u(rng);
        c.pz[i] = u(rng);
        c.ax[i] = areaScale * u(rng);
        c.ay[i] = areaScale * u(rng);
        c.az[i] = areaScale * u(rng);
        c.area[i] = std::sqrt(c.ax[i] * c.ax[i] + c.ay[i] * c.ay[i] + c.az[i] * c.az[i]) * (1 + 0.5 * (u(rng) + 1));
        Eigen::Matrix3d G;
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) G(r, k) = spread * u(rng);
        if (flat(i)) G.setZero();
        const Eigen::Matrix3d C = G * G.transpose();
        c.cxx[i] = C(0, 0);
        c.cxy[i] = C(0, 1);
        c.cxz[i] = C(0, 2);
        c.cyy[i] = C(1, 1);
        c.cyz[i] = C(1, 2);
        c.czz[i] = C(2, 2);
    }
    return c;
}

TEST_CASE("drag kernel: posing the clusters at every width matches the rotation written out", "[integrals][drag]") {
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<int> widths = {2};
    if (dragKernelLanes() >= 4) widths.push_back(4);
    if (dragKernelLanes() >= 8) widths.push_back(8);
    int compared = 0;
    for (std::size_t n : {std::size_t(1), std::size_t(13), std::size_t(64)}) {
        // The last cluster has no spread (a flat point).
        const DragClusters c = randomClusters(n, rng, 1.0, 0.3, [n](std::size_t i) { return i + 1 == n; });
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(2 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
        const Eigen::Vector3d t(5 * u(rng), 5 * u(rng), 5 * u(rng));
        const double Rm[9] = {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)};
        const double tv[3] = {t.x(), t.y(), t.z()};
        for (int width : widths) {
            Clusters w;
            w.resize(n);
            poseDragClusters(c, Rm, tv, w.pose(), width);
            const std::vector<double>&x = w.x, &y = w.y, &z = w.z, &ax = w.ax, &ay = w.ay, &az = w.az, &half = w.half;
            for (std::size_t i = 0; i < n; ++i) {
                INFO("clusters " << n << " width " << width << " cluster " << i);
                const Eigen::Vector3d p = R * Eigen::Vector3d(c.px[i], c.py[i], c.pz[i]) + t;
                const Eigen::Vector3d a = R * Eigen::Vector3d(c.ax[i], c.ay[i], c.az[i]);
                Eigen::Matrix3d C;
                C << c.cxx[i], c.cxy[i], c.cxz[i], c.cxy[i], c.cyy[i], c.cyz[i], c.cxz[i], c.cyz[i], c.czz[i];
                // The world covariance R C Rᵀ: its yy entry is the vertical variance.
                const double varY = (R * C * R.transpose())(1, 1);
                CHECK((Eigen::Vector3d(x[i], y[i], z[i]) - p).norm() <= 1e-13 * (1 + p.norm()));
                CHECK((Eigen::Vector3d(ax[i], ay[i], az[i]) - a).norm() <= 1e-13 * (1 + a.norm()));
                CHECK(std::abs(half[i] - std::sqrt(3.0 * std::max(varY, 0.0))) <= 1e-12);
            }
            ++compared;
        }
    }
    CHECK(compared >= 3);
}
