// Soak: many random bodies (shapes, methods, densities, mass models, ballast, drag settings,
// poses, velocities), some holding a water graph that floods through permeable regions, settings and mass
// changed on the fly, for many substeps in Gerstner waves. After every substep every body passes
// btBuoyancyCheckBody (finite pose and velocities, mass > 0, positive-definite inertia), no action ever
// refuses a non-finite impulse, the water in every graph stays finite and conserved, and the resident
// memory is flat after warm-up (sampled every 1 % of the run). The default run has a short version; the full one
// (1,000 bodies × 10^5 substeps) is tagged [long] (scripts/long-tests.sh).

#include "reliability/ReliabilityHelpers.h"

#include <BulletBuoyancy/graph/WaterIngress.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

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
    s.addedMassWaterplaneCoefficient = 0.4 * u(rng);
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

/// Random Gerstner waves: 2–3 trains, A 0.2–1 m, λ 15–60 m, Q 0.2–0.8, any direction (Σ Q A k ≤ 0.8 < 1).
std::vector<btGerstnerWave> randomWaves(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<btGerstnerWave> waves(2 + std::size_t(u(rng) < 0.5));
    for (btGerstnerWave& w : waves) {
        w.amplitude = 0.2 + 0.8 * u(rng);
        w.wavelength = 15 + 45 * u(rng);
        const double a = 2 * M_PI * u(rng);
        w.directionX = std::cos(a);
        w.directionZ = std::sin(a);
        w.steepness = 0.2 + 0.6 * u(rng);
        w.phase = 2 * M_PI * u(rng);
    }
    double loop = 0;
    for (const btGerstnerWave& w : waves) loop += w.steepness * w.amplitude * 2 * M_PI / w.wavelength;
    for (btGerstnerWave& w : waves) w.steepness *= std::min(1.0, 0.8 / loop);
    return waves;
}

/// A water graph of 1–3 nodes inside the shape's bounds (capacity 40 % of its volume, some water already in)
/// with a permeable region around a random surface sample.
std::pair<buoyancy::WaterGraph, buoyancy::PermeableSamples> randomFlooding(std::mt19937& rng, const btBuoyancyShape& shape) {
    std::uniform_real_distribution<double> u(0, 1);
    buoyancy::WaterGraph g;
    g.seed = rng();
    g.flow = u(rng) < 0.7 ? buoyancy::WaterFlowModel::Poiseuille : buoyancy::WaterFlowModel::Diffusion;
    g.ingress = u(rng) < 0.8 ? buoyancy::WaterIngressModel::Orifice : buoyancy::WaterIngressModel::Paper;
    const int n = 1 + int(3 * u(rng)) % 3;
    const double r = shape.getBoundsRadius();
    for (int k = 0; k < n; ++k) {
        buoyancy::WaterNode node;
        node.name = "n" + std::to_string(k);
        node.position = shape.getBoundsCentre() + 0.2 * r * Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        node.capacity = 0.4 * shape.getVolume() / n;
        node.water = u(rng) * 0.5 * node.capacity;
        g.nodes.push_back(node);
        if (k > 0) {
            buoyancy::WaterEdge e;
            e.from = k - 1;
            e.to = k;
            e.radius = 0.02 + 0.05 * u(rng);
            e.length = 0.2 + r * u(rng);
            g.edges.push_back(e);
        }
    }
    const buoyancy::SurfaceSamples& samples = shape.getDragSamples();  // per-face samples for exact-mesh (as the scene runner)
    const std::size_t at = std::size_t(u(rng) * samples.size()) % samples.size();
    buoyancy::PermeabilityRegion region;
    region.centre = Eigen::Vector3d(samples.px[at], samples.py[at], samples.pz[at]);
    region.radius = (0.1 + 0.4 * u(rng)) * r;
    region.value = 0.05 + 0.95 * u(rng);
    return {g, buoyancy::permeableSamplesFromRegions(samples, {region}, g)};
}

struct SoakResult {
    std::uint64_t substeps = 0;
    std::string violation;
    std::uint64_t rejected = 0;
    std::size_t rssWarm = 0, rssMax = 0, rssEnd = 0;
    std::size_t nonFinite = 0;
    std::size_t flooded = 0;     ///< bodies with a water graph
    double waterIn = 0;          ///< Σ water in the graphs at the end, m³
    double worstLedger = 0;      ///< worst |Σ water − initial − (entered − drained)| / capacity over the graphs
    double seconds = 0;
};

