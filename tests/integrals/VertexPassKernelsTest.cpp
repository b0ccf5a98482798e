// Passes 1 and 3 of the per-vertex hydrostatics (plugin/integrals/VertexPassKernels): every SIMD width this CPU runs
// against plain loops written here. Pass 1: each vertex moved by the pose and its height asked of WaterPatch::height one
// by one (vertices outside the patch's footprint included: clamped cells). Pass 3: the triangle classes from depths
// that are negative, zero (two and three corners on the water), positive and +∞, triangle counts that leave a tail.
#include "integrals/VertexPassKernels.h"
#include "integrals/VertexShares.h"
#include "integrals/VertexSharesKernel.h"
#include "integrals/WaterPatch.h"
#include "oracles/OracleMeshes.h"
#include "water/btGerstnerWaterSurface.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

using namespace buoyancy;
using namespace buoyancy_test;

namespace {
/// The widths to compare: 2 always, 4 and 8 when the CPU runs them.
std::vector<int> cpuWidths() {
    std::vector<int> widths = {2};
    if (vertexKernelLanes() >= 4) widths.push_back(4);
    if (vertexKernelLanes() >= 8) widths.push_back(8);
    return widths;
}
}  // namespace

TEST_CASE("vertex pass kernels: depths on a water patch at every width match the patch's own heights",
          "[integrals][vertex]") {
    const btGerstnerWaterSurface sea({{0.6, 20.0, 1.0, 0.3, 0.6, 0.0}, {0.25, 7.0, 0.2, 1.0, 0.5, 1.3}});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int compared = 0, dry = 0, outside = 0;
    for (const OracleMesh& m : {oracleSphere(0.8, 13, 7), oracleTorus(1.0, 0.3, 17, 9), oracleBox(2, 0.5, 1)}) {
        const VertexShares s = buildVertexShares(toTriangleMesh(m));
        const std::size_t n = s.vertexCount();
        for (int trial = 0; trial < 8; ++trial) {
            const Eigen::Matrix3d R =
                Eigen::AngleAxisd(3 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
            const Eigen::Vector3d t(10 * u(rng), 0.5 * u(rng), 10 * u(rng));
            const double time = 0.7 * trial;
            WaterPatch patch;
            btWaterQueryCache cache;
            // Trials 0–1: a footprint smaller than the body (its far vertices fall outside, in the clamped cells).
            const double r = trial < 2 ? 0.4 : 1.3;
            patch.build(sea, t.x(), t.z(), r, time, 9, cache);
            const double high = trial == 3 ? t.y() : patch.maxNode() + 0.5 * (patch.maxNode() - patch.minNode());
            const double Rm[9] = {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)};
            const double tv[3] = {t.x(), t.y(), t.z()};
            std::vector<double> expected(n);
            for (std::size_t v = 0; v < n; ++v) {
                const Eigen::Vector3d w = R * Eigen::Vector3d(s.qx[v], s.qy[v], s.qz[v]) + t;
                if (std::abs(w.x() - t.x()) > r || std::abs(w.z() - t.z()) > r) ++outside;
                expected[v] = w.y() > high ? std::numeric_limits<double>::infinity() : w.y() - patch.height(w.x(), w.z());
                if (w.y() > high) ++dry;
            }
            for (int width : cpuWidths()) {
                std::vector<double> D(n, std::nan(""));
                REQUIRE(vertexDepthsOnPatch(s, Rm, tv, patch.cellGrid(), high, D.data(), width));
                for (std::size_t v = 0; v < n; ++v) {
                    INFO("vertices " << n << " trial " << trial << " width " << width << " vertex " << v);
                    if (std::isinf(expected[v]))
                        CHECK(D[v] == expected[v]);
                    else
                        CHECK(std::abs(D[v] - expected[v]) <= 1e-12 * (1 + std::abs(expected[v])));
                }
                ++compared;
            }
        }
    }
    CHECK(compared >= 24);
    CHECK(dry > 0);      // some vertices above the given height (+∞)
    CHECK(outside > 0);  // some outside the footprint
}

