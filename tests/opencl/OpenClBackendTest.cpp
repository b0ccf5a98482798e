// OpenCL backend against the CPU path: the same bodies at identical states give the same per-substep
// forces (1e-9 of the weight scale in double, 1e-4 in float), in one batched launch for all bodies, on flat
// water with a current, Gerstner waves, a height grid and a sampled FFT ocean; the selection falls back to the
// CPU with a message, never a crash. Every test skips with a WARN when no OpenCL device exists.
#include "OpenClTestSupport.h"

#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>
#include <BulletBuoyancy/water/btRiverSurface.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace buoyancy_test;

namespace {

constexpr double kDt = 1.0 / 240.0;
#ifdef BT_USE_DOUBLE_PRECISION
constexpr bool kBulletDouble = true;
#else
constexpr bool kBulletDouble = false;
#endif

btBuoyancySettings sampled(int n) {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactCoverage;
    s.textureSize = n;
    s.waterPatchNodes = 0;  // exact water queries on the CPU too (the device always queries exactly)
    s.skinFriction = 0.005; // every drag term in use
    s.hydrostaticsInterval = 1;  // every substep evaluated on the CPU too, as the device does
    return s;
}

/// Several shapes (two bodies share one shape), tilted, moving and spinning, half in the water at y ≈ 0.
struct Scene {
    std::vector<double> volumes, lengths;
    /// @param coarse  32² textures everywhere (the trajectory test: 720 substeps)
    void populate(BulletTestWorld& w, bool coarse = false) {
        const btBuoyancySettings s64 = sampled(coarse ? 32 : 64), s128 = sampled(coarse ? 32 : 128);
        auto box = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 0.5, 1.0), s64);
        auto ball = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.5, 32, 16), s128);
        auto torus = btBuoyancyShape::create(buoyancy::makeTorusMesh(0.6, 0.2, 32, 16), s128);
        auto can = btBuoyancyShape::create(buoyancy::makeCylinderMesh(0.3, 1.2, 24), s64);
        btBuoyantBodySettings body;
        body.density = 600;
        struct Item {
            std::shared_ptr<const btBuoyancyShape> shape;
            btTransform pose;
            btVector3 v, w;
            double length;
        };
        const Item items[] = {
            {box, makePose(btVector3(0, 0.05, 0), btVector3(1, 0, 1), 20), btVector3(0.3, -0.2, 0.1), btVector3(0.2, 0.5, -0.3), 2.3},
            {ball, makePose(btVector3(3, 0.1, 1), btVector3(0, 0, 1), 0), btVector3(-0.5, 0.4, 0), btVector3(1, 0, 0.5), 1.0},
            {torus, makePose(btVector3(-3, -0.05, 2), btVector3(1, 0, 0), 60), btVector3(0, 0, 0.7), btVector3(0, 2, 0), 1.6},
            {can, makePose(btVector3(6, 0.2, -2), btVector3(0, 0, 1), 35), btVector3(0.1, 0.1, 0.1), btVector3(-0.4, 0.3, 0.9), 1.3},
            {box, makePose(btVector3(-6, -0.1, -3), btVector3(0, 1, 1), 45), btVector3(0, -1, 0), btVector3(0, 0, 0), 2.3},
        };
        for (const Item& it : items) {
            const std::size_t i = w.add(it.shape, body, it.pose, s64);
            w.rigid(i)->setLinearVelocity(it.v);
            w.rigid(i)->setAngularVelocity(it.w);
            volumes.push_back(it.shape->getVolume());
            lengths.push_back(it.length);
        }
    }
};

