#include "benchmark/OpenClScaling.h"

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btOpenClBuoyancyBackend.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <ostream>
#include <stdexcept>

namespace buoyancy::bench {

namespace {

using Clock = std::chrono::steady_clock;

/// The scaling run's sea (Scaling.cpp): four Gerstner waves, 10–60 m.
std::vector<btGerstnerWave> sea() {
    std::vector<btGerstnerWave> w(4);
    w[0] = {1.0, 60.0, 1.0, 0.0, 0.5, 0.0};
    w[1] = {0.6, 35.0, 0.8, 0.6, 0.5, 1.3};
    w[2] = {0.35, 20.0, -0.3, 1.0, 0.5, 2.1};
    w[3] = {0.2, 10.0, 0.6, -0.8, 0.5, 0.4};
    return w;
}

enum class Backend { Cpu, CpuExact, OpenClDouble, OpenClFloat };

}  // namespace

std::vector<OpenClScalingRow> runOpenClScaling(const TriangleMesh& mesh, const std::string& model,
                                               const OpenClScalingOptions& o, std::ostream& log) {
    std::vector<OpenClScalingRow> rows;
    btBuoyancySettings settings;
    settings.method = btBuoyancyMethod::ExactCoverage;
    settings.textureSize = o.textureSize;
    const auto shape = btBuoyancyShape::create(mesh, settings);
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const double spacing = 4.0 * (hi - lo).maxCoeff();
    const btGerstnerWaterSurface water(sea());
    const double dt = 1.0 / 240.0;
    for (Backend which : {Backend::Cpu, Backend::CpuExact, Backend::OpenClDouble, Backend::OpenClFloat}) {
        btBuoyancySettings s = settings;
        if (which != Backend::Cpu) s.waterPatchNodes = 0;  // exact water queries: the work the device does
        s.hydrostaticsInterval = 1;  // every substep evaluated, as the device does (no temporal level of detail)
        for (int n : o.bodies) {
            btDefaultCollisionConfiguration config;
            btCollisionDispatcher dispatcher(&config);
            btDbvtBroadphase broadphase;
            btSequentialImpulseConstraintSolver solver;
            btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
            world.setGravity(btVector3(0, btScalar(-9.81), 0));
            btBuoyancyWorld buoyancy(&water, 1000.0, 9.81);
            std::string device;
            if (which == Backend::OpenClDouble || which == Backend::OpenClFloat) {
                btOpenClOptions co;
                co.precision = which == Backend::OpenClDouble ? btOpenClOptions::Precision::Double
                                                              : btOpenClOptions::Precision::Float;
                std::string message;
                auto backend = btOpenClBuoyancyBackend::create(buoyancy, co, &message);
                if (!backend) {
                    log << "  opencl scaling: " << message << " (rows skipped)\n";
                    break;
                }
                device = backend->deviceName();
                buoyancy.setDeviceBackend(std::move(backend));
            }
            std::vector<std::unique_ptr<btBuoyantBody>> bodies;
            std::vector<std::unique_ptr<btBuoyancyAction>> actions;
            btBuoyantBodySettings bs;
            bs.density = 500.0;
            const int side = int(std::ceil(std::sqrt(double(n))));
            for (int i = 0; i < n; ++i) {
                btTransform t = btTransform::getIdentity();
                t.setRotation(btQuaternion(btVector3(0, 1, 0), btScalar(0.7 * i)));
                t.setOrigin(btVector3(btScalar(spacing * (i % side)), 0, btScalar(spacing * (i / side))));
                bodies.push_back(std::make_unique<btBuoyantBody>(shape, bs, t));
                world.addRigidBody(bodies.back()->getRigidBody());
                actions.push_back(std::make_unique<btBuoyancyAction>(*bodies.back(), &buoyancy, s));
                world.addAction(actions.back().get());
            }
            world.stepSimulation(btScalar(2 * dt), 2, btScalar(dt));  // untimed: uploads, first launches
            const int perFrame = 4;
            const double substeps = std::max(double(o.minSubsteps), std::min(o.simSeconds / dt, o.maxBodySubsteps / n));
            const long frames = std::max(1L, std::lround(substeps / perFrame));
            const auto t0 = Clock::now();
            for (long f = 0; f < frames; ++f) world.stepSimulation(btScalar(perFrame * dt), perFrame, btScalar(dt));
            const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
            for (auto& a : actions) world.removeAction(a.get());
            for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
            actions.clear();

            OpenClScalingRow r;
            r.backend = which == Backend::Cpu        ? "cpu"
                        : which == Backend::CpuExact ? "cpu-exact"
                        : which == Backend::OpenClDouble ? "opencl-double"
                                                         : "opencl-float";
            r.device = device;
            r.model = model;
            r.samples = int(shape->getSamples().size());
            r.bodies = n;
            r.substeps = frames * perFrame;
            r.wallSeconds = wall;
            r.msPerSubstep = 1e3 * wall / double(r.substeps);
            r.nsPerBodySubstep = 1e9 * wall / (double(n) * double(r.substeps));
            r.realtimeFactor = double(r.substeps) * dt / wall;
            log << "  opencl scaling: " << r.backend << " " << n << " bodies: " << r.msPerSubstep << " ms/substep, "
                << r.nsPerBodySubstep << " ns/body-substep\n";
            rows.push_back(r);
        }
    }
    return rows;
}

void writeOpenClScalingCsv(const std::string& path, const std::vector<OpenClScalingRow>& rows) {
    std::ofstream f(path);
    f << "backend,device,model,samples,bodies,substeps,wall_s,ms_per_substep,ns_per_body_substep,realtime_factor\n";
    for (const auto& r : rows)
        f << r.backend << ",\"" << r.device << "\"," << r.model << ',' << r.samples << ',' << r.bodies << ','
          << r.substeps << ',' << r.wallSeconds << ',' << r.msPerSubstep << ',' << r.nsPerBodySubstep << ','
          << r.realtimeFactor << '\n';
    if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace buoyancy::bench
