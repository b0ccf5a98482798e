#include <BulletBuoyancy/integrals/BuoyancyMethod.h>

#include <BulletBuoyancy/integrals/IntegrationMethod.h>

namespace buoyancy {

const char* buoyancyMethodName(BuoyancyMethod method) {
    if (method == BuoyancyMethod::Auto) return "default";
    const IntegrationMethod* m = findIntegrationMethod(method);
    return m ? m->name : "unknown";
}

std::optional<BuoyancyMethod> parseBuoyancyMethod(const std::string& name) {
    if (name == buoyancyMethodName(BuoyancyMethod::Auto)) return BuoyancyMethod::Auto;
    for (const IntegrationMethod& m : integrationMethods())
        if (name == m.name) return m.method;
    return std::nullopt;
}

BuoyancyMethod resolveMethod(BuoyancyMethod requested, std::size_t triangleCount) {
    if (requested != BuoyancyMethod::Auto) return requested;
    return triangleCount <= kDefaultExactMeshMaxTriangles ? BuoyancyMethod::ExactMesh : BuoyancyMethod::ExactCoverage;
}

}  // namespace buoyancy
