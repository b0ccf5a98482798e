// Level of detail (design.md 2.5): drag clusters and the per-body water patch, against independent
// references (sums over the fine samples computed here, the sphere's silhouette area, polynomials and sines).
#include <BulletBuoyancy/integrals/DragClusters.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include "oracles/OracleMeshes.h"
#include <BulletBuoyancy/water/btWaterSurface.h>
#include "TestSamples.h"

#include <catch2/catch.hpp>
#include <atomic>
#include <cmath>

using namespace buoyancy;
using namespace buoyancy_test;

namespace {

/// f(x, z) = a + b x + c z + d x² + e x z + g z²: Catmull-Rom reproduces quadratics exactly.
class QuadraticWater : public btWaterSurface {
public:
    void heights(const double* x, const double* z, std::size_t n, double, double* out) const override {
        ++calls;
        points += n;
        for (std::size_t i = 0; i < n; ++i) out[i] = f(x[i], z[i]);
    }
    void heightBounds(double, double, double, double, double, double& lo, double& hi) const override {
        lo = -100;
        hi = 100;
    }
    static double f(double x, double z) { return 0.3 - 0.1 * x + 0.05 * z + 0.02 * x * x - 0.03 * x * z + 0.01 * z * z; }
    mutable std::atomic<int> calls{0};
    mutable std::atomic<std::size_t> points{0};
};

/// One sine wave of wavelength L and amplitude a along a diagonal.
class SineWater : public btWaterSurface {
public:
    SineWater(double a, double L) : m_a(a), m_k(2 * M_PI / L) {}
    void heights(const double* x, const double* z, std::size_t n, double, double* out) const override {
        for (std::size_t i = 0; i < n; ++i) out[i] = f(x[i], z[i]);
    }
    void heightBounds(double, double, double, double, double, double& lo, double& hi) const override {
        lo = -m_a;
        hi = m_a;
    }
    double f(double x, double z) const { return m_a * std::sin(m_k * (0.8 * x + 0.6 * z) + 0.3); }

private:
    double m_a, m_k;
};

double worstPatchError(const SineWater& water, int nodes) {
    WaterPatch patch;
    btWaterQueryCache cache;
    patch.build(water, 1.3, -0.7, 2.0, 0.0, nodes, cache);
    double worst = 0;
    for (int i = 0; i <= 40; ++i)
        for (int j = 0; j <= 40; ++j) {
            const double x = 1.3 - 2.0 + 0.1 * i, z = -0.7 - 2.0 + 0.1 * j;
            worst = std::max(worst, std::abs(patch.height(x, z) - water.f(x, z)));
        }
    return worst;
}

}  // namespace

TEST_CASE("WaterPatch: one batch of M² queries, exact on quadratic water", "[integrals][lod]") {
    QuadraticWater water;
    btWaterQueryCache cache;
    WaterPatch patch;
    patch.build(water, 0.4, -1.1, 1.7, 0.0, 8, cache);
    CHECK(water.calls == 1);
    CHECK(water.points == 64u);
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j) {
            const double x = 0.4 - 1.7 + 0.17 * i, z = -1.1 - 1.7 + 0.17 * j;
            CHECK(patch.height(x, z) == Approx(QuadraticWater::f(x, z)).margin(1e-12));
        }
    CHECK_THROWS_AS(patch.build(water, 0, 0, 1, 0, 4, cache), std::invalid_argument);
    CHECK_THROWS_AS(patch.build(water, 0, 0, 0, 0, 8, cache), std::invalid_argument);
}

