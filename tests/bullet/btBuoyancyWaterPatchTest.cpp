// The per-body height patch is chosen by what the surface says of its queries (btWaterSurface::prefersHeightPatch),
// not by its type: the same waves behind a wrapper that says yes or no. Counted: the height queries of one substep.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <atomic>
#include <memory>

namespace {

// A new wave model, as a user would write one: here it answers with a Gerstner surface's heights and counts them.
class CountingWaves : public btWaterSurface {
public:
    CountingWaves(const btGerstnerWaterSurface& waves, bool prefersPatch) : m_waves(waves), m_prefersPatch(prefersPatch) {}
    void heights(const double* x, const double* z, std::size_t n, double t, double* out) const override {
        m_count += n;
        m_waves.heights(x, z, n, t, out);
    }
    void velocities(const double* x, const double* y, const double* z, std::size_t n, double t, double* vx, double* vy,
                    double* vz) const override {
        m_waves.velocities(x, y, z, n, t, vx, vy, vz);
    }
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& lo,
                      double& hi) const override {
        m_waves.heightBounds(minX, minZ, maxX, maxZ, t, lo, hi);
    }
    bool isTimeVarying() const override { return true; }
    double shortestWavelength() const override { return m_waves.shortestWavelength(); }
    bool prefersHeightPatch() const override { return m_prefersPatch; }
    std::size_t count() const { return m_count; }

private:
    const btGerstnerWaterSurface& m_waves;
    bool m_prefersPatch;
    mutable std::atomic<std::size_t> m_count{0};
};

std::size_t heightQueriesOfOneSubstep(bool prefersPatch) {
    btGerstnerWave wave;
    wave.amplitude = 0.1;
    wave.wavelength = 20.0;
    const btGerstnerWaterSurface waves({wave}, 0.0, 9.81);
    CountingWaves water(waves, prefersPatch);
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, btScalar(-9.81), 0));
    btBuoyancyWorld buoyancy(&world, &water, 1000.0);
    // A finely tessellated body (a sphere of 4,000 triangles) across the waterline: many more vertices than patch nodes.
    auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(1.0, 64, 32));
    btSphereShape collision{btScalar(1.0)};
    btRigidBody body(btRigidBody::btRigidBodyConstructionInfo(500, nullptr, &collision, btVector3(200, 200, 200)));
    world.addRigidBody(&body);
    btBuoyancySettings settings;
    settings.dragCoefficient = 0;
    settings.skinFriction = 0;
    settings.linearDamping = 0;
    settings.hydrostaticsInterval = 1;
    btBuoyancyAction action(&body, shape, &buoyancy, settings);
    world.addAction(&action);
    world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
    world.removeAction(&action);
    world.removeRigidBody(&body);
    REQUIRE(action.getLastResult().submergedVolume > 0.5);
    return water.count();
}

}  // namespace

TEST_CASE("water patch: a surface that prefers it gets the per-body height patch whatever its type", "[bullet][water]") {
    const std::size_t withPatch = heightQueriesOfOneSubstep(true);
    const std::size_t exact = heightQueriesOfOneSubstep(false);
    INFO("height queries in one substep: " << withPatch << " with the patch, " << exact << " without");
    CHECK(withPatch * 4 < exact);  // a grid of nodes against one query per vertex (≈ 2,000)
}

TEST_CASE("water patch: the library's surfaces say whether they prefer it", "[bullet][water]") {
    btGerstnerWave wave;
    wave.amplitude = 0.1;
    wave.wavelength = 20.0;
    CHECK(btGerstnerWaterSurface({wave}, 0.0, 9.81).prefersHeightPatch());  // Newton's inversion per query
    CHECK_FALSE(btGerstnerWaterSurface({}, 0.0, 9.81).prefersHeightPatch()); // flat: no waves to invert
    CHECK_FALSE(btFlatWaterSurface(0.0).prefersHeightPatch());
}
