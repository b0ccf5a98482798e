#include "benchmark/Fig9.h"

#include "benchmark/ComparisonMethods.h"

#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <cmath>
#include <functional>
#include <cstdio>
#include <ostream>
#include <stdexcept>

namespace buoyancy::bench {

void runFig9(const Fig9Options& o, const std::string& path, std::ostream& log) {
    constexpr double R = 0.5, rho = 1000.0, g = 9.81;
    const TriangleMesh mesh = makeSphereMesh(R, o.segments, o.rings);
    const btFlatWaterSurface water(0.0);
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "method,texture,depth,volume,analytic_volume,error_pct\n");
    const double vSphere = 4.0 * M_PI * R * R * R / 3.0;
    auto pose = [&](double depth) {
        Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
        p.translation() = Eigen::Vector3d(0, R - depth, 0);  // lowest point at −depth, water at 0
        return p;
    };
    auto emit = [&](const std::string& method, int n, const std::function<double(double)>& volumeAt) {
        double worst = 0;
        for (int i = 0; i < o.depths; ++i) {
            const double d = 2 * R * i / double(o.depths - 1);
            const double analytic = M_PI * d * d * (3 * R - d) / 3.0;  // design.md 5: spherical cap
            const double v = volumeAt(d);
            const double err = 100.0 * (v - analytic) / vSphere;
            worst = std::max(worst, std::abs(err));
            std::fprintf(f, "%s,%d,%.6f,%.9g,%.9g,%.6g\n", method.c_str(), n, d, v, analytic, err);
        }
        log << "  fig9 " << method << ' ' << n << ": worst |V - analytic| = " << worst << " % of the sphere\n";
    };
    const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    for (const char* m : {"texel-centre", "exact-coverage"})
        for (int n : o.textures) {
            btBuoyancySettings st;
            st.method = btBuoyancyMethodFromName(m);
            st.textureSize = n;
            std::shared_ptr<const btBuoyancyShape> shape;
            try {
                shape = btBuoyancyShape::create(mesh, st);
            } catch (const std::exception& e) {
                log << "  fig9 " << m << ' ' << n << ": skipped (" << e.what() << ")\n";
                continue;
            }
            SampleWorkspace ws;
            emit(m, n, [&](double d) {
                return sampledHydrostatics(shape->getSamples(), pose(d), water, 0, rho, g, origin, ws).submerged_volume;
            });
        }
    emit("exact-mesh", 0, [&](double d) { return clippedHydrostatics(mesh, pose(d), water, 0, rho, g, origin).submerged_volume; });
    const FaceSet faces = makeFaceSet(mesh);
    ComparisonWorkspace cws;
    emit("downward-faces", 0, [&](double d) {
        return downwardFaceHydrostatics(faces, pose(d), water, 0, rho, g, origin, cws).volume;
    });
    if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + path);
}

}  // namespace buoyancy::bench
