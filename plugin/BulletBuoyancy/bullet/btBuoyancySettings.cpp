#include <BulletBuoyancy/bullet/btBuoyancySettings.h>

#include <BulletBuoyancy/integrals/BuoyancyMethod.h>
#include <BulletBuoyancy/integrals/IntegrationMethod.h>
#include <BulletBuoyancy/integrals/LevelOfDetail.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace {

void requireNonNegative(double value, const char* field) {
    if (!std::isfinite(value) || value < 0.0)
        throw std::invalid_argument(std::string(field) + ": must be a finite number >= 0 (got " +
                                    std::to_string(value) + ")");
}

}  // namespace

const char* btBuoyancyMethodName(btBuoyancyMethod method) { return buoyancy::buoyancyMethodName(method); }

btBuoyancyMethod btBuoyancyMethodFromName(const std::string& name) {
    if (name == "auto") return btBuoyancyMethod::Auto;
    if (const auto m = buoyancy::parseBuoyancyMethod(name)) return *m;
    throw std::invalid_argument("method: unknown value \"" + name +
                                "\" (expected default, texel-centre, exact-coverage or exact-mesh)");
}

void btBuoyancySettings::validate() const {
    if (method != btBuoyancyMethod::Auto && !buoyancy::findIntegrationMethod(method))
        throw std::invalid_argument("method: not a btBuoyancyMethod value");
    if (textureSize < 0 || textureSize > 16384)
        throw std::invalid_argument("textureSize: must be 0 (default) or in 1..16384 (got " +
                                    std::to_string(textureSize) + ")");
    if (dragClusters < 0 || dragClusters > 1000000)
        throw std::invalid_argument("dragClusters: must be in 0..1000000 (got " + std::to_string(dragClusters) + ")");
    if (waterVelocityProbes < 0 || waterVelocityProbes > 1000000)
        throw std::invalid_argument("waterVelocityProbes: must be in 0..1000000 (got " + std::to_string(waterVelocityProbes) + ")");
    if (hydrostaticsInterval < 0 || hydrostaticsInterval > 16)
        throw std::invalid_argument("hydrostaticsInterval: must be 0 (automatic) or in 1..16 (got " +
                                    std::to_string(hydrostaticsInterval) + ")");
    // std::isfinite first: an ordered comparison with NaN raises FE_INVALID (bad input must not trap).
    if (!std::isfinite(hydrostaticsReuseTolerance) || hydrostaticsReuseTolerance <= 0 || hydrostaticsReuseTolerance > 1)
        throw std::invalid_argument("hydrostaticsReuseTolerance: must be a finite number in (0, 1] (got " +
                                    std::to_string(hydrostaticsReuseTolerance) + ")");
    if (waterPatchNodes != 0 && (waterPatchNodes < 5 || waterPatchNodes > 64))
        throw std::invalid_argument("waterPatchNodes: must be 0 (exact queries) or in 5..64 (got " +
                                    std::to_string(waterPatchNodes) + ")");
    requireNonNegative(waterPatchNodesPerWavelength, "waterPatchNodesPerWavelength");
    requireNonNegative(errorBudget, "errorBudget");
    requireNonNegative(dragCoefficient, "dragCoefficient");
    requireNonNegative(skinFriction, "skinFriction");
    requireNonNegative(linearDamping, "linearDamping");
    requireNonNegative(radiationDamping, "radiationDamping");
    if (radiationDamping > 10)
        throw std::invalid_argument("radiationDamping: must be in 0..10 (got " + std::to_string(radiationDamping) + ")");
    if (linearDamping > 100)
        throw std::invalid_argument("linearDamping: must be in 0..100 m/s (got " + std::to_string(linearDamping) + ")");
    requireNonNegative(addedMassCoefficient, "addedMassCoefficient");
    requireNonNegative(addedMassWaterplaneCoefficient, "addedMassWaterplaneCoefficient");
    if (waterAcceleration != btWaterAccelerationForce::None && waterAcceleration != btWaterAccelerationForce::AddedMass &&
        waterAcceleration != btWaterAccelerationForce::AddedMassAndFroudeKrylov)
        throw std::invalid_argument("waterAcceleration: not a btWaterAccelerationForce (got " +
                                    std::to_string(int(waterAcceleration)) + ")");
    if (!std::isfinite(curvedShapeTolerance) || curvedShapeTolerance <= 0 || curvedShapeTolerance > 0.1)
        throw std::invalid_argument("curvedShapeTolerance: must be a finite number in (0, 0.1] (got " +
                                    std::to_string(curvedShapeTolerance) + ")");
}