TEST_CASE("vertex pass kernels: triangle classes and (sum of D)^2 sums at every width match a plain loop",
          "[integrals][vertex]") {
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-1, 1);
    int compared = 0, listedTotal = 0, twoOnWater = 0;
    for (const OracleMesh& m : {oracleTetrahedron(1.0), oracleBox(1, 0.5, 0.8), oracleSphere(0.5, 13, 7),
                                oracleTorus(0.6, 0.2, 17, 9)}) {
        const VertexShares s = buildVertexShares(toTriangleMesh(m));
        const std::size_t nv = s.vertexCount(), nt = s.triangleCount();
        for (int trial = 0; trial < 6; ++trial) {
            std::vector<double> D(nv);
            for (std::size_t v = 0; v < nv; ++v) {
                switch ((v * 7 + std::size_t(trial)) % 9) {
                    case 0:
                    case 1: D[v] = 0.0; break;
                    case 2: D[v] = std::numeric_limits<double>::infinity(); break;
                    default: D[v] = 0.5 * u(rng) - 0.1 * trial; break;
                }
            }
            // The plain loop: the classes as VertexHydrostatics.cpp defines them.
            double ref[3] = {0, 0, 0}, scale = 0;
            std::vector<std::int32_t> refList;
            for (std::size_t t = 0; t < nt; ++t) {
                const double d[3] = {D[std::size_t(s.corner[0][t])], D[std::size_t(s.corner[1][t])],
                                     D[std::size_t(s.corner[2][t])]};
                int wet = 0, zero = 0;
                for (double x : d) {
                    wet += x <= 0;
                    zero += x == 0;
                }
                if (wet == 3 && zero != 2) {
                    const double sum2 = (d[0] + d[1] + d[2]) * (d[0] + d[1] + d[2]);
                    ref[0] += sum2 * s.ax[t];
                    ref[1] += sum2 * s.ay[t];
                    ref[2] += sum2 * s.az[t];
                    scale += sum2 * s.absArea[t];
                } else if (wet > 0) {
                    refList.push_back(std::int32_t(t));
                    if (wet == 3) ++twoOnWater;
                }
            }
            for (int width : cpuWidths()) {
                double S[3] = {0, 0, 0};
                std::vector<std::int32_t> list(nt, -1);
                const std::size_t listed = sumWetTriangles(s, D.data(), S, list.data(), width);
                INFO("triangles " << nt << " trial " << trial << " width " << width);
                REQUIRE(listed == refList.size());
                CHECK(std::equal(refList.begin(), refList.end(), list.begin()));
                for (int k = 0; k < 3; ++k) CHECK(std::abs(S[k] - ref[k]) <= 1e-13 * scale + 1e-300);
                listedTotal += int(listed);
                ++compared;
            }
        }
    }
    CHECK(compared >= 24);
    CHECK(listedTotal > 0);
    CHECK(twoOnWater > 0);  // wet triangles with two corners exactly on the water are listed, not summed
}

TEST_CASE("vertex pass kernels: the patch's batch heights at every width match its one-point height",
          "[integrals][vertex]") {
    const btGerstnerWaterSurface sea({{0.5, 15.0, 0.4, 1.0, 0.7, 0.3}, {0.2, 6.0, 1.0, -0.2, 0.5, 2.0}});
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    WaterPatch patch;
    btWaterQueryCache cache;
    patch.build(sea, 3.0, -2.0, 1.5, 0.9, 10, cache);
    int compared = 0;
    for (std::size_t n : {std::size_t(1), std::size_t(7), std::size_t(64), std::size_t(203)}) {
        std::vector<double> x(n), z(n), expected(n);
        for (std::size_t k = 0; k < n; ++k) {
            x[k] = 3.0 + 2.0 * u(rng);  // some beyond the footprint's half side 1.5: clamped
            z[k] = -2.0 + 2.0 * u(rng);
            expected[k] = patch.height(x[k], z[k]);
        }
        for (int width : cpuWidths()) {
            std::vector<double> h(n, std::nan(""));
            interpolatePatchHeights(patch.cellGrid(), x.data(), z.data(), n, h.data(), width);
            for (std::size_t k = 0; k < n; ++k) {
                INFO("points " << n << " width " << width << " point " << k);
                CHECK(std::abs(h[k] - expected[k]) <= 1e-12 * (1 + std::abs(expected[k])));
            }
            ++compared;
        }
        std::vector<double> h(n, std::nan(""));
        patch.heights(x.data(), z.data(), n, h.data());  // the class's batch query, few points or many
        for (std::size_t k = 0; k < n; ++k) CHECK(std::abs(h[k] - expected[k]) <= 1e-12 * (1 + std::abs(expected[k])));
    }
    CHECK(compared >= 4);
}