TEST_CASE("WaterPatch: Taylor data exact on quadratic water, derivatives match the sine wave's", "[integrals][lod]") {
    QuadraticWater water;
    btWaterQueryCache cache;
    WaterPatch patch;
    patch.build(water, 0.4, -1.1, 1.7, 0.0, 8, cache);
    for (int i = 0; i <= 12; ++i)
        for (int j = 0; j <= 12; ++j) {
            const double x = 0.4 - 1.7 + 0.283 * i, z = -1.1 - 1.7 + 0.283 * j;
            double f, fx, fz, fxx, fxz, fzz;
            patch.taylor(x, z, f, fx, fz, fxx, fxz, fzz);
            // f = 0.3 − 0.1 x + 0.05 z + 0.02 x² − 0.03 x z + 0.01 z² (QuadraticWater)
            CHECK(f == Approx(QuadraticWater::f(x, z)).margin(1e-12));
            CHECK(fx == Approx(-0.1 + 0.04 * x - 0.03 * z).margin(1e-12));
            CHECK(fz == Approx(0.05 - 0.03 * x + 0.02 * z).margin(1e-12));
            CHECK(fxx == Approx(0.04).margin(1e-12));
            CHECK(fxz == Approx(-0.03).margin(1e-12));
            CHECK(fzz == Approx(0.02).margin(1e-12));
            CHECK(patch.height(x, z) == Approx(f).margin(1e-15));
        }
    // Curvature scale: 1.25 × (largest axial + mixed second difference) / h² = 1.25 (0.04 + 0.03) for this quadratic.
    CHECK(patch.curvatureBound() == Approx(1.25 * (0.04 + 0.03)).epsilon(1e-9));
    // A 10 m sine of amplitude 0.2 with 20 nodes over 4 m: derivatives close to the analytic ones.
    const SineWater sine(0.2, 10.0);
    patch.build(sine, 1.3, -0.7, 2.0, 0.0, 20, cache);
    const double k = 2 * M_PI / 10.0;
    double worst1 = 0, worst2 = 0;
    for (int i = 0; i <= 10; ++i)
        for (int j = 0; j <= 10; ++j) {
            const double x = 1.3 - 2.0 + 0.4 * i, z = -0.7 - 2.0 + 0.4 * j;
            double f, fx, fz, fxx, fxz, fzz;
            patch.taylor(x, z, f, fx, fz, fxx, fxz, fzz);
            const double th = k * (0.8 * x + 0.6 * z) + 0.3;
            worst1 = std::max({worst1, std::abs(fx - 0.2 * k * 0.8 * std::cos(th)), std::abs(fz - 0.2 * k * 0.6 * std::cos(th))});
            worst2 = std::max({worst2, std::abs(fxx + 0.2 * k * k * 0.64 * std::sin(th)),
                               std::abs(fxz + 0.2 * k * k * 0.48 * std::sin(th)), std::abs(fzz + 0.2 * k * k * 0.36 * std::sin(th))});
        }
    INFO("worst slope error " << worst1 << ", worst curvature error " << worst2 << " (curvature amplitude " << 0.2 * k * k << ")");
    CHECK(worst1 < 0.02 * 0.2 * k);
    CHECK(worst2 < 0.15 * 0.2 * k * k);
}

TEST_CASE("WaterPatch: error on a sine wave shrinks at least like h^2.5 (bicubic)", "[integrals][lod]") {
    // Wavelength 10 m, amplitude 0.2 m (the scaling sea's shortest wave) over a 4 m footprint.
    const SineWater water(0.2, 10.0);
    const double e8 = worstPatchError(water, 8), e12 = worstPatchError(water, 12), e20 = worstPatchError(water, 20);
    INFO("worst |error| m: 8 nodes " << e8 << ", 12 nodes " << e12 << ", 20 nodes " << e20);
    CHECK(e8 < 0.01 * 0.2 * 2);     // h = 1 m (k h = 0.63): ≤ 2 % of the wave height
    CHECK(e12 < e8 / std::pow(2.0, 2.5));  // h halves: 8 → 12 nodes
    CHECK(e20 < e12 / std::pow(2.0, 2.5)); // h halves again
}

TEST_CASE("Drag clusters conserve area vectors, areas and first moments, 0 means no merging", "[integrals][lod]") {
    const SurfaceSamples fine = subdividedSamples(oracleTorus(0.6, 0.2, 32, 16), 3);
    double A[3] = {0, 0, 0}, area = 0, m[3] = {0, 0, 0};
    for (std::size_t i = 0; i < fine.size(); ++i) {
        A[0] += fine.ax[i];
        A[1] += fine.ay[i];
        A[2] += fine.az[i];
        area += fine.area[i];
        m[0] += fine.area[i] * fine.px[i];
        m[1] += fine.area[i] * fine.py[i];
        m[2] += fine.area[i] * fine.pz[i];
    }
    for (std::size_t maxClusters : {std::size_t(0), std::size_t(16), std::size_t(64), std::size_t(256)}) {
        const DragClusters c = clusterDragSamples(fine, maxClusters);
        INFO("maxClusters " << maxClusters << " -> " << c.size() << " clusters, grid " << c.grid);
        if (maxClusters == 0) CHECK(c.size() == fine.size());
        else CHECK(c.size() <= maxClusters);
        CHECK(c.size() > 0);
        double cA[3] = {0, 0, 0}, ca = 0, cm[3] = {0, 0, 0};
        for (std::size_t k = 0; k < c.size(); ++k) {
            cA[0] += c.ax[k];
            cA[1] += c.ay[k];
            cA[2] += c.az[k];
            ca += c.area[k];
            cm[0] += c.area[k] * c.px[k];
            cm[1] += c.area[k] * c.py[k];
            cm[2] += c.area[k] * c.pz[k];
            CHECK(c.cxx[k] >= 0);
            CHECK(c.cyy[k] >= 0);
            CHECK(c.czz[k] >= 0);
        }
        CHECK(ca == Approx(area).epsilon(1e-12));
        for (int d = 0; d < 3; ++d) {
            CHECK(cA[d] == Approx(A[d]).margin(1e-12 * area));
            CHECK(cm[d] == Approx(m[d]).epsilon(1e-12).margin(1e-12 * area));
        }
    }
}

