// Soak (issue 10): many random bodies (shapes, methods, densities, mass models, ballast, drag settings,
// poses, velocities), settings and mass changed on the fly, for many substeps in flat water. After every
// substep every body passes btBuoyancyCheckBody (finite pose and velocities, mass > 0, positive-definite
// inertia), no action ever refuses a non-finite impulse, and the resident memory is flat after warm-up.
// The default run has a short version; the full one (1,000 bodies × 10^5 substeps) is tagged [long]
// (scripts/long-tests.sh).
// TODO(waves): run the same soak in waves (and with water graphs) once a wave btWaterSurface exists.

#include "reliability/ReliabilityWorld.h"

#include "mesh/PrimitiveMeshes.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

using namespace reliability_test;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;  // its quarantine keeps freed memory resident: RSS is not meaningful
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

/// A pool of shapes shared by the bodies (baking is the expensive part; sharing is the intended use).
std::vector<std::shared_ptr<const btBuoyancyShape>> shapePool(std::mt19937& rng) {
    std::uniform_real_distribution<double> size(0.2, 2.5);
    std::vector<std::pair<buoyancy::TriangleMesh, btBuoyancyMethod>> meshes;
    for (int k = 0; k < 3; ++k) meshes.push_back({buoyancy::makeBoxMesh(size(rng), size(rng), size(rng)), btBuoyancyMethod::ExactMesh});
    meshes.push_back({buoyancy::makeBoxMesh(2.0, 0.4, 1.0), btBuoyancyMethod::ExactCoverage});
    meshes.push_back({buoyancy::makeBoxMesh(0.05, 0.05, 3.0), btBuoyancyMethod::TexelCentre});  // a thin rod
    meshes.push_back({buoyancy::makeSphereMesh(0.5 * size(rng), 12, 6), btBuoyancyMethod::ExactMesh});
    meshes.push_back({buoyancy::makeSphereMesh(0.5, 16, 8), btBuoyancyMethod::ExactCoverage});
    meshes.push_back({buoyancy::makeCylinderMesh(0.3, 1.5, 12), btBuoyancyMethod::ExactCoverage});
    meshes.push_back({buoyancy::makeCylinderMesh(0.6, 0.2, 16), btBuoyancyMethod::ExactMesh});
    meshes.push_back({buoyancy::makeTorusMesh(0.6, 0.2, 16, 8), btBuoyancyMethod::ExactMesh});
    meshes.push_back({buoyancy::makeTorusMesh(0.5, 0.15, 12, 6), btBuoyancyMethod::TexelCentre});
    std::vector<std::shared_ptr<const btBuoyancyShape>> pool;
    for (auto& [mesh, method] : meshes) {
        btBuoyancySettings s;
        s.method = method;
        s.textureSize = method == btBuoyancyMethod::ExactMesh ? 0 : 32;
        pool.push_back(btBuoyancyShape::create(mesh, s));
    }
    return pool;
}

btBuoyancySettings randomBuoyancy(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    btBuoyancySettings s;
    s.dragCoefficient = u(rng) < 0.2 ? 0.0 : 2.0 * u(rng);
    s.skinFriction = u(rng) < 0.5 ? 0.0 : 0.02 * u(rng);
    s.linearDamping = u(rng) < 0.2 ? 0.0 : u(rng);
    s.addedMass = u(rng) < 0.8;
    s.addedMassCoefficient = u(rng);
    s.buoyancyEnabled = u(rng) < 0.95;
    return s;
}

btBuoyantBodySettings randomBody(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    btBuoyantBodySettings b;
    b.density = std::exp(std::log(50.0) + u(rng) * std::log(5000.0 / 50.0));  // log-uniform 50..5000 kg/m³
    if (u(rng) < 0.2) {
        b.massModel = btBuoyantMassModel::Shell;
        b.shellThickness = 0.005 + 0.05 * u(rng);
    }
    if (u(rng) < 0.1) b.mass = 1.0 + 500.0 * u(rng);
    const int ballast = u(rng) < 0.3 ? 1 + int(2 * u(rng)) : 0;
    for (int k = 0; k < ballast; ++k)
        b.ballast.push_back({Eigen::Vector3d(u(rng) - 0.5, -u(rng), u(rng) - 0.5), 1.0 + 100.0 * u(rng)});
    b.collision = u(rng) < 0.2 ? btBuoyantCollision::ConvexHull : btBuoyantCollision::None;
    return b;
}

