// Pass 2 of the per-vertex hydrostatics (plugin/integrals/VertexSharesKernel): every SIMD width this CPU runs against
// a plain loop over the same shares written here, with D values that are negative, zero, positive, +∞ (not computed)
// and NaN, and vertex counts that leave a tail.
#include "integrals/VertexShares.h"
#include "integrals/VertexSharesKernel.h"
#include "oracles/FloatingPointTraps.h"
#include "oracles/OracleMeshes.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

using namespace buoyancy;
using namespace buoyancy_test;


TEST_CASE("vertex shares kernel: every width the CPU runs matches a plain loop", "[integrals][vertex]") {
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
