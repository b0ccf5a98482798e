// Bodies in waves: the horizontal pressure push on a slope (against the exact divergence-theorem
// result), a small buoy following a long Gerstner wave, and the interactive grid's volume conservation
// and ring speed.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>
#include <BulletBuoyancy/bullet/btInteractiveWaterCoupler.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

namespace {
constexpr double kPi = 3.14159265358979323846;

/// A Bullet world with one water surface and buoyant bodies.
struct WaveWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btBuoyancyWorld water;
    std::vector<std::unique_ptr<btBuoyantBody>> bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> actions;
    explicit WaveWorld(const btWaterSurface* s) : water(s, 1000.0, 9.81) { world.setGravity(btVector3(0, -9.81, 0)); }
    ~WaveWorld() {
        for (auto& a : actions) world.removeAction(a.get());
        for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
    }
    btRigidBody* add(buoyancy::TriangleMesh mesh, double density, const btVector3& pos) {
        btBuoyancySettings settings;
        settings.textureSize = 64;  // small and fast: these tests are about the water, not the sampling
        auto shape = btBuoyancyShape::create(std::move(mesh), settings);
        btBuoyantBodySettings bs;
        bs.density = density;
        btTransform t;
        t.setIdentity();
        t.setOrigin(pos);
        bodies.push_back(std::make_unique<btBuoyantBody>(shape, bs, t));
        world.addRigidBody(bodies.back()->getRigidBody());
        actions.push_back(std::make_unique<btBuoyancyAction>(*bodies.back(), &water));
        world.addAction(actions.back().get());
        return bodies.back()->getRigidBody();
    }
};
}  // namespace

TEST_CASE("waves: a body on a sloped surface gets the horizontal pressure push", "[water][physics]") {
    // Planar slope f = s·x (a bilinear grid of a plane is that plane). With p = ρ g (f − y) and p = 0 on
    // the water surface, the divergence theorem gives F = −∫∇p dV = ρ g V_sub (−∂f/∂x, 1, −∂f/∂z):
    // a push down the slope of −s times the lift, which Archimedes (vertical only) misses.
    const double slope = 0.15;
    std::vector<double> hs(4);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) hs[j * 2 + i] = slope * (-50.0 + i * 100.0);
    btGridWaterSurface plane(2, 2, 100.0, -50.0, -50.0, hs, false);
    const buoyancy::TriangleMesh box = buoyancy::makeBoxMesh(1.0, 0.6, 0.8);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(0.2, 0.05, -0.1);
    pose.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, 0.4).normalized()));
    const auto exact = buoyancy::clippedHydrostatics(box, pose, plane, 0.0, 1000.0, 9.81, pose.translation());
    REQUIRE(exact.force.y() > 0);
    CHECK(exact.force.x() / exact.force.y() == Approx(-slope).margin(1e-9));
    CHECK(exact.force.z() / exact.force.y() == Approx(0.0).margin(1e-9));
    CHECK(exact.force.y() == Approx(1000.0 * 9.81 * exact.submerged_volume).epsilon(1e-9));
    // The sampled (default) method gives the same push to its waterline error.
    auto shape = btBuoyancyShape::create(box);
    if (shape->getSamples().size() > 0) {
        buoyancy::SampleWorkspace ws;
        const auto sampled = buoyancy::sampledHydrostatics(shape->getSamples(), pose, plane, 0.0, 1000.0, 9.81,
                                                           pose.translation(), ws);
        CHECK(sampled.force.x() / sampled.force.y() == Approx(-slope).margin(5e-3));
    }
    // In a long Gerstner wave the push follows the local slope of the surface (curvature: a few %).
    btGerstnerWaterSurface wave({{0.4, 60.0, 1.0, 0.0, 0.5, 0.0}}, 0.0);
    const double t = 0.0, x = 60.0 / 4 * 0.8;  // on the flank
    const double e = 1e-4, dfdx = (wave.height(x + e, 0, t) - wave.height(x - e, 0, t)) / (2 * e);
    Eigen::Isometry3d p2 = Eigen::Isometry3d::Identity();
    p2.translation() = Eigen::Vector3d(x, wave.height(x, 0, t), 0);
    const auto w = buoyancy::clippedHydrostatics(box, p2, wave, t, 1000.0, 9.81, p2.translation());
    INFO("slope " << dfdx << ", Fx/Fy " << w.force.x() / w.force.y());
    REQUIRE(std::abs(dfdx) > 0.01);
    CHECK(w.force.x() / w.force.y() == Approx(-dfdx).epsilon(0.05));
}