SoakResult soak(int bodies, int substeps, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const btGerstnerWaterSurface sea(randomWaves(rng));
    CheckedWorld w(&sea);
    w.addGround(-15);
    const auto pool = shapePool(rng);
    const double half = 2.0 * std::sqrt(double(bodies)) + 2.0;  // ~16 m² per body
    std::vector<btFloodingAction*> flooding;
    for (int i = 0; i < bodies; ++i) {
        const btVector3 p(btScalar(half * (2 * u(rng) - 1)), btScalar(-4 + 7 * u(rng)), btScalar(half * (2 * u(rng) - 1)));
        const btVector3 axis(btScalar(u(rng) - 0.5), btScalar(u(rng) - 0.5), btScalar(u(rng) - 0.5));
        const auto& shape = pool[std::size_t(u(rng) * pool.size()) % pool.size()];
        const std::size_t k = w.add(shape, randomBody(rng),
                                    makePose(p, axis.length() > 1e-3 ? axis : btVector3(0, 1, 0), 360 * u(rng)),
                                    randomBuoyancy(rng));
        w.rigid(k)->setLinearVelocity(btVector3(btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3)));
        w.rigid(k)->setAngularVelocity(btVector3(btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3), btScalar(6 * u(rng) - 3)));
        if (u(rng) < 0.15) {  // some bodies hold water (a fixed body cannot: none are fixed here)
            auto [graph, holes] = randomFlooding(rng, *shape);
            flooding.push_back(&w.addFlooding(k, std::move(graph), std::move(holes)));
        } else {
            flooding.push_back(nullptr);
        }
    }
    const int n = 4;
    const int frames = substeps / n;
    const int warm = std::max(1, frames / 10);
    SoakResult r;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
        w.step(1, n);
        if (f == warm) r.rssWarm = r.rssMax = residentBytes();
        if (f > 0 && f % std::max(1, frames / 100) == 0) {  // every 1 %: progress, and RSS after warm-up
            const std::size_t rss = residentBytes();
            if (f > warm) r.rssMax = std::max(r.rssMax, rss);
            std::printf("  soak frame %d/%d: %.0f s, RSS %.1f MiB%s\n", f, frames,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), rss / 1048576.0,
                        f > warm ? "" : " (warm-up)");
            std::fflush(stdout);
        }
        // Now and then change a body's settings or its mass on the fly (valid values: must just work; a
        // flooded body's dry mass goes through its flooding action, which composes it with the water).
        if (f % 50 == 25) {
            const std::size_t k = std::size_t(u(rng) * w.size()) % w.size();
            w.action(k).setSettings(randomBuoyancy(rng));
            const double s = 0.5 + 1.5 * u(rng);
            if (flooding[k]) {
                buoyancy::MassProperties dry = flooding[k]->getDryMassProperties();
                dry.mass *= s;
                dry.inertia *= s;
                flooding[k]->setDryMassProperties(dry);
            } else {
                btBuoyantBody& b = w.body(k);
                b.updateMassProperties(b.getMass() * s, b.getMassProperties().centre, b.getMassProperties().inertia * s);
            }
        }
        if (!w.firstViolation().empty()) break;
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.rssEnd = residentBytes();
    r.rssMax = std::max(r.rssMax, r.rssEnd);
    r.substeps = w.checkedSubsteps();
    r.violation = w.firstViolation();
    r.rejected = w.rejectedTotal();
    for (std::size_t k = 0; k < w.size(); ++k) {
        const btBuoyancyResult& res = w.action(k).getLastResult();
        const btVector3 sum = res.buoyancyForce + res.dragForce + res.buoyancyTorque + res.dragTorque;
        if (!std::isfinite(sum.x() + sum.y() + sum.z()) || !std::isfinite(res.submergedVolume)) ++r.nonFinite;
        if (!flooding[k]) continue;
        const buoyancy::WaterGraphState& st = flooding[k]->getState();
        ++r.flooded;
        r.waterIn += st.totalWater();
        const double ledger = st.totalWater() - st.initialVolume() - (st.enteredVolume() - st.drainedVolume());
        r.worstLedger = std::max(r.worstLedger, std::abs(ledger) / st.graph().totalCapacity());
        if (!std::isfinite(st.totalWater())) ++r.nonFinite;
    }
    return r;
}

void checkSoak(int bodies, int substeps, std::uint32_t seed) {
    const SoakResult r = soak(bodies, substeps, seed);
    std::printf("soak %d bodies (%zu with water graphs) x %d substeps in Gerstner waves: %.1f s, RSS %.1f MiB after "
                "warm-up, max %.1f, end %.1f; water in graphs %.3f m^3, worst ledger error %.2e of capacity\n",
                bodies, r.flooded, substeps, r.seconds, r.rssWarm / 1048576.0, r.rssMax / 1048576.0,
                r.rssEnd / 1048576.0, r.waterIn, r.worstLedger);
    INFO("first broken invariant: " << r.violation);
    CHECK(r.violation.empty());
    CHECK(r.substeps == std::uint64_t(substeps / 4 * 4));
    CHECK(r.rejected == 0);
    CHECK(r.nonFinite == 0);
    CHECK(r.flooded > 0);
    CHECK(r.worstLedger < 1e-9);  // WaterGraphState: conservation exact to rounding
    if (!kAddressSanitizer) {
        // Flat memory: no per-substep allocation that is kept (4 MiB + 2 % for allocator noise).
        INFO("RSS after warm-up " << r.rssWarm << " B, largest sample " << r.rssMax << " B");
        CHECK(double(r.rssMax) <= double(r.rssWarm) * 1.02 + 4.0 * 1048576.0);
    }
}

}  // namespace

TEST_CASE("soak: 100 random bodies, 2,000 substeps, Gerstner waves and water graphs", "[reliability][soak][slow]") {
    checkSoak(100, 2000, 12345u);
}

TEST_CASE("soak: 1,000 random bodies, 100,000 substeps, Gerstner waves and water graphs", "[reliability][soak][long]") {
    checkSoak(1000, 100000, 2024u);
}
