/// @file LevelOfDetail.cpp
/// Automatic level of detail (declared in LevelOfDetail.h).

#include <BulletBuoyancy/integrals/LevelOfDetail.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace buoyancy {

namespace {

/// Worst submerged-volume error (% of the body's volume) measured by `buoyancy bench` (docs/benchmarks,
/// speed_vs_error.csv: box, sphere, torus, boat, duck, duck-x4, torus-fine × 15 poses, flat water), per N.
struct MeasuredError {
    int n;
    double exactCoverage;
    double texelCentre;
};
constexpr MeasuredError kMeasured[] = {
    {32, 1.556, 108.7}, {64, 0.2107, 14.44}, {128, 0.02119, 7.962},
    {256, 0.005343, 1.29}, {512, 0.001337, 0.414}, {1024, 0.000328, 0.4058},
};
/// Exact-mesh is exact to rounding in flat water (measured ≤ 6e-12 %).
constexpr double kExactMeshErrorPct = 1e-10;
/// Cost model, ns per body-substep (one btBuoyancyAction substep, flat water, drag on; docs/benchmarks run of
/// 2026-11-22 on a loaded 2-core machine): ≈ 15 ns per clipped triangle (sphere 3968: 60 µs, torus 4096: 71 µs)
/// and ≈ 13 ns per surface sample at 64²–256² (more above: cache misses), and the samples an N² texture yields
/// (0.49–0.93 N² measured; the middle is used). Only the ratio of the two matters for the pick.
constexpr double kNsPerTriangle = 15.0;
constexpr double kNsPerSample = 13.0;
constexpr double kSamplesPerTexel = 0.7;

}  // namespace

std::vector<LodCandidate> lodCandidates(BuoyancyMethod requested, std::size_t triangleCount) {
    std::vector<LodCandidate> c;
    if (requested == BuoyancyMethod::Auto || requested == BuoyancyMethod::ExactMesh)
        c.push_back({BuoyancyMethod::ExactMesh, 0, kExactMeshErrorPct, kNsPerTriangle * double(triangleCount)});
    if (requested == BuoyancyMethod::ExactMesh) return c;
    for (const MeasuredError& m : kMeasured) {
        const double cost = kNsPerSample * kSamplesPerTexel * double(m.n) * double(m.n);
        if (requested == BuoyancyMethod::Auto || requested == BuoyancyMethod::ExactCoverage)
            c.push_back({BuoyancyMethod::ExactCoverage, m.n, kLodSafetyFactor * m.exactCoverage, cost});
        if (requested == BuoyancyMethod::TexelCentre)
            c.push_back({BuoyancyMethod::TexelCentre, m.n, kLodSafetyFactor * m.texelCentre, cost});
    }
    return c;
}

LodChoice pickLevelOfDetail(double budgetPct, BuoyancyMethod requested, std::size_t triangleCount) {
    if (!std::isfinite(budgetPct) || !(budgetPct > 0))
        throw std::invalid_argument("errorBudget: must be a finite number > 0 (% of the body's volume)");
    const std::vector<LodCandidate> all = lodCandidates(requested, triangleCount);
    LodChoice out;
    out.budgetPct = budgetPct;
    const LodCandidate* best = nullptr;
    for (const LodCandidate& c : all) {
        if (c.volumeErrorPct > budgetPct) continue;
        if (!best || c.costNs < best->costNs || (c.costNs == best->costNs && c.volumeErrorPct < best->volumeErrorPct))
            best = &c;
    }
    out.withinBudget = best != nullptr;
    if (!best)
        for (const LodCandidate& c : all)
            if (!best || c.volumeErrorPct < best->volumeErrorPct) best = &c;
    out.picked = *best;
    char b[256];
    if (best->method == BuoyancyMethod::ExactMesh)
        std::snprintf(b, sizeof b, "%s (exact in flat water; model cost %.0f ns for %zu triangles; budget %g %%)",
                      buoyancyMethodName(best->method), best->costNs, triangleCount, budgetPct);
    else
        std::snprintf(b, sizeof b, "%s %d (model worst volume error %.3g %% %s budget %g %%; model cost %.0f ns)",
                      buoyancyMethodName(best->method), best->textureSize, best->volumeErrorPct,
                      out.withinBudget ? "<=" : "> (nothing fits)", budgetPct, best->costNs);
    out.description = b;
    return out;
}

}  // namespace buoyancy
