#pragma once
/// @file LevelOfDetail.h
/// Automatic level of detail: given an error budget per body (worst submerged-volume error, % of
/// the body's volume), pick the cheapest integration method and texture size whose *measured* worst error
/// fits, from the error and cost model measured by `buoyancy bench` (docs/benchmarks/speed_vs_error.csv).

#include <BulletBuoyancy/integrals/BuoyancyMethod.h>

#include <cstddef>
#include <string>
#include <vector>

namespace buoyancy {

/// One configuration of the error/cost model.
struct LodCandidate {
    BuoyancyMethod method = BuoyancyMethod::ExactMesh; ///< concrete method
    int textureSize = 0;                               ///< N (0 for exact-mesh)
    /// Model worst volume error, % of the body's volume: the worst measured over the benchmark's 7 shapes ×
    /// 15 poses (flat water), times kLodSafetyFactor.
    double volumeErrorPct = 0;
    /// Model hydrostatic cost per body-substep, ns: per triangle (exact-mesh) or per sample (≈ 0.9 N²).
    double costNs = 0;
};

/// Margin on the measured worst errors (other meshes than the benchmark's can be somewhat worse).
constexpr double kLodSafetyFactor = 2.0;
/// The texture sizes the automatic pick considers for a sampled method (the sizes the error model was measured at).
constexpr int kLodTextureSizes[] = {32, 64, 128, 256, 512, 1024};

/// What pickLevelOfDetail chose and why.
struct LodChoice {
    LodCandidate picked;        ///< the configuration used
    double budgetPct = 0;       ///< the budget asked, %
    bool withinBudget = true;   ///< false when no candidate fits (then the most accurate one is picked)
    std::string description;    ///< e.g. "exact-coverage 128 (model worst volume error 0.042 % <= budget 0.1 %)"
};

/// The model's candidates for a mesh of `triangleCount` triangles and a method restriction: `requested`
/// Auto allows exact-mesh and exact-coverage 32…1024; ExactCoverage or TexelCentre only that method's
/// sizes; ExactMesh only itself. Dominated candidates (another one at most as costly and at most as wrong)
/// are kept: the pick below takes the cheapest feasible one.
std::vector<LodCandidate> lodCandidates(BuoyancyMethod requested, std::size_t triangleCount);

/// Pick the cheapest candidate whose model error is ≤ budgetPct (ties: the more accurate); when none fits,
/// the most accurate candidate, with withinBudget = false.
/// @param budgetPct  > 0, % of the body's volume
/// @throws std::invalid_argument for a budget that is not a finite number > 0
LodChoice pickLevelOfDetail(double budgetPct, BuoyancyMethod requested, std::size_t triangleCount);

}  // namespace buoyancy
