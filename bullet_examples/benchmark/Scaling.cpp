#include "benchmark/Scaling.h"

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/water/btWaterSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#ifdef BUOYANCY_BENCH_OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <stdexcept>

namespace buoyancy::bench {

namespace {

using Clock = std::chrono::steady_clock;

/// The benchmark's own driver (`bench` rows, kept for comparison with the library's threads): runs every body's
/// btBuoyancyAction once per substep, across OpenMP threads, from one Bullet action. The first action runs alone: it
/// advances the shared water clock (btBuoyancyWorld::beginSubstepIfNew); the others then only read it and
/// touch their own body, so they can run concurrently. Below 9 bodies the loop stays on one thread (an idle
/// OpenMP worker spin-waiting between substeps would only steal the main thread's core). Chunks of 16 bodies are
/// handed out as threads free up: with the temporal level of detail a body costs ≈ 40 µs at an exact evaluation and
/// a few µs when predicted, so equal static halves left one thread waiting (measured at 1,000 boats: 1.64× from the
/// second thread with schedule(static), 1.88× with dynamic chunks of 16).
class ParallelBuoyancy : public btActionInterface {
public:
    std::vector<btBuoyancyAction*> actions;
    double seconds = 0;
    void updateAction(btCollisionWorld* world, btScalar dt) override {
        const auto t0 = Clock::now();
        if (!actions.empty()) actions[0]->updateAction(world, dt);
        const int n = int(actions.size());
#ifdef BUOYANCY_BENCH_OPENMP
#pragma omp parallel for schedule(dynamic, 16) if (n > 8)
#endif
        for (int i = 1; i < n; ++i) actions[i]->updateAction(world, dt);
        seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    }
    void debugDraw(btIDebugDraw*) override {}
};

/// Observers of the `world` driver (they drive nothing): the first action of the world notes the time, the last one
/// adds the time since, so `seconds` is the time spent in the buoyancy actions (the library's parallel evaluation at
/// the first of them, then each applying its impulses).
struct BuoyancyClock {
    Clock::time_point start;
    double seconds = 0;
};
class ClockStart : public btActionInterface {
public:
    explicit ClockStart(BuoyancyClock& c) : m_clock(c) {}
    void updateAction(btCollisionWorld*, btScalar) override { m_clock.start = Clock::now(); }
    void debugDraw(btIDebugDraw*) override {}

private:
    BuoyancyClock& m_clock;
};
class ClockStop : public btActionInterface {
public:
    ClockStop(BuoyancyClock& c, const std::vector<std::unique_ptr<btBuoyancyAction>>& actions)
        : m_clock(c), m_actions(actions) {}
    void updateAction(btCollisionWorld*, btScalar) override {
        m_clock.seconds += std::chrono::duration<double>(Clock::now() - m_clock.start).count();
        // Outside the timed span: how many bodies predicted this substep (the temporal level of detail's share).
        for (const auto& a : m_actions) m_predicted += a->getLastResult().predicted ? 1 : 0;
        m_bodySubsteps += long(m_actions.size());
    }
    void debugDraw(btIDebugDraw*) override {}
    /// Predicted body-substeps / body-substeps since the last reset (0 when none).
    double predictedShare() const { return m_bodySubsteps > 0 ? double(m_predicted) / double(m_bodySubsteps) : 0.0; }
    void reset() { m_predicted = m_bodySubsteps = 0; }

private:
    BuoyancyClock& m_clock;
    const std::vector<std::unique_ptr<btBuoyancyAction>>& m_actions;
    long m_predicted = 0, m_bodySubsteps = 0;
};

/// The machine's 1-minute load average (/proc/loadavg; −1 where there is none): runs on a loaded machine are slower.
double loadAverage() {
    double load = -1;
    if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf", &load) != 1) load = -1;
        std::fclose(f);
    }
    return load;
}

}  // namespace

std::vector<btGerstnerWave> p3Sea() {
    std::vector<btGerstnerWave> w(4);
    w[0] = {1.0, 60.0, 1.0, 0.0, 0.5, 0.0};
    w[1] = {0.6, 35.0, 0.8, 0.6, 0.5, 1.3};
    w[2] = {0.35, 20.0, -0.3, 1.0, 0.5, 2.1};
    w[3] = {0.2, 10.0, 0.6, -0.8, 0.5, 0.4};
    return w;
}