TEST_CASE("Drag clusters: one vertical square's half extent is half its side", "[integrals][lod]") {
    SurfaceSamples s;
    s.push(0, 0, 0, 0.25, 0, 0, 0.25, 0u, 0u);  // 0.5 m square facing +x
    const DragClusters c = clusterDragSamples(s, 0);
    REQUIRE(c.size() == 1);
    CHECK(std::sqrt(3.0 * c.cyy[0]) == Approx(0.25));  // vertical half extent 0.25 m
    CHECK(std::sqrt(3.0 * c.czz[0]) == Approx(0.25));
    CHECK(c.cxx[0] == Approx(0.0).margin(1e-15));       // no extent along the normal
}

TEST_CASE("Drag clusters: a sphere's front-facing projected area stays within 10 % of pi R^2", "[integrals][lod]") {
    // design.md 2.6: Σ_front A·v̂ is the silhouette area πR² for a convex body (the quadratic-drag oracle).
    const double R = 0.5;
    const SurfaceSamples fine = subdividedSamples(oracleSphere(R, 64, 32), 2);
    for (std::size_t maxClusters : {std::size_t(32), std::size_t(64), std::size_t(128)}) {
        const DragClusters c = clusterDragSamples(fine, maxClusters);
        for (const Eigen::Vector3d v : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.3, -0.8, 0.52).normalized(),
                                        Eigen::Vector3d(-0.6, 0.1, -0.79).normalized()}) {
            double front = 0;
            for (std::size_t k = 0; k < c.size(); ++k) front += std::max(0.0, c.ax[k] * v.x() + c.ay[k] * v.y() + c.az[k] * v.z());
            INFO(maxClusters << " clusters (" << c.size() << "), v = " << v.transpose() << ": front area " << front
                             << " vs " << M_PI * R * R);
            CHECK(front == Approx(M_PI * R * R).epsilon(0.10));
        }
    }
}

TEST_CASE("clippedHydrostatics with a water patch: exact on quadratic-free (linear) water, close on a wave",
          "[integrals][lod]") {
    const TriangleMesh mesh = toTriangleMesh(oracleSphere(0.5, 32, 16));
    const Eigen::Isometry3d pose = Eigen::Translation3d(0.3, 0.05, -0.2) * Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 0, 1).normalized());
    const SineWater water(0.2, 10.0);
    btWaterQueryCache cache;
    WaterPatch patch;
    patch.build(water, pose.translation().x(), pose.translation().z(), 0.5, 0.0, 8, cache);
    const Eigen::Vector3d ref = pose.translation();
    const HydrostaticsResult exact = clippedHydrostatics(mesh, pose, water, 0.0, 1000, 9.81, ref);
    const HydrostaticsResult lod = clippedHydrostatics(mesh, pose, water, 0.0, 1000, 9.81, ref, &patch);
    const double V = 4.0 / 3.0 * M_PI * 0.125;
    INFO("V exact " << exact.submerged_volume << " patch " << lod.submerged_volume);
    CHECK(std::abs(lod.submerged_volume - exact.submerged_volume) / V < 1e-4);
    CHECK((lod.centre_of_buoyancy - exact.centre_of_buoyancy).norm() < 1e-4);
}

#include <BulletBuoyancy/bullet/btBuoyancySettings.h>

#include <stdexcept>
#include <string>