namespace {
bool budgetApplies(const btBuoyancySettings& s) {
    // Auto picks among methods and sizes, a sampled method only its texture size.
    const buoyancy::IntegrationMethod* method = buoyancy::findIntegrationMethod(s.method);
    return s.errorBudget > 0 && (!method || method->sampled);
}
}  // namespace

btBuoyancyMethod btBuoyancyResolveMethod(const btBuoyancySettings& settings, std::size_t triangleCount) {
    if (budgetApplies(settings))
        return buoyancy::pickLevelOfDetail(settings.errorBudget, settings.method, triangleCount).picked.method;
    return buoyancy::resolveMethod(settings.method, triangleCount);
}

int btBuoyancyResolveTextureSize(const btBuoyancySettings& settings, btBuoyancyMethod resolved) {
    if (settings.textureSize > 0) return settings.textureSize;
    const buoyancy::IntegrationMethod* method = buoyancy::findIntegrationMethod(resolved);
    const bool sampled = !method || method->sampled;  // an unresolved value: as for a sampled method
    if (budgetApplies(settings) && sampled) {
        // The budget's pick for that method (the triangle count does not change a texture method's N).
        const btBuoyancyMethod m = settings.method == btBuoyancyMethod::Auto ? resolved : settings.method;
        return buoyancy::pickLevelOfDetail(settings.errorBudget, m, 0).picked.textureSize;
    }
    if (!sampled) return 0;
    if (settings.method == btBuoyancyMethod::Auto) return buoyancy::kDefaultLargeMeshTexture;
    return method ? method->defaultTextureSize : 0;
}

btBuoyancyLevelOfDetail btBuoyancyPickLevelOfDetail(const btBuoyancySettings& settings, std::size_t triangleCount) {
    settings.validate();
    btBuoyancyLevelOfDetail out;
    out.method = btBuoyancyResolveMethod(settings, triangleCount);
    out.textureSize = buoyancy::integrationMethod(out.method).sampled ? btBuoyancyResolveTextureSize(settings, out.method) : 0;
    out.budgetPct = settings.errorBudget;
    // The model's error for what is used (an explicit textureSize may differ from the budget's pick).
    for (const buoyancy::LodCandidate& c : buoyancy::lodCandidates(out.method, triangleCount))
        if (c.textureSize == out.textureSize) out.modelVolumeErrorPct = c.volumeErrorPct;
    const std::string what = std::string(btBuoyancyMethodName(out.method)) +
                             (out.textureSize ? " " + std::to_string(out.textureSize) : std::string());
    if (budgetApplies(settings)) {
        const buoyancy::LodChoice c = buoyancy::pickLevelOfDetail(settings.errorBudget, settings.method, triangleCount);
        out.withinBudget = c.withinBudget && out.modelVolumeErrorPct <= settings.errorBudget;
        out.description = (settings.textureSize > 0 ? what + " (textureSize given; budget's pick: " + c.description + ")"
                                                    : c.description);
    } else {
        char b[64];
        std::snprintf(b, sizeof b, "%.2g", out.modelVolumeErrorPct);
        out.description = what + (settings.errorBudget > 0 ? " (method given; no budget pick)"
                                                           : " (library default, no error budget; model worst volume error " +
                                                                 std::string(b) + " %)");
    }
    // Temporal level of detail (hydrostaticsInterval 0): a budget may allow longer than the default 1/30 s.
    if (settings.hydrostaticsInterval == 0) {
        double temporalError = 0;
        out.evaluationPeriod = btBuoyancyEvaluationPeriod(settings, &temporalError);
        if (temporalError > 0) {
            char b[160];
            std::snprintf(b, sizeof b,
                          "; exact hydrostatics every %.1f ms, predicted in between (temporal model worst force error "
                          "%.2g %% x 2 <= budget; prediction tolerance %.2g %%)",
                          1e3 * out.evaluationPeriod, temporalError, 100.0 * btBuoyancyResolveReuseTolerance(settings));
            out.description += b;
        }
    }
    return out;
}