namespace {
std::vector<btGerstnerWave> sea() { return p3Sea(); }

/// The scaling sea without its third-derivative scale: the exact-mesh default then models the water over each triangle
/// as the plane through its corners' heights (the model before the curved-water default), still with the wave patch.
class PlaneGerstnerWaterSurface : public btGerstnerWaterSurface {
public:
    using btGerstnerWaterSurface::btGerstnerWaterSurface;
    double heightThirdDerivativeScale(double) const override { return 0.0; }
};

}  // namespace

double floatingHeight(const TriangleMesh& mesh, double volume, double densityRatio) {
    double lo = 1e300, hi = -1e300;
    for (const auto& v : mesh.vertices) {
        lo = std::min(lo, v.y());
        hi = std::max(hi, v.y());
    }
    const btFlatWaterSurface flat(0.0);
    double a = -hi, b = -lo;  // origin heights: fully under (V_sub = V) … fully above (0)
    for (int i = 0; i < 60; ++i) {
        const double y = 0.5 * (a + b);
        const Eigen::Isometry3d pose(Eigen::Translation3d(0, y, 0));
        const double v = clippedHydrostatics(mesh, pose, flat, 0.0, 1000.0, 9.81, Eigen::Vector3d::Zero()).submerged_volume;
        (v > densityRatio * volume ? a : b) = y;
    }
    return 0.5 * (a + b);
}

bool scalingHasOpenMP() {
#ifdef BUOYANCY_BENCH_OPENMP
    return true;
#else
    return false;
#endif
}

