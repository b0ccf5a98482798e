// The registry of integration methods (integrals/IntegrationMethod.h, design.md 8.2): one entry per method of the
// enumeration, names that round-trip, preparations that give what each method reads, and evaluations that are the
// integrals they stand for, to the bit.
#include <BulletBuoyancy/integrals/IntegrationMethod.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>

using namespace buoyancy;

namespace {

/// A sine wave along a diagonal (not flat, so the exact-mesh method takes its wave path).
class DiagonalSine : public btWaterSurface {
public:
    void heights(const double* x, const double* z, std::size_t n, double t, double* out) const override {
        for (std::size_t i = 0; i < n; ++i) out[i] = 0.1 + 0.15 * std::sin(0.6 * (x[i] + 0.5 * z[i]) - 0.8 * t);
    }
    void heightBounds(double, double, double, double, double, double& lo, double& hi) const override {
        lo = 0.1 - 0.15;
        hi = 0.1 + 0.15;
    }
};

}  // namespace

TEST_CASE("integration methods: one entry per method, in the enumeration's order, with names that round-trip") {
    const std::vector<IntegrationMethod>& all = integrationMethods();
    REQUIRE(all.size() == 3);
    for (std::size_t i = 0; i < all.size(); ++i) {
        const IntegrationMethod& m = all[i];
        INFO(m.name);
        CHECK(m.method != BuoyancyMethod::Auto);
        if (i > 0) CHECK(int(all[i - 1].method) < int(m.method));
        CHECK(findIntegrationMethod(m.method) == &m);
        CHECK(&integrationMethod(m.method) == &m);
        CHECK(std::string(buoyancyMethodName(m.method)) == m.name);
        CHECK(parseBuoyancyMethod(m.name) == m.method);
        CHECK(m.prepare != nullptr);
        CHECK(m.evaluate != nullptr);
        CHECK((m.defaultTextureSize > 0) == m.sampled);
        if (m.deviceBatched) CHECK(m.sampled);  // the device kernels sum surface samples
    }
    CHECK(std::string(buoyancyMethodName(BuoyancyMethod::Auto)) == "default");
    CHECK(parseBuoyancyMethod("default") == BuoyancyMethod::Auto);
    CHECK_FALSE(parseBuoyancyMethod("fast"));
    CHECK(findIntegrationMethod(BuoyancyMethod::Auto) == nullptr);
    CHECK_THROWS_AS(integrationMethod(BuoyancyMethod::Auto), std::invalid_argument);
    CHECK_THROWS_AS(integrationMethod(static_cast<BuoyancyMethod>(42)), std::invalid_argument);
    CHECK(std::string(buoyancyMethodName(static_cast<BuoyancyMethod>(42))) == "unknown");
    CHECK(resolveMethod(BuoyancyMethod::Auto, 12) == BuoyancyMethod::ExactMesh);
    CHECK(resolveMethod(BuoyancyMethod::Auto, kDefaultExactMeshMaxTriangles + 1) == BuoyancyMethod::ExactCoverage);
    CHECK(resolveMethod(BuoyancyMethod::TexelCentre, 12) == BuoyancyMethod::TexelCentre);
}

TEST_CASE("integration methods: a prepared shape holds what its method reads, and a pose evaluates to its integral") {
    const TriangleMesh mesh = makeBoxMesh(2.0, 1.0, 1.2);
    PrepareOptions options;
    options.textureSize = 64;
    options.boundsRadius = 0.5 * std::sqrt(2.0 * 2.0 + 1.0 + 1.2 * 1.2);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(0.3, 0.05, -0.2));
    pose.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
    const Eigen::Vector3d reference = pose * Eigen::Vector3d(0.01, -0.02, 0.03);
    const DiagonalSine water;
    const double time = 0.7, rho = 1025.0, g = 9.81;
    for (const IntegrationMethod& m : integrationMethods()) {
        INFO(m.name);
        PreparedShape prepared;
        m.prepare(mesh, options, prepared);
        CHECK(prepared.unitSolid.volume == Approx(2.4).epsilon(m.method == BuoyancyMethod::TexelCentre ? 0.05 : 1e-9));
        CHECK(prepared.unitShell.mass > 0);
        if (m.sampled) {
            REQUIRE(prepared.samples.size() > 0);
            CHECK(prepared.samples.method == m.bake);
            CHECK(prepared.samples.texture_size == options.textureSize);
        } else {
            CHECK(prepared.samples.size() == 0);
            CHECK(prepared.faceSamples.size() >= mesh.triangleCount());
            CHECK(prepared.tree.triangles.size() == mesh.triangleCount());
        }

        SampleWorkspace ws, wsDirect;
        const HydrostaticsResult h = m.evaluate({mesh, prepared.tree, prepared.samples}, pose,
                                                {water, time, rho, g, reference, nullptr, &ws, nullptr});
        const HydrostaticsResult direct =
            m.sampled ? sampledHydrostatics(prepared.samples, pose, water, time, rho, g, reference, wsDirect)
                      : treeHydrostatics(prepared.tree, mesh, pose, water, time, rho, g, reference);
        CHECK(h.submerged_volume > 0);
        CHECK(h.submerged_volume == direct.submerged_volume);
        CHECK(h.centre_of_buoyancy == direct.centre_of_buoyancy);
        CHECK(h.force == direct.force);
        CHECK(h.torque == direct.torque);
        CHECK(h.waterline_area == direct.waterline_area);
        CHECK(h.wetted_area == direct.wetted_area);
    }
}

TEST_CASE("integration methods: a sampled evaluation without a workspace is refused") {
    const IntegrationMethod& m = integrationMethod(BuoyancyMethod::ExactCoverage);
    const TriangleMesh mesh = makeBoxMesh(1.0, 1.0, 1.0);
    PrepareOptions options;
    options.textureSize = 32;
    PreparedShape prepared;
    m.prepare(mesh, options, prepared);
    const DiagonalSine water;
    const Eigen::Vector3d reference = Eigen::Vector3d::Zero();
    CHECK_THROWS_AS(m.evaluate({mesh, prepared.tree, prepared.samples}, Eigen::Isometry3d::Identity(),
                               {water, 0.0, 1000.0, 9.81, reference, nullptr, nullptr, nullptr}),
                    std::invalid_argument);
}
