// The passes of the per-vertex hydrostatics (plugin/BulletBuoyancy/integrals/VertexPassKernels): every SIMD width this CPU runs
// against plain loops written here, and pass 4 against clipping each listed triangle as a polygon (BodyFrameSums.h's
// addClippedBodyTriangle) less the corner shares of VertexShares.h. Pass 2 with D values that are negative, zero,
// positive, +∞ (not computed) and NaN, and vertex counts that leave a tail. Pass 1: each vertex moved by the pose and its height asked of WaterPatch::height one
// by one (vertices outside the patch's footprint included: clamped cells). Pass 3: the triangle classes from depths
// that are negative, zero (two and three corners on the water), positive and +∞, triangle counts that leave a tail.
#include <BulletBuoyancy/integrals/BodyFrameSums.h>
#include <BulletBuoyancy/integrals/VertexPassKernels.h>
#include <BulletBuoyancy/integrals/VertexShares.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include "oracles/FloatingPointTraps.h"
#include "oracles/OracleMeshes.h"
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

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

TEST_CASE("vertex pass kernels: the straddling triangles at every width match clipping them one by one",
          "[integrals][vertex]") {
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> u01(-1, 1);
    int compared = 0;
    std::size_t listedTotal = 0;
    for (const OracleMesh& m : {oracleBox(1, 0.5, 0.8), oracleSphere(0.5, 13, 7), oracleTorus(0.6, 0.2, 17, 9)}) {
        const TriangleMesh mesh = toTriangleMesh(m);
        const VertexShares s = buildVertexShares(mesh);
        for (int trial = 0; trial < 5; ++trial) {
            const Eigen::Matrix3d R =
                Eigen::AngleAxisd(3 * u01(rng), Eigen::Vector3d(u01(rng), u01(rng), u01(rng)).normalized())
                    .toRotationMatrix();
            const Eigen::Vector3d up = R.row(1).transpose(), X = R.row(0).transpose(), Z = R.row(2).transpose();
            // Depths of a tilted plane through the body, some corners exactly on it.
            const double level = 0.2 * u01(rng);
            std::vector<double> D(s.vertexCount());
            for (std::size_t v = 0; v < D.size(); ++v) {
                D[v] = up.dot(Eigen::Vector3d(s.qx[v], s.qy[v], s.qz[v])) - level + 0.05 * u01(rng);
                if ((v + std::size_t(trial)) % 11 == 0) D[v] = 0.0;
            }
            double S[3] = {0, 0, 0};
            std::vector<std::int32_t> list(s.triangleCount());
            const std::size_t n = sumWetTriangles(s, D.data(), S, list.data());
            listedTotal += n;
            // Expected: each listed triangle clipped as a polygon (BodyFrameSums.h, about the body origin) less the
            // corner shares of VertexShares.h for its wet corners, in the kernel's scales.
            NodeSums clip;
            double shareF[3] = {0, 0, 0}, shareT[3] = {0, 0, 0}, shareQ[3] = {0, 0, 0}, shareD2 = 0, shareAy = 0,
                   shareArea = 0;
            for (std::size_t k = 0; k < n; ++k) {
                const std::size_t t = std::size_t(list[k]);
                BodyCorner in[3];
                Eigen::Vector3d q[3];
                for (int c = 0; c < 3; ++c) {
                    const std::size_t v = std::size_t(s.corner[c][t]);
                    q[c] = Eigen::Vector3d(s.qx[v], s.qy[v], s.qz[v]);
                    in[c] = BodyCorner{q[c], D[v]};
                }
                addClippedBodyTriangle(in, up, X, Z, clip);
                const Eigen::Vector3d A(s.ax[t], s.ay[t], s.az[t]), sum = q[0] + q[1] + q[2];
                for (int c = 0; c < 3; ++c) {
                    const double d = in[c].D;
                    if (!(d <= 0)) continue;
                    const Eigen::Vector3d w12 = q[c] + sum, T = d * w12.cross(A);
                    for (int a = 0; a < 3; ++a) {
                        shareF[a] += d * A[a];
                        shareT[a] += T[a];
                        shareQ[a] += d * w12[a] * A.dot(up);
                    }
                    shareD2 += d * d * A.dot(up);
                    shareAy += A.dot(up);
                    shareArea += s.absArea[t];
                }
            }
            for (int width : cpuWidths()) {
                StraddlingSums p;
                const double uv[3] = {up.x(), up.y(), up.z()}, Xv[3] = {X.x(), X.y(), X.z()},
                             Zv[3] = {Z.x(), Z.y(), Z.z()};
                sumStraddlingTriangles(s, D.data(), list.data(), n, uv, Xv, Zv, 0.0, 0.0, p, width);
                INFO("trial " << trial << " width " << width << " listed " << n);
                const double tol = 1e-12;
                for (int a = 0; a < 3; ++a) {
                    CHECK(std::abs(p.F[a] - (3 * clip.F[a] - shareF[a])) <= tol);
                    CHECK(std::abs(p.T[a] - (12 * clip.T[a] - shareT[a])) <= tol);
                    CHECK(std::abs(p.Q[a] - (12 * clip.Q[a] - shareQ[a])) <= tol);
                }
                CHECK(std::abs(p.D2 - (12 * clip.D2 - shareD2)) <= tol);
                CHECK(std::abs(up.dot(Eigen::Vector3d(p.B[0], p.B[1], p.B[2])) - (3 * clip.Ay - shareAy)) <= tol);
                CHECK(std::abs(p.area - (3 * clip.area - shareArea)) <= tol);
                CHECK(std::abs(p.waterline.area2 - clip.waterline.area2) <= tol);
                CHECK(std::abs(p.waterline.x6 - clip.waterline.x6) <= tol);
                CHECK(std::abs(p.waterline.z6 - clip.waterline.z6) <= tol);
                CHECK(std::abs(p.waterline.xx12 - clip.waterline.xx12) <= tol);
                CHECK(std::abs(p.waterline.xz24 - clip.waterline.xz24) <= tol);
                CHECK(std::abs(p.waterline.zz12 - clip.waterline.zz12) <= tol);
                ++compared;
            }
        }
    }
    CHECK(compared >= 15);
    CHECK(listedTotal > 100);
}

