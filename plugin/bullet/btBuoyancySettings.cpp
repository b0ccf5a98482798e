#include "bullet/btBuoyancySettings.h"

#include "integrals/BuoyancyMethod.h"

#include <cmath>
#include <stdexcept>

namespace {

buoyancy::BuoyancyMethod toCore(btBuoyancyMethod m) {
    switch (m) {
        case btBuoyancyMethod::TexelCentre: return buoyancy::BuoyancyMethod::TexelCentre;
        case btBuoyancyMethod::ExactCoverage: return buoyancy::BuoyancyMethod::ExactCoverage;
        case btBuoyancyMethod::ExactMesh: return buoyancy::BuoyancyMethod::ExactMesh;
        case btBuoyancyMethod::Auto: break;
    }
    return buoyancy::BuoyancyMethod::Default;
}

btBuoyancyMethod fromCore(buoyancy::BuoyancyMethod m) {
    switch (m) {
        case buoyancy::BuoyancyMethod::TexelCentre: return btBuoyancyMethod::TexelCentre;
        case buoyancy::BuoyancyMethod::ExactCoverage: return btBuoyancyMethod::ExactCoverage;
        case buoyancy::BuoyancyMethod::ExactMesh: return btBuoyancyMethod::ExactMesh;
        case buoyancy::BuoyancyMethod::Default: break;
    }
    return btBuoyancyMethod::Auto;
}

void requireNonNegative(double value, const char* field) {
    if (!std::isfinite(value) || value < 0.0)
        throw std::invalid_argument(std::string(field) + ": must be a finite number >= 0 (got " +
                                    std::to_string(value) + ")");
}

}  // namespace

const char* btBuoyancyMethodName(btBuoyancyMethod method) { return buoyancy::buoyancyMethodName(toCore(method)); }

btBuoyancyMethod btBuoyancyMethodFromName(const std::string& name) {
    if (name == "auto") return btBuoyancyMethod::Auto;
    if (const auto m = buoyancy::parseBuoyancyMethod(name)) return fromCore(*m);
    throw std::invalid_argument("method: unknown value \"" + name +
                                "\" (expected default, texel-centre, exact-coverage or exact-mesh)");
}

void btBuoyancySettings::validate() const {
    if (method != btBuoyancyMethod::Auto && method != btBuoyancyMethod::TexelCentre &&
        method != btBuoyancyMethod::ExactCoverage && method != btBuoyancyMethod::ExactMesh)
        throw std::invalid_argument("method: not a btBuoyancyMethod value");
    if (textureSize < 0 || textureSize > 16384)
        throw std::invalid_argument("textureSize: must be 0 (default) or in 1..16384 (got " +
                                    std::to_string(textureSize) + ")");
    requireNonNegative(dragCoefficient, "dragCoefficient");
    requireNonNegative(skinFriction, "skinFriction");
    requireNonNegative(linearDamping, "linearDamping");
    requireNonNegative(addedMassCoefficient, "addedMassCoefficient");
}

btBuoyancyMethod btBuoyancyResolveMethod(const btBuoyancySettings& settings, std::size_t triangleCount) {
    return fromCore(buoyancy::resolveMethod(toCore(settings.method), triangleCount));
}

int btBuoyancyResolveTextureSize(const btBuoyancySettings& settings, btBuoyancyMethod resolved) {
    if (settings.textureSize > 0) return settings.textureSize;
    if (resolved == btBuoyancyMethod::ExactMesh) return 0;
    if (settings.method == btBuoyancyMethod::Auto) return buoyancy::kDefaultLargeMeshTexture;
    return buoyancy::defaultTextureSize(toCore(resolved));
}
