/// @file LevelOfDetail.cpp
/// Automatic level of detail (declared in LevelOfDetail.h).

#include <BulletBuoyancy/integrals/LevelOfDetail.h>

#include <BulletBuoyancy/integrals/IntegrationMethod.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace buoyancy {

std::vector<LodCandidate> lodCandidates(BuoyancyMethod requested, std::size_t triangleCount) {
    // Each method's model is on its registry entry (IntegrationMethod::modelErrorPct, modelCostNs): a method without
    // a texture is one candidate, a sampled one a candidate per texture size.
    std::vector<LodCandidate> c;
    for (const IntegrationMethod& m : integrationMethods()) {
        if (!(requested == m.method || (requested == BuoyancyMethod::Auto && m.automatic))) continue;
        if (!m.modelErrorPct || !m.modelCostNs) continue;
        if (!m.sampled) {
            c.push_back({m.method, 0, kLodSafetyFactor * m.modelErrorPct(0), m.modelCostNs(triangleCount, 0)});
            continue;
        }
        for (int n : kLodTextureSizes)
            c.push_back({m.method, n, kLodSafetyFactor * m.modelErrorPct(n), m.modelCostNs(triangleCount, n)});
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