std::vector<ScalingRow> runScaling(const TriangleMesh& mesh, const std::string& model, const ScalingOptions& o,
                                   std::ostream& log) {
    std::vector<ScalingRow> rows;
    const auto shape = btBuoyancyShape::create(mesh, o.settings);  // the library's default settings unless told
    const std::string method = std::string(btBuoyancyMethodName(shape->getMethod())) +
                               (shape->getMethod() == btBuoyancyMethod::ExactMesh ? "" : "-" + std::to_string(shape->getTextureSize()));
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const double spacing = 4.0 * (hi - lo).maxCoeff();  // four body lengths
    const double density = 500.0;
    const double floating = floatingHeight(mesh, shape->getUnitSolid().volume, density / 1000.0);
    const btGerstnerWaterSurface curvedWater(sea());
    const PlaneGerstnerWaterSurface planeWater(sea());
    const btGerstnerWaterSurface& water = o.planeWater ? planeWater : curvedWater;
    const double dt = 1.0 / o.substepsPerSecond;
    for (const std::string& driver : o.drivers) {
    if (driver != "world" && driver != "bench") throw std::invalid_argument("scaling: unknown driver '" + driver + "'");
    const bool viaWorld = driver == "world";
    for (int threads : o.threads) {
        if (!viaWorld && threads > 1 && !scalingHasOpenMP()) {
            log << "  scaling: " << threads << " threads skipped (built without OpenMP)\n";
            continue;
        }
#ifdef BUOYANCY_BENCH_OPENMP
        if (!viaWorld) omp_set_num_threads(threads);
#endif
        for (int n : o.bodies) {
            btDefaultCollisionConfiguration config;
            btCollisionDispatcher dispatcher(&config);
            btDbvtBroadphase broadphase;
            btSequentialImpulseConstraintSolver solver;
            btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
            world.setGravity(btVector3(0, btScalar(-9.81), 0));
            // `world`: the user's code (README): the context of the world, its threads, one action per body in the
            // world. `bench`: the context without the world, the actions run by the benchmark's OpenMP action.
            std::unique_ptr<btBuoyancyWorld> context = viaWorld ? std::make_unique<btBuoyancyWorld>(&world, &water, 1000.0)
                                                                : std::make_unique<btBuoyancyWorld>(&water, 1000.0, 9.81);
            if (viaWorld) context->setThreads(threads);
            btBuoyancyWorld& buoyancy = *context;
            std::vector<std::unique_ptr<btBuoyantBody>> bodies;
            std::vector<std::unique_ptr<btBuoyancyAction>> actions;
            ParallelBuoyancy batch;
            BuoyancyClock clock;
            ClockStart clockStart(clock);
            ClockStop clockStop(clock, actions);
            if (viaWorld) world.addAction(&clockStart);
            btBuoyantBodySettings bs;
            bs.density = density;
            const int side = int(std::ceil(std::sqrt(double(n))));
            for (int i = 0; i < n; ++i) {
                btTransform t = btTransform::getIdentity();
                const double yaw = 0.7 * i;  // varied headings
                t.setRotation(btQuaternion(btVector3(0, 1, 0), btScalar(yaw)));
                // Floating on the local water surface (not at the mean level, where the 4 m swell would drop or bury
                // them): the draft of flat-water equilibrium below the local height.
                const double x = spacing * (i % side), z = spacing * (i / side);
                t.setOrigin(btVector3(btScalar(x), btScalar(water.height(x, z, 0.0) + floating), btScalar(z)));
                bodies.push_back(std::make_unique<btBuoyantBody>(shape, bs, t));
                world.addRigidBody(bodies.back()->getRigidBody());
                actions.push_back(std::make_unique<btBuoyancyAction>(*bodies.back(), &buoyancy, o.settings));
                if (viaWorld)
                    world.addAction(actions.back().get());
                else
                    batch.actions.push_back(actions.back().get());
            }
            if (viaWorld)
                world.addAction(&clockStop);
            else
                world.addAction(&batch);
            const int perFrame = 4;  // 60 frames/s × 4 substeps
            // Untimed warm-up (warmupSeconds): the bodies settle from their starting pose into the waves, and the
            // temporal level of detail has the exact evaluations it extrapolates from before the clock starts.
            const long warmupFrames = std::max(1L, std::lround(o.warmupSeconds / (perFrame * dt)));
            for (long f = 0; f < warmupFrames; ++f) world.stepSimulation(btScalar(perFrame * dt), perFrame, btScalar(dt));
            const double substeps = std::max(double(o.minSubsteps), std::min(o.simSeconds / dt, o.maxBodySubsteps / n));
            const long frames = std::max(1L, std::lround(substeps / perFrame));
            struct Window {
                double wall, buoyancy;
                long contacts;
                double predictedShare;
            };
            std::vector<Window> windows;
            for (int k = 0; k < std::max(1, o.windows); ++k) {
                batch.seconds = 0;
                clock.seconds = 0;
                clockStop.reset();
                long contacts = 0;
                const auto t0 = Clock::now();
                for (long f = 0; f < frames; ++f) {
                    world.stepSimulation(btScalar(perFrame * dt), perFrame, btScalar(dt));
                    for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
                        if (dispatcher.getManifoldByIndexInternal(m)->getNumContacts() > 0) ++contacts;
                }
                const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
                windows.push_back({wall, viaWorld ? clock.seconds : batch.seconds, contacts,
                                   viaWorld ? clockStop.predictedShare() : -1.0});
            }
            if (viaWorld) {
                world.removeAction(&clockStart);
                world.removeAction(&clockStop);
                for (auto& a : actions) world.removeAction(a.get());
            } else {
                world.removeAction(&batch);
            }
            for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
            actions.clear();
            std::vector<Window> sorted = windows;
            std::sort(sorted.begin(), sorted.end(), [](const Window& a, const Window& b) { return a.wall < b.wall; });
            const Window& median = sorted[sorted.size() / 2];

            ScalingRow r;
            r.model = model;
            r.triangles = mesh.triangleCount();
            r.method = method;
            r.variant = o.variant;
            r.driver = driver;
            r.bodies = n;
            r.threads = viaWorld ? buoyancy.getThreads() : threads;
            r.substeps = frames * perFrame;
            r.simSeconds = double(r.substeps) * dt;
            r.wallSeconds = median.wall;
            r.buoyancySeconds = median.buoyancy;
            r.realtimeFactor = r.simSeconds / median.wall;
            r.windows = int(windows.size());
            r.realtimeFactorMin = r.simSeconds / sorted.back().wall;
            r.realtimeFactorMax = r.simSeconds / sorted.front().wall;
            r.nsPerBodySubstepTotal = 1e9 * median.wall / (double(n) * double(r.substeps));
            r.nsPerBodySubstepBuoyancy = 1e9 * median.buoyancy / (double(n) * double(r.substeps));
            r.contacts = median.contacts;
            r.predictedShare = median.predictedShare;
            r.loadAverage = loadAverage();
            rows.push_back(r);
            log << "  scaling " << model << (o.variant.empty() ? "" : " [" + o.variant + "]") << " driver " << driver
                << " x" << n << ", " << r.threads << " thread(s): " << r.nsPerBodySubstepTotal
                << " ns/body-substep total, " << r.nsPerBodySubstepBuoyancy << " buoyancy; real-time factor "
                << r.realtimeFactor << " (median of " << r.windows << ")";
            if (r.predictedShare >= 0) log << ", " << 100 * r.predictedShare << " % of body-substeps predicted";
            log << ", load average " << loadAverage() << "\n";
        }
    }
    }
    return rows;
}