TEST_CASE("waves: a small buoy follows a long Gerstner wave", "[water][physics][slow]") {
    // λ = 40 m (period 5.06 s), A = 0.5 m; a 0.3 m sphere of density 500: heave amplitude ≈ A.
    const double A = 0.5, lambda = 40.0;
    btGerstnerWaterSurface sea({{A, lambda, 1.0, 0.0, 0.5, 0.0}}, 0.0);
    WaveWorld w(&sea);
    btRigidBody* rb = w.add(buoyancy::makeSphereMesh(0.15, 32, 16), 500.0, btVector3(0, A, 0));
    const double dt = 1.0 / 120.0, period = std::sqrt(2 * kPi * lambda / 9.81);
    double lo = 1e9, hi = -1e9, t = 0;
    while (t < 4 * period) {
        w.world.stepSimulation(btScalar(2 * dt), 2, btScalar(dt));
        t += 2 * dt;
        if (t > 2 * period) {
            lo = std::min(lo, double(rb->getCenterOfMassPosition().y()));
            hi = std::max(hi, double(rb->getCenterOfMassPosition().y()));
        }
    }
    const double amp = 0.5 * (hi - lo);
    INFO("heave amplitude " << amp << " m for a wave amplitude " << A << " m");
    CHECK(amp == Approx(A).epsilon(0.15));
    CHECK(std::isfinite(rb->getCenterOfMassPosition().x()));
}

TEST_CASE("interactive water: volume conserved, rings travel at the wave speed", "[water][interactive]") {
    SECTION("an impulse makes a ring moving at c") {
        btInteractiveWaterSurface g(20.0, 20.0, 200, 2.0, 0.0);
        g.addVolumeChange(0.0, 0.0, 0.05, 0.2);
        const double v0 = g.waterVolume();
        CHECK(v0 == Approx(0.0).margin(1e-15));
        const double T = 3.0;
        for (int i = 0; i < 300; ++i) g.step(T / 300);
        CHECK(g.waterVolume() == Approx(0.0).margin(1e-12));
        // The leading edge (outermost |η| above 5 % of the largest) along +x is near r₀ + c T = 6.6 m: the
        // volume starts in a ring of outer radius r₀ = 0.2 + 2 dx + max(2 dx, 0.2/2) = 0.6 m (dx = 0.1 m,
        // btInteractiveWaterSurface::addVolumeChange).
        double peak = 0, rBest = 0;
        for (int i = g.cellsX() / 2; i < g.cellsX(); ++i) peak = std::max(peak, std::abs(g.cellHeight(i, g.cellsZ() / 2)));
        for (int i = g.cellsX() / 2; i < g.cellsX(); ++i)
            if (std::abs(g.cellHeight(i, g.cellsZ() / 2)) > 0.05 * peak) rBest = (i + 0.5) * g.cellSize() - 10.0;
        INFO("front at " << rBest << " m, expected ~6.6 m");
        CHECK(rBest == Approx(6.6).margin(0.6));
    }
    SECTION("a dropped buoy disturbs the water; water volume conserved; rings reach a neighbour") {
        btInteractiveWaterSurface water(12.0, 12.0, 96, 2.0, 0.1);
        WaveWorld w(&water);
        btRigidBody* drop = w.add(buoyancy::makeBoxMesh(0.8, 0.4, 0.8), 400.0, btVector3(0, 0.6, 0));
        btRigidBody* neighbour = w.add(buoyancy::makeBoxMesh(0.6, 0.3, 0.6), 500.0, btVector3(3.0, 0.0, 0));
        btInteractiveWaterCoupler coupler(&water, &w.water);
        w.world.addAction(&coupler);
        const double dt = 1.0 / 240.0;
        double worstVolume = 0, maxNeighbourSpeed = 0, maxEta = 0, meanDisplaced = 0;
        for (int f = 0; f < 480; ++f) {  // 8 s: the dropped box has settled
            w.world.stepSimulation(btScalar(4 * dt), 4, btScalar(dt));
            worstVolume = std::max(worstVolume, std::abs(water.waterVolume()));
            maxNeighbourSpeed = std::max(maxNeighbourSpeed, double(neighbour->getLinearVelocity().length()));
            double lo, hi;
            water.heightBounds(0, 0, 0, 0, 0, lo, hi);
            maxEta = std::max(maxEta, std::max(hi, -lo));
            if (f >= 360) meanDisplaced += coupler.displacedVolume() / 120.0;  // the last 2 s
        }
        w.world.removeAction(&coupler);
        INFO("worst |water volume| " << worstVolume << " m^3, displaced " << coupler.displacedVolume()
                                     << " m^3, max |eta| " << maxEta << " m, neighbour speed " << maxNeighbourSpeed);
        // The water the bodies displace is moved, never created: Σ(η − h)A stays 0 to rounding.
        CHECK(worstVolume <= 1e-9);
        // Displaced volumes equal the bodies' weights / (ρ g) once they float (Archimedes): on average over the last
        // 2 s, since the bodies still bob ±5 % in the waves they made.
        const double floating = (0.8 * 0.4 * 0.8 * 400.0 + 0.6 * 0.3 * 0.6 * 500.0) / 1000.0;
        INFO("mean displaced over the last 2 s " << meanDisplaced << " m^3");
        CHECK(meanDisplaced == Approx(floating).epsilon(0.03));
        CHECK(maxEta > 1e-3);              // the drop made waves
        CHECK(maxNeighbourSpeed > 1e-3);   // which rocked the other body
        CHECK(std::isfinite(drop->getCenterOfMassPosition().y()));
    }
}