TEST_CASE("Level-of-detail settings: bad values are refused with the field's name", "[integrals][lod]") {
    auto message = [](const btBuoyancySettings& s) {
        try {
            s.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    btBuoyancySettings s;
    CHECK(message(s).empty());
    s.dragClusters = -1;
    CHECK(message(s).find("dragClusters") != std::string::npos);
    s = btBuoyancySettings();
    s.waterPatchNodes = 3;
    CHECK(message(s).find("waterPatchNodes") != std::string::npos);
    s.waterPatchNodes = 0;  // exact queries: valid
    CHECK(message(s).empty());
    s.waterVelocityProbes = -5;
    CHECK(message(s).find("waterVelocityProbes") != std::string::npos);
    s = btBuoyancySettings();
    s.errorBudget = -0.1;
    CHECK(message(s).find("errorBudget") != std::string::npos);
    s.errorBudget = std::nan("");
    CHECK(message(s).find("errorBudget") != std::string::npos);
    s = btBuoyancySettings();
    s.waterPatchNodesPerWavelength = -1;
    CHECK(message(s).find("waterPatchNodesPerWavelength") != std::string::npos);
    s.waterPatchNodesPerWavelength = std::nan("");
    CHECK(message(s).find("waterPatchNodesPerWavelength") != std::string::npos);
    s.waterPatchNodesPerWavelength = 0;  // the fixed count: valid
    CHECK(message(s).empty());
}

TEST_CASE("Wave patch size: spacing at most the shortest wavelength / nodes per wavelength, 8..64 nodes",
          "[integrals][lod]") {
    btBuoyancySettings s;  // 8 nodes at least, 16 per shortest wavelength
    // spacing 2r / (M − 4) ≤ λ / 16  ⇔  M ≥ 32 r / λ + 4
    CHECK(btBuoyancyWaterPatchNodes(s, 2.157, 10.0) == 11);  // 32·2.157/10 = 6.9 → 7 cells
    CHECK(btBuoyancyWaterPatchNodes(s, 0.5, 10.0) == 8);     // 1.6 → 2 cells: the minimum 8 rules
    CHECK(btBuoyancyWaterPatchNodes(s, 2.5, 10.0) == 12);    // exactly 8 cells
    CHECK(btBuoyancyWaterPatchNodes(s, 100.0, 10.0) == 64);  // capped
    CHECK(btBuoyancyWaterPatchNodes(s, 2.157, 0.0) == 8);    // wavelength unknown: the fixed count
    for (double r : {0.3, 1.0, 2.157, 5.0, 9.0}) {
        const int m = btBuoyancyWaterPatchNodes(s, r, 10.0);
        if (m < 64) CHECK(2.0 * r / (m - 4) <= 10.0 / 16.0 + 1e-12);
    }
    s.waterPatchNodesPerWavelength = 0;
    CHECK(btBuoyancyWaterPatchNodes(s, 100.0, 10.0) == 8);
    s.waterPatchNodes = 0;  // exact queries
    CHECK(btBuoyancyWaterPatchNodes(s, 2.157, 10.0) == 0);
}

#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

TEST_CASE("Wave patch sized per wavelength: a 4 m body in 10-60 m waves within 1e-4 of V of exact queries",
          "[integrals][lod]") {
    // The scaling sea; a 4 x 0.8 x 1.4 m box (the demo boat's extents) heeled and trimmed at several times.
    const btGerstnerWaterSurface sea({{1.0, 60.0, 1.0, 0.0, 0.5, 0.0},
                                      {0.6, 35.0, 0.8, 0.6, 0.5, 1.3},
                                      {0.35, 20.0, -0.3, 1.0, 0.5, 2.1},
                                      {0.2, 10.0, 0.6, -0.8, 0.5, 0.4}});
    const TriangleMesh mesh = toTriangleMesh(oracleBox(4.0, 0.8, 1.4));
    const double V = 4.0 * 0.8 * 1.4;
    const double r = 0.5 * std::sqrt(16.0 + 0.64 + 1.96);
    const int adaptive = btBuoyancyWaterPatchNodes(btBuoyancySettings(), r, sea.shortestWavelength());
    CHECK(sea.shortestWavelength() == 10.0);
    CHECK(adaptive == 11);
    double worst[2] = {0, 0};  // fixed 8 nodes, adaptive
    for (double t : {0.5, 2.3, 4.1, 7.7})
        for (double heel : {0.0, 0.3}) {
            const Eigen::Vector3d at(5.0 * t, 0.0, -3.0 * t);
            const double surface = sea.height(at.x(), at.z(), t);
            const Eigen::Isometry3d pose = Eigen::Translation3d(at.x(), surface - 0.1, at.z()) *
                                           Eigen::AngleAxisd(heel, Eigen::Vector3d(1, 0, 0.4).normalized());
            const HydrostaticsResult exact = clippedHydrostatics(mesh, pose, sea, t, 1000, 9.81, at);
            for (int k = 0; k < 2; ++k) {
                btWaterQueryCache cache;
                WaterPatch patch;
                patch.build(sea, at.x(), at.z(), r, t, k == 0 ? 8 : adaptive, cache);
                const HydrostaticsResult lod = clippedHydrostatics(mesh, pose, sea, t, 1000, 9.81, at, &patch);
                worst[k] = std::max(worst[k], std::abs(lod.submerged_volume - exact.submerged_volume) / V);
            }
        }
    std::printf("4 m box in the scaling sea, worst volume error of V against exact queries: 8x8 patch %.2e, %dx%d %.2e\n",
                worst[0], adaptive, adaptive, worst[1]);
    CHECK(worst[1] < 1e-4);
    CHECK(worst[1] < worst[0]);
}