int btBuoyancyWaterPatchNodes(const btBuoyancySettings& settings, double footprintRadius, double shortestWavelength) {
    if (settings.waterPatchNodes <= 0) return 0;
    int nodes = settings.waterPatchNodes;
    const double perWave = settings.waterPatchNodesPerWavelength;
    if (perWave > 0 && std::isfinite(perWave) && shortestWavelength > 0 && std::isfinite(shortestWavelength) &&
        footprintRadius > 0 && std::isfinite(footprintRadius)) {
        const double cells = std::ceil(2.0 * footprintRadius * perWave / shortestWavelength);  // spacing ≤ λ_min / perWave
        if (cells + 4.0 > double(nodes)) nodes = cells + 4.0 >= 64.0 ? 64 : int(cells) + 4;
    }
    return std::min(nodes, 64);
}

namespace {
/// Temporal error model: time between exact evaluations (s) and the worst force error measured there (% of ρ g V)
/// with the tolerance at 0.2 %. Source: `buoyancy bench --parts scaling` → temporal_lod.csv (boat-x4, 3,400
/// triangles, 5 boats in the scaling sea, 240 substeps/s, 10 s after 2 s of settling; against clipping every triangle
/// with exact wave queries), intervals 8, 12, 16 at tolerance 0.2 % (cubic extrapolation with the stiffness
/// correction; the worst substeps are waves overrunning a deck, caught by the next check; 2026-11-22 run at c60193f:
/// 0.2085, 0.2389, 0.2753 %), rounded up.
struct TemporalModelPoint {
    double period;
    double worstForceErrorPct;
};
constexpr TemporalModelPoint kTemporalModel[] = {{8.0 / 240.0, 0.21}, {12.0 / 240.0, 0.24}, {16.0 / 240.0, 0.28}};
/// s; measured (temporal_lod.csv, 1,000 boats in scaling.csv): at 1/30 s with the tolerance at 0.01 % the force
/// error's mean and 99th percentile stay at exact evaluation's; an undamped bobbing box keeps its energy as exact
/// evaluation does (tests/scenarios/DynamicsTest.cpp, "energy is conserved with drag off"), an undamped sphere its
/// amplitude within 0.1 % a minute (tests/bullet/TemporalLodTest.cpp).
constexpr double kDefaultEvaluationPeriod = 1.0 / 30.0;
}  // namespace

double btBuoyancyEvaluationPeriod(const btBuoyancySettings& settings, double* modelErrorPct) {
    double period = kDefaultEvaluationPeriod, error = 0;
    if (std::isfinite(settings.errorBudget) && settings.errorBudget > 0)
        for (const TemporalModelPoint& p : kTemporalModel)
            if (p.worstForceErrorPct * buoyancy::kLodSafetyFactor <= settings.errorBudget && p.period > period) {
                period = p.period;
                error = p.worstForceErrorPct;
            }
    if (modelErrorPct) *modelErrorPct = error;
    return period;
}

int btBuoyancyResolveInterval(const btBuoyancySettings& settings, double dt) {
    if (settings.hydrostaticsInterval > 0) return settings.hydrostaticsInterval;
    return btBuoyancyAutomaticInterval(dt, btBuoyancyEvaluationPeriod(settings));
}

double btBuoyancyResolveReuseTolerance(const btBuoyancySettings& settings) {
    double tolerance = settings.hydrostaticsReuseTolerance;
    if (settings.hydrostaticsInterval == 0 && std::isfinite(settings.errorBudget) && settings.errorBudget > 0)
        tolerance = std::max(tolerance, std::min(1.0, settings.errorBudget / 100.0 / buoyancy::kLodSafetyFactor));
    return tolerance;
}

int btBuoyancyAutomaticInterval(double dt, double periodSeconds) {
    // std::isfinite first: an ordered comparison with NaN raises FE_INVALID.
    if (!std::isfinite(dt) || !std::isfinite(periodSeconds) || dt <= 0 || periodSeconds <= 0) return 1;
    const double ratio = periodSeconds / dt;
    return int(std::max(1.0, std::min(16.0, std::floor(ratio + 1e-6))));
}
