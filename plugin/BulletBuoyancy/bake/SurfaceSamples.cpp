#include <BulletBuoyancy/bake/SurfaceSamples.h>

namespace buoyancy {

void SurfaceSamples::reserve(std::size_t n) {
    for (auto* v : {&px, &py, &pz, &ax, &ay, &az, &area}) v->reserve(n);
    texel.reserve(n);
    triangle.reserve(n);
}

void SurfaceSamples::push(double x, double y, double z, double Ax, double Ay, double Az, double a,
                          std::uint32_t texelIndex, std::uint32_t triangleIndex) {
    px.push_back(x);
    py.push_back(y);
    pz.push_back(z);
    ax.push_back(Ax);
    ay.push_back(Ay);
    az.push_back(Az);
    area.push_back(a);
    texel.push_back(texelIndex);
    triangle.push_back(triangleIndex);
}

const char* bakeMethodName(BakeMethod method) {
    switch (method) {
        case BakeMethod::TexelCentre: return "texel-centre";
        case BakeMethod::ExactCoverage: return "exact-coverage";
    }
    return "unknown";
}

}  // namespace buoyancy