/// Compare CPU and device for every body of `w` over a few substeps (the bodies move between them).
void compareWorld(BulletTestWorld& w, btOpenClBuoyancyBackend& backend, const Scene& scene, double tolerance,
                  const char* label) {
    double worst = 0, worstHydro = 0;
    std::uint64_t answers = 0;
    for (int step = 0; step < 4; ++step) {
        std::vector<btBuoyancyResult> cpu, dev;
        std::uint64_t answered = 0;
        evaluateBoth(w.world(), w.water(), backend, kDt, cpu, dev, answered);
        answers += answered;
        for (std::size_t i = 0; i < cpu.size(); ++i) {
            const double weight = 1000 * 9.81 * scene.volumes[i];
            const double d = resultDifference(cpu[i], dev[i], weight, scene.lengths[i], scene.volumes[i]);
            worst = std::max(worst, d);
            REQUIRE(dev[i].applied == cpu[i].applied);
            // The double hydrostatics straight from both paths (no rounding to btScalar on the way).
            btBuoyancyAction& a = w.action(i);
            const Eigen::Isometry3d pose = buoyancy::toEigen(a.getRigidBody()->getWorldTransform() * a.getMeshInComFrame());
            const Eigen::Vector3d com = buoyancy::toEigen(a.getRigidBody()->getCenterOfMassPosition());
            buoyancy::SampleWorkspace ws;
            const buoyancy::HydrostaticsResult hc = buoyancy::sampledHydrostatics(
                a.getSamplesInUse(), pose, *w.water().getWater(), w.water().getTime(), 1000, w.water().getGravity(), com, ws);
            buoyancy::HydrostaticsResult hd;
            if (backend.hydrostatics(a, pose, com, hd)) {
                worstHydro = std::max(worstHydro, std::abs(hc.submerged_volume - hd.submerged_volume) / scene.volumes[i]);
                worstHydro = std::max(worstHydro, (hc.force - hd.force).norm() / weight);
                worstHydro = std::max(worstHydro, (hc.torque - hd.torque).norm() / (weight * scene.lengths[i]));
            }
        }
        w.step(1, 1, kDt);  // move on (the device is installed: Bullet's own substep runs through it)
    }
    // Results go through btScalar: in a float Bullet build they carry float rounding (≈ 6e-8 of the value).
    const double resultTolerance = kBulletDouble ? tolerance : std::max(tolerance, 1e-6);
    std::printf("[opencl] %s: %s, worst |CPU - device| %.3g (results), %.3g (double hydrostatics), %llu answers\n",
                label, backend.describe().c_str(), worst, worstHydro, (unsigned long long)answers);
    CHECK(answers >= 4 * 4);  // every wet body was answered by the device (at least 4 of 5 are wet)
    CHECK(worst <= resultTolerance);
    CHECK(worstHydro <= tolerance);
}

}  // namespace

TEST_CASE("OpenCL: selection reports the device, falls back to the CPU with a message", "[opencl]") {
    BulletTestWorld w;
    std::string message;
    if (btOpenClBuoyancyBackend::compiledIn() && deviceTestsDisabled()) return;
    if (!btOpenClBuoyancyBackend::compiledIn()) {
        CHECK_FALSE(w.water().setCompute(btBuoyancyCompute::OpenCl, &message));
        CHECK(message.find("built without OpenCL") != std::string::npos);
        CHECK(w.water().getCompute() == btBuoyancyCompute::Cpu);
        return;
    }
    if (!w.water().setCompute(btBuoyancyCompute::OpenCl, &message)) {
        WARN("OpenCL test skipped: " << message);
        CHECK(w.water().getCompute() == btBuoyancyCompute::Cpu);
        return;
    }
    CHECK(w.water().getCompute() == btBuoyancyCompute::OpenCl);
    CHECK(message.rfind("OpenCL: ", 0) == 0);
    CHECK((message.find("double") != std::string::npos || message.find("float") != std::string::npos));
    // A device that does not exist: nullptr and the reason, the world keeps its backend.
    btOpenClOptions o;
    o.deviceIndex = 999;
    CHECK(btOpenClBuoyancyBackend::create(w.water(), o, &message) == nullptr);
    CHECK(message.find("device 999 asked") != std::string::npos);
    CHECK(message.find("CPU path") != std::string::npos);
    o = btOpenClOptions();
    ::setenv("BULLET_BUOYANCY_OPENCL_DEVICE", "gpu", 1);
    CHECK(btOpenClBuoyancyBackend::create(w.water(), o, &message) == nullptr);
    ::unsetenv("BULLET_BUOYANCY_OPENCL_DEVICE");
    CHECK(message.find("'gpu' is not a device number") != std::string::npos);
    o.tileSamples = 10;
    CHECK(btOpenClBuoyancyBackend::create(w.water(), o, &message) == nullptr);
    CHECK(message.find("tileSamples") != std::string::npos);
    CHECK(w.water().getCompute() == btBuoyancyCompute::OpenCl);
    CHECK(w.water().setCompute(btBuoyancyCompute::Cpu, &message));
    CHECK(w.water().getCompute() == btBuoyancyCompute::Cpu);
}