TEST_CASE("vertex pass kernels: the shares of the wet vertices at every width match a plain loop", "[integrals][vertex]") {
    const ScopedFpTrapsOff nanOnPurpose;  // NaN depths on purpose: comparing them raises FE_INVALID in the FPE run
    std::vector<int> widths = {2};
    if (vertexKernelLanes() >= 4) widths.push_back(4);
    if (vertexKernelLanes() >= 8) widths.push_back(8);
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> u(-1, 1);
    int compared = 0;
    for (const OracleMesh& m : {oracleTetrahedron(1.0), oracleBox(1, 0.5, 0.8), oracleSphere(0.5, 13, 7), oracleTorus(0.6, 0.2, 17, 9)}) {
        const VertexShares s = buildVertexShares(toTriangleMesh(m));
        const std::size_t n = s.vertexCount();
        for (int trial = 0; trial < 6; ++trial) {
            std::vector<double> D(n);
            for (std::size_t v = 0; v < n; ++v) {
                switch ((v + std::size_t(trial)) % 7) {
                    case 0: D[v] = 0.0; break;
                    case 1: D[v] = std::numeric_limits<double>::infinity(); break;
                    case 2: D[v] = trial == 5 ? std::nan("") : 0.3; break;
                    default: D[v] = 0.5 * u(rng) - 0.2 * trial / 5.0; break;
                }
            }
            double ref[kShareSums] = {}, scale[kShareSums] = {};
            for (std::size_t v = 0; v < n; ++v) {
                const double d = D[v];
                if (!(d <= 0)) continue;
                const double terms[kShareSums] = {d * s.bx[v], d * s.by[v], d * s.bz[v], d * s.tx[v], d * s.ty[v], d * s.tz[v],
                                                  d * d * s.bx[v], d * d * s.by[v], d * d * s.bz[v], s.bx[v], s.by[v], s.bz[v],
                                                  s.area[v], d * s.m[0][v], d * s.m[1][v], d * s.m[2][v], d * s.m[3][v],
                                                  d * s.m[4][v], d * s.m[5][v], d * s.m[6][v], d * s.m[7][v], d * s.m[8][v]};
                for (int k = 0; k < kShareSums; ++k) {
                    ref[k] += terms[k];
                    scale[k] += std::abs(terms[k]);
                }
            }
            for (int width : widths) {
                double out[kShareSums] = {};
                sumWetShares(s, D.data(), n, out, width);
                for (int k = 0; k < kShareSums; ++k) {
                    INFO("vertices " << n << " trial " << trial << " width " << width << " sum " << k);
                    REQUIRE(std::isfinite(out[k]));
                    CHECK(std::abs(out[k] - ref[k]) <= 1e-13 * scale[k] + 1e-300);
                }
                ++compared;
            }
        }
    }
    CHECK(compared >= 24);
}