std::string scalingBreakdownMarkdown(const TriangleMesh& mesh, std::ostream& log) {
    const btGerstnerWaterSurface water(sea());
    const std::size_t n = 16384;
    std::vector<double> x(n), y(n), z(n), h(n), u(n), v(n), w(n);
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = 0.37 * double(i % 128);
        z[i] = 0.53 * double(i / 128);
        y[i] = -0.5;
    }
    auto timeIt = [&](auto&& f) {
        double best = 1e300;
        for (int r = 0; r < 5; ++r) {
            const auto t0 = Clock::now();
            f();
            best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
        }
        return 1e9 * best / double(n);
    };
    const double nsH = timeIt([&] { water.heights(x.data(), z.data(), n, 1.0, h.data()); });
    const double nsV = timeIt([&] { water.velocities(x.data(), y.data(), z.data(), n, 1.0, u.data(), v.data(), w.data()); });
    const auto shape = btBuoyancyShape::create(mesh);
    const bool exact = shape->getMethod() == btBuoyancyMethod::ExactMesh;
    const btBuoyancySettings st;  // the library defaults, as in the run
    const std::size_t points = exact ? mesh.vertices.size() : shape->getSamples().size();
    const std::size_t fineDrag = shape->getDragSamples().size();
    // With the default level of detail (design.md 2.5) a body-substep on Gerstner waves queries the heights at
    // the waterPatchNodes² grid nodes (vertices, samples and drag clusters are interpolated from it) and the
    // velocities at waterVelocityProbes probes; without it (no-lod), one height query per vertex/sample and per
    // fine drag sample, one velocity query per fine drag sample.
    const int patchNodes =
        btBuoyancyWaterPatchNodes(st, shape->getBoundsRadius(), btGerstnerWaterSurface(sea()).shortestWavelength());
    const double heightQueries = double(patchNodes) * patchNodes;
    const double velocityQueries = double(st.waterVelocityProbes);
    const double oldHeights = double(points) + double(fineDrag), oldVelocities = double(fineDrag);
    char b[1200];
    std::snprintf(b, sizeof b,
                  "- Where the time goes (scaling model, %s): the 4-wave Gerstner sea costs %.0f ns per height query and "
                  "%.0f ns per velocity query (batches of 16384, one thread). Per body-substep the default level of detail "
                  "makes %.0f height queries (a %d×%d patch) and %.0f velocity queries (probes): ≈ %.0f µs of water queries; "
                  "without it (no-lod rows) %.0f height queries (%zu %s + %zu drag samples) and %.0f velocity queries: "
                  "≈ %.0f µs. Budget for 1,000 bodies in real time: ≈ 7 µs of buoyancy per body-substep on 2 cores.\n",
                  btBuoyancyMethodName(shape->getMethod()), nsH, nsV, heightQueries, patchNodes, patchNodes,
                  velocityQueries, (heightQueries * nsH + velocityQueries * nsV) / 1000.0, oldHeights, points,
                  exact ? "mesh vertices" : "samples", fineDrag, oldVelocities, (oldHeights * nsH + oldVelocities * nsV) / 1000.0);
    log << "  " << b;
    return b;
}

void writeScalingCsv(const std::string& path, const std::vector<ScalingRow>& rows) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "model,triangles,method,variant,driver,bodies,threads,substeps,sim_seconds,wall_seconds,buoyancy_seconds,"
                    "realtime_factor,windows,realtime_factor_min,realtime_factor_max,ns_per_body_substep_total,"
                    "ns_per_body_substep_buoyancy,ns_per_body_substep_bullet,contact_manifolds,predicted_share,"
                    "load_average\n");
    for (const ScalingRow& r : rows)
        std::fprintf(f, "%s,%zu,%s,%s,%s,%d,%d,%ld,%.4f,%.4f,%.4f,%.4g,%d,%.4g,%.4g,%.1f,%.1f,%.1f,%ld,%.4f,%.2f\n", r.model.c_str(),
                     r.triangles, r.method.c_str(), r.variant.c_str(), r.driver.c_str(), r.bodies, r.threads, r.substeps,
                     r.simSeconds, r.wallSeconds, r.buoyancySeconds, r.realtimeFactor, r.windows, r.realtimeFactorMin,
                     r.realtimeFactorMax, r.nsPerBodySubstepTotal, r.nsPerBodySubstepBuoyancy,
                     r.nsPerBodySubstepTotal - r.nsPerBodySubstepBuoyancy, r.contacts, r.predictedShare, r.loadAverage);
    if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + path);
}

}  // namespace buoyancy::bench