TEST_CASE("OpenCL double: per-substep forces of 5 bodies in one batch match the CPU to 1e-9 (flat water, current)",
          "[opencl]") {
    btFlatWaterSurface flat(0.0, 0.4, -0.2);
    BulletTestWorld w(&flat);
    Scene scene;
    scene.populate(w);
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
    if (!backend) return;
    REQUIRE(backend->usesDouble());
    const auto before = backend->stats();
    compareWorld(w, *backend, scene, 1e-9, "flat water, double");
    // One hydrostatic launch set per substep for all bodies, not one per body.
    const auto after = backend->stats();
    CHECK(after.hydroBatches - before.hydroBatches <= 3 * 4);  // per step: CPU run (paused), device run, Bullet's substep
    CHECK(after.bodiesComputed - before.bodiesComputed >= 4 * (after.hydroBatches - before.hydroBatches));
    CHECK(backend->lastFallbackReason().empty());
}

TEST_CASE("OpenCL double: Gerstner waves evaluated on the device match the CPU to 1e-9", "[opencl]") {
    std::vector<btGerstnerWave> waves(2);
    waves[0].amplitude = 0.3;
    waves[0].wavelength = 12;
    waves[0].steepness = 0.6;
    waves[1].amplitude = 0.1;
    waves[1].wavelength = 5;
    waves[1].directionX = 0.3;
    waves[1].directionZ = 1;
    waves[1].steepness = 0.5;
    waves[1].phase = 1;
    btGerstnerWaterSurface sea(waves, 0.0);
    BulletTestWorld w(&sea);
    w.water().setTime(3.7);
    Scene scene;
    scene.populate(w);
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
    if (!backend) return;
    compareWorld(w, *backend, scene, 1e-9, "Gerstner, double");
}

TEST_CASE("OpenCL float: per-substep forces match the CPU to 1e-4 of the weight scale", "[opencl]") {
    std::vector<btGerstnerWave> waves(1);
    waves[0].amplitude = 0.25;
    waves[0].wavelength = 10;
    btGerstnerWaterSurface sea(waves, 0.0);
    BulletTestWorld w(&sea);
    Scene scene;
    scene.populate(w);
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Float);
    if (!backend) return;
    REQUIRE_FALSE(backend->usesDouble());
    compareWorld(w, *backend, scene, 1e-4, "Gerstner, float");
}

TEST_CASE("OpenCL double: height grid and sampled FFT ocean uploaded as buffers match the CPU", "[opencl]") {
    // A periodic grid with a velocity field (drag on the device too).
    const int nx = 24, nz = 20;
    std::vector<double> h(nx * nz), vx(nx * nz), vy(nx * nz), vz(nx * nz);
    for (int j = 0; j < nz; ++j)
        for (int i = 0; i < nx; ++i) {
            h[j * nx + i] = 0.15 * std::sin(0.7 * i) * std::cos(0.4 * j);
            vx[j * nx + i] = 0.2 * std::cos(0.3 * j);
            vy[j * nx + i] = 0.05 * std::sin(0.5 * i);
            vz[j * nx + i] = -0.1;
        }
    btGridWaterSurface grid(nx, nz, 0.5, -6.0, -5.0, h, true);
    grid.setVelocities(vx, vy, vz);
    {
        BulletTestWorld w(&grid);
        Scene scene;
        scene.populate(w);
        btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
        if (!backend) return;
        compareWorld(w, *backend, scene, 1e-9, "grid, double");
    }
    btFftOceanSettings fs;
    fs.resolution = 32;
    fs.patchSize = 16;
    fs.windSpeed = 6;
    btFftOceanSurface fft(fs);
    BulletTestWorld w(&fft);
    w.water().setTime(2.0);
    Scene scene;
    scene.populate(w);
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
    if (!backend) return;
    compareWorld(w, *backend, scene, 1e-9, "FFT (hydrostatics on the device, drag on the CPU), double");
}

namespace {
/// A surface type the device does not know: its bodies must run on the CPU path.
class TiltedPlane : public btWaterSurface {
public:
    void heights(const double* x, const double* z, std::size_t n, double, double* out) const override {
        for (std::size_t i = 0; i < n; ++i) out[i] = 0.02 * x[i] - 0.01 * z[i];
    }
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double, double& lo, double& hi) const override {
        lo = 0.02 * minX - 0.01 * maxZ;
        hi = 0.02 * maxX - 0.01 * minZ;
    }
};
}  // namespace