struct SoakResult {
    std::uint64_t substeps = 0;
    std::string violation;
    std::uint64_t rejected = 0;
    std::size_t rssWarm = 0, rssEnd = 0;
    std::size_t nonFinite = 0;
    double seconds = 0;
};

SoakResult soak(int bodies, int substeps, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    ReliabilityWorld w;
    w.addGround(-15);
    const auto pool = shapePool(rng);
    const double half = 2.0 * std::sqrt(double(bodies)) + 2.0;  // ~16 m² per body
    for (int i = 0; i < bodies; ++i) {
        const btVector3 p(btScalar(half * (2 * u(rng) - 1)), btScalar(-4 + 7 * u(rng)), btScalar(half * (2 * u(rng) - 1)));
        const btVector3 axis(btScalar(u(rng) - 0.5), btScalar(u(rng) - 0.5), btScalar(u(rng) - 0.5));
        const std::size_t k = w.add(pool[std::size_t(u(rng) * pool.size()) % pool.size()], randomBody(rng),
                                    pose(p, axis.length() > 1e-3 ? axis : btVector3(0, 1, 0), 360 * u(rng)),
                                    randomBuoyancy(rng));
        w.rigid(k)->setLinearVelocity(btVector3(btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3)));
        w.rigid(k)->setAngularVelocity(btVector3(btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3)));
    }
    const int n = 4;
    const int frames = substeps / n;
    const int warm = std::max(1, frames / 10);
    SoakResult r;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
        w.step(1, n);
        if (f == warm) r.rssWarm = residentBytes();
        // Now and then change a body's settings or its mass on the fly (valid values: must just work).
        if (f % 50 == 25) {
            const std::size_t k = std::size_t(u(rng) * w.size()) % w.size();
            w.action(k).setSettings(randomBuoyancy(rng));
            btBuoyantBody& b = w.body(k);
            const double s = 0.5 + 1.5 * u(rng);
            b.updateMassProperties(b.getMass() * s, b.getMassProperties().centre, b.getMassProperties().inertia * s);
        }
        if (!w.firstViolation().empty()) break;
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.rssEnd = residentBytes();
    r.substeps = w.checkedSubsteps();
    r.violation = w.firstViolation();
    r.rejected = w.rejectedTotal();
    for (std::size_t k = 0; k < w.size(); ++k) {
        const btBuoyancyResult& res = w.action(k).getLastResult();
        const btVector3 sum = res.buoyancyForce + res.dragForce + res.buoyancyTorque + res.dragTorque;
        if (!std::isfinite(sum.x() + sum.y() + sum.z()) || !std::isfinite(res.submergedVolume)) ++r.nonFinite;
    }
    return r;
}

void checkSoak(int bodies, int substeps, std::uint32_t seed) {
    const SoakResult r = soak(bodies, substeps, seed);
    std::printf("soak %d bodies x %d substeps: %.1f s, RSS %.1f -> %.1f MiB after warm-up\n", bodies, substeps,
                r.seconds, r.rssWarm / 1048576.0, r.rssEnd / 1048576.0);
    INFO("first broken invariant: " << r.violation);
    CHECK(r.violation.empty());
    CHECK(r.substeps == std::uint64_t(substeps / 4 * 4));
    CHECK(r.rejected == 0);
    CHECK(r.nonFinite == 0);
    if (!kAddressSanitizer) {
        // Flat memory: no per-substep allocation that is kept (4 MiB + 2 % for allocator noise).
        INFO("RSS after warm-up " << r.rssWarm << " B, at the end " << r.rssEnd << " B");
        CHECK(double(r.rssEnd) <= double(r.rssWarm) * 1.02 + 4.0 * 1048576.0);
    }
}

}  // namespace

TEST_CASE("soak: 50 random bodies, 2,000 substeps, flat water", "[reliability][soak][slow]") { checkSoak(50, 2000, 12345u); }

TEST_CASE("soak: 1,000 random bodies, 100,000 substeps, flat water", "[reliability][soak][long]") {
    checkSoak(1000, 100000, 2024u);
}
