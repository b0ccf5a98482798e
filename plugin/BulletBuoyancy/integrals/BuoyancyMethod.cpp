#include <BulletBuoyancy/integrals/BuoyancyMethod.h>

namespace buoyancy {

const char* buoyancyMethodName(BuoyancyMethod method) {
    switch (method) {
        case BuoyancyMethod::Default: return "default";
        case BuoyancyMethod::TexelCentre: return "texel-centre";
        case BuoyancyMethod::ExactCoverage: return "exact-coverage";
        case BuoyancyMethod::ExactMesh: return "exact-mesh";
    }
    return "unknown";
}

std::optional<BuoyancyMethod> parseBuoyancyMethod(const std::string& name) {
    for (BuoyancyMethod m : {BuoyancyMethod::Default, BuoyancyMethod::TexelCentre, BuoyancyMethod::ExactCoverage,
                             BuoyancyMethod::ExactMesh})
        if (name == buoyancyMethodName(m)) return m;
    return std::nullopt;
}

bool methodUsesTexture(BuoyancyMethod method) {
    return method == BuoyancyMethod::TexelCentre || method == BuoyancyMethod::ExactCoverage;
}

int defaultTextureSize(BuoyancyMethod method) {
    switch (method) {
        case BuoyancyMethod::TexelCentre: return 512;
        case BuoyancyMethod::ExactCoverage: return 128;
        default: return 0;
    }
}

BuoyancyMethod resolveMethod(BuoyancyMethod requested, std::size_t triangleCount) {
    if (requested != BuoyancyMethod::Default) return requested;
    return triangleCount <= kDefaultExactMeshMaxTriangles ? BuoyancyMethod::ExactMesh : BuoyancyMethod::ExactCoverage;
}

}  // namespace buoyancy