namespace {
/// A world on `water` whose surface the device must decline: no body answered by the device, a fallback reason that
/// contains `reason`, and the CPU's forces.
void checkFallsBackToCpu(const btWaterSurface& water, const char* reason) {
    BulletTestWorld w(&water);
    Scene scene;
    scene.populate(w);
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Auto);
    if (!backend) return;
    std::vector<btBuoyancyResult> cpu, dev;
    std::uint64_t answered = 0;
    evaluateBoth(w.world(), w.water(), *backend, kDt, cpu, dev, answered);
    CHECK(answered == 0);
    CHECK(backend->lastFallbackReason().find(reason) != std::string::npos);
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        CHECK(cpu[i].buoyancyForce == dev[i].buoyancyForce);
        CHECK(cpu[i].dragForce == dev[i].dragForce);
    }
}
}  // namespace

TEST_CASE("OpenCL: an unknown water surface type falls back to the CPU with a reason, same results", "[opencl]") {
    TiltedPlane plane;
    checkFallsBackToCpu(plane, "not evaluated on the device");
}

namespace {
/// A user's own surface class (none of the library's) that describes itself for the device as a height grid: the
/// tilted plane 0.02 x − 0.01 z sampled every 0.5 m over [−16, 16]², whose bilinear interpolation is the plane itself.
class DescribedPlane : public TiltedPlane {
public:
    bool describeForDevice(double, btWaterDeviceDescription& out) const override {
        out.kind = btWaterDeviceDescription::Kind::HeightGrid;
        out.sizeX = out.sizeZ = 65;
        out.spacing = 0.5;
        out.originX = out.originZ = -16.0;
        out.periodic = false;
        out.heights.resize(65 * 65);
        for (int j = 0; j < 65; ++j)
            for (int i = 0; i < 65; ++i) out.heights[std::size_t(j * 65 + i)] = 0.02 * (-16.0 + 0.5 * i) - 0.01 * (-16.0 + 0.5 * j);
        out.velocityX.clear();
        out.velocityY.clear();
        out.velocityZ.clear();
        out.velocityOnDevice = true;  // still water, as its CPU queries say
        return true;
    }
};
/// A user's surface whose description is inconsistent (fewer heights than its grid has samples).
class BadlyDescribedPlane : public DescribedPlane {
public:
    bool describeForDevice(double t, btWaterDeviceDescription& out) const override {
        DescribedPlane::describeForDevice(t, out);
        out.heights.resize(100);
        return true;
    }
};
}  // namespace

TEST_CASE("OpenCL: a user's surface that describes itself as a height grid is evaluated on the device", "[opencl]") {
    DescribedPlane plane;
    BulletTestWorld w(&plane);
    Scene scene;
    scene.populate(w);
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
    if (!backend) return;
    std::vector<btBuoyancyResult> cpu, dev;
    std::uint64_t answered = 0;
    evaluateBoth(w.world(), w.water(), *backend, kDt, cpu, dev, answered);
    CHECK(answered > 0);
    CHECK(backend->lastFallbackReason().empty());
    compareWorld(w, *backend, scene, 1e-9, "a described user surface, double");
}

TEST_CASE("OpenCL: an inconsistent height-grid description falls back to the CPU and says why", "[opencl]") {
    BadlyDescribedPlane plane;
    checkFallsBackToCpu(plane, "height-grid description is inconsistent");
}

TEST_CASE("OpenCL: a river is not taken for uniform flat water: it falls back to the CPU with a reason", "[opencl]") {
    // The river is flat (isFlat) but its current varies with position: it does not describe itself as one of the
    // device's kinds (flat water there has one uniform current), so its bodies stay on the CPU path, with the CPU's
    // forces.
    btRiverSettings rs;
    rs.centreline = {{-10.0, -1.0}, {0.0, 0.0}, {10.0, 3.0}};
    rs.width = 6.0;
    rs.surfaceSpeed = 1.2;
    const btRiverSurface river(rs);
    checkFallsBackToCpu(river, "not evaluated on the device");
}

