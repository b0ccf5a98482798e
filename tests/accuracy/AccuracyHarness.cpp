#include "AccuracyHarness.h"

#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/MassProperties.h>
#include "oracles/PolyhedralOracle.h"
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace buoyancy_test {

using namespace buoyancy;

AccuracyReport measureAccuracy(const TriangleMesh& mesh, BuoyancyMethod requested, int texture, int depthCount) {
    AccuracyReport rep;
    // Through btBuoyancyShape: the same pipeline (method choice, UVs, bake, mass properties) a body gets.
    btBuoyancySettings settings;
    settings.method = requested;  // btBuoyancyMethod is buoyancy::BuoyancyMethod
    settings.textureSize = texture;
    const auto shape = btBuoyancyShape::create(mesh, settings);
    rep.method = btBuoyancyMethodName(shape->getMethod());
    rep.texture = shape->getTextureSize();
    rep.samples = shape->getSamples().size();
    rep.generated_uvs = shape->usesGeneratedUvs();
    const SurfaceSamples& samples = shape->getSamples();
    const MassProperties& dry = shape->getUnitSolid();
    const OracleMoments exact = oracleDryMoments(mesh.vertices, mesh.triangles);
    Eigen::AlignedBox3d box;
    for (const auto& v : mesh.vertices) box.extend(v);
    const double diag = box.diagonal().norm();
    rep.dry_volume_pct = 100 * std::fabs(dry.volume - exact.volume) / exact.volume;
    rep.centre_pct_diag = 100 * (dry.centre - exact.centroid).norm() / diag;
    const Eigen::Matrix3d Iex = exact.inertiaAboutCentroid();
    rep.inertia_pct = 100 * (dry.inertia - Iex).norm() / Iex.norm();

    const std::vector<Eigen::AngleAxisd> tilts = {
        Eigen::AngleAxisd(0, Eigen::Vector3d::UnitX()),
        Eigen::AngleAxisd(23 * M_PI / 180, Eigen::Vector3d::UnitX()),
        Eigen::AngleAxisd(41 * M_PI / 180, Eigen::Vector3d(1, 2, 3).normalized()),
        Eigen::AngleAxisd(90 * M_PI / 180, Eigen::Vector3d::UnitZ())};
    SampleWorkspace ws;
    for (const auto& tilt : tilts) {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translate(Eigen::Vector3d(0.3, -0.2, 0.1));
        pose.rotate(tilt);
        const auto posed = oraclePose(mesh.vertices, pose);
        double ymin = 1e300, ymax = -1e300;
        for (const auto& v : posed) ymin = std::min(ymin, v.y()), ymax = std::max(ymax, v.y());
        for (int k = 0; k < depthCount; ++k) {
            // Levels strictly inside (ymin, ymax), plus an irrational-ish offset so no level sits on a vertex row.
            const double h = ymin + (ymax - ymin) * (k + 0.5 + 0.0137) / depthCount;
            const OracleMoments sub = oracleSubmergedMoments(posed, mesh.triangles, h);
            const btFlatWaterSurface water(h);
            const Eigen::Vector3d reference = pose * dry.centre;
            // What the library computes: the method's own evaluation (IntegrationMethod.h).
            const HydrostaticsResult r = shape->getIntegrationMethod().evaluate(
                shape->getGeometry(samples), pose, {water, 0.0, 1000.0, 9.81, reference, nullptr, &ws, nullptr});
            rep.sub_volume_pct =
                std::max(rep.sub_volume_pct, 100 * std::fabs(r.submerged_volume - sub.volume) / exact.volume);
            if (sub.volume > 0.01 * exact.volume)
                rep.cob_pct_diag =
                    std::max(rep.cob_pct_diag, 100 * (r.centre_of_buoyancy - sub.centroid).norm() / diag);
            ++rep.poses;
        }
    }
    return rep;
}

void recordAccuracyRow(const std::string& mesh, std::size_t triangles, const std::string& label,
                       const AccuracyReport& r) {
    const char* path = std::getenv("BUOYANCY_ACCURACY_REPORT");
    if (!path || !*path) return;
    if (FILE* f = std::fopen(path, "a")) {
        std::fprintf(f, "| %s | %zu | %s | %s | %d | %zu | %s | %.2g | %.2g | %.2g | %.2g | %.2g |\n", mesh.c_str(),
                     triangles, label.c_str(), r.method.c_str(), r.texture, r.samples,
                     r.generated_uvs ? "generated" : "model", r.dry_volume_pct, r.centre_pct_diag, r.inertia_pct,
                     r.sub_volume_pct, r.cob_pct_diag);
        std::fclose(f);
    }
}

std::string describe(const AccuracyReport& r) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "%s %d^2 (%zu samples, %s UVs): dry V %.3g %%, centre %.3g %% diag, inertia %.3g %%, "
                  "submerged V %.3g %%, CoB %.3g %% diag over %d poses",
                  r.method.c_str(), r.texture, r.samples, r.generated_uvs ? "generated" : "model", r.dry_volume_pct,
                  r.centre_pct_diag, r.inertia_pct, r.sub_volume_pct, r.cob_pct_diag, r.poses);
    return buf;
}

}  // namespace buoyancy_test