TEST_CASE("OpenCL double: trajectories stay close to the CPU's over 3 s of waves", "[opencl][slow]") {
    std::vector<btGerstnerWave> waves(1);
    waves[0].amplitude = 0.2;
    waves[0].wavelength = 8;
    btGerstnerWaterSurface sea(waves, 0.0);
    BulletTestWorld cpu(&sea), dev(&sea);
    Scene a, b;
    a.populate(cpu, true);
    b.populate(dev, true);
    btOpenClBuoyancyBackend* backend = installTestBackend(dev.water(), btOpenClOptions::Precision::Double);
    if (!backend) return;
    double worst = 0;
    for (int frame = 0; frame < 180; ++frame) {  // 3 s at 60 Hz, 4 substeps each
        cpu.step(1);
        dev.step(1);
        for (std::size_t i = 0; i < cpu.size(); ++i)
            worst = std::max(worst, double((cpu.rigid(i)->getCenterOfMassPosition() -
                                            dev.rigid(i)->getCenterOfMassPosition()).length()));
    }
    std::printf("[opencl] trajectories over 3 s, 5 bodies: worst COM distance CPU vs device %.3g m (%s Bullet)\n", worst,
                kBulletDouble ? "double" : "float");
    CHECK(backend->stats().hydroAnswers > 0);
    // Double Bullet: the device's rounding differences (1e-13 of the forces) stay far below a micrometre. Float
    // Bullet rounds every pose to float (6e-8 m per metre), and a 1-ulp difference grows through contacts-free
    // floating dynamics only slowly.
    CHECK(worst <= (kBulletDouble ? 1e-6 : 1e-3));
}

TEST_CASE("OpenCL: a whole scene turned to an oblique gravity (water frame) gives the CPU's results", "[opencl][upaxis]") {
    // The backend evaluates every body in the water frame, as the action does: the same bodies, gravity and frame
    // turned by one rotation (and shifted) must give the CPU's per-substep results (1e-9 of the weight scale in double).
    btFlatWaterSurface flat(0.0, 0.4, -0.2);  // the current is along the frame's horizontal axes
    BulletTestWorld w(&flat);
    Scene scene;
    scene.populate(w);
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
    const Eigen::Vector3d o(1.0, -2.0, 0.5);
    w.world().setGravity(buoyancy::toBullet(Eigen::Vector3d(Q * Eigen::Vector3d(0, -9.81, 0))));
    w.water().setWaterFrame(btWaterFrame(o, Eigen::Vector3d(Q.col(1)), Eigen::Vector3d(Q.col(0))));
    Eigen::Isometry3d map = Eigen::Isometry3d::Identity();
    map.linear() = Q;
    map.translation() = o;
    for (std::size_t i = 0; i < w.size(); ++i) {
        btRigidBody* b = w.rigid(i);
        b->setCenterOfMassTransform(buoyancy::toBullet(Eigen::Isometry3d(map * buoyancy::toEigen(b->getCenterOfMassTransform()))));
        b->setLinearVelocity(buoyancy::toBullet(Eigen::Vector3d(Q * buoyancy::toEigen(b->getLinearVelocity()))));
        b->setAngularVelocity(buoyancy::toBullet(Eigen::Vector3d(Q * buoyancy::toEigen(b->getAngularVelocity()))));
    }
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
    if (!backend) return;
    double worst = 0;
    std::uint64_t answers = 0;
    for (int step = 0; step < 4; ++step) {
        std::vector<btBuoyancyResult> cpu, dev;
        std::uint64_t answered = 0;
        evaluateBoth(w.world(), w.water(), *backend, kDt, cpu, dev, answered);
        answers += answered;
        for (std::size_t i = 0; i < cpu.size(); ++i) {
            REQUIRE(cpu[i].status == btBuoyancyStatus::Ok);
            REQUIRE(dev[i].applied == cpu[i].applied);
            worst = std::max(worst, resultDifference(cpu[i], dev[i], 1000 * 9.81 * scene.volumes[i], scene.lengths[i],
                                                     scene.volumes[i]));
        }
        w.step(1, 1, kDt);
    }
    std::printf("[opencl] oblique water frame: worst |CPU - device| %.3g, %llu answers\n", worst,
                (unsigned long long)answers);
    CHECK(answers >= 4 * 4);  // the device answered (it did not decline the turned bodies)
    CHECK(worst <= (kBulletDouble ? 1e-9 : 1e-6));
    // And a wet body is wet in the turned world too: its buoyancy points up the frame.
    const btBuoyancyResult& r = w.action(0).getLastResult();
    CHECK(buoyancy::toEigen(r.buoyancyForce).normalized().dot(Q.col(1)) > 0.5);
}
