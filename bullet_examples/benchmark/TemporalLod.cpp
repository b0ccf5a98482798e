#include "benchmark/TemporalLod.h"

#include "benchmark/Scaling.h"
#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace buoyancy::bench {

namespace {
using Clock = std::chrono::steady_clock;

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

/// A Bullet world (its four usual parts) with gravity −g ŷ.
struct BulletWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    explicit BulletWorld(double g) { world.setGravity(btVector3(0, btScalar(-g), 0)); }
};

/// One undamped body (exact-mesh, drag, damping and added mass off; `settings`' temporal level of detail kept) of
/// density ρ_w·ratio in flat water at 0, released level with its mesh origin at `height`, stepped at 240 substeps/s.
struct UndampedBody {
    static constexpr double kDt = 1.0 / 240.0;  ///< substep, s
    BulletWorld bullet{9.81};
    btFlatWaterSurface flat{0.0};
    btBuoyancyWorld buoyancy{&flat, 1000.0, 9.81};
    std::unique_ptr<btBuoyantBody> body;
    std::unique_ptr<btBuoyancyAction> action;
    UndampedBody(const TriangleMesh& mesh, double ratio, double height, btBuoyancySettings settings) {
        settings.method = btBuoyancyMethod::ExactMesh;
        settings.dragCoefficient = 0;
        settings.linearDamping = 0;
        settings.radiationDamping = 0;
        settings.skinFriction = 0;
        settings.addedMass = false;
        btBuoyantBodySettings bs;
        bs.density = 1000.0 * ratio;
        btTransform t = btTransform::getIdentity();
        t.setOrigin(btVector3(0, btScalar(height), 0));
        body = std::make_unique<btBuoyantBody>(btBuoyancyShape::create(mesh, settings), bs, t);
        bullet.world.addRigidBody(body->getRigidBody());
        action = std::make_unique<btBuoyancyAction>(*body, &buoyancy, settings);
        bullet.world.addAction(action.get());
    }
    ~UndampedBody() {
        bullet.world.removeAction(action.get());
        bullet.world.removeRigidBody(body->getRigidBody());
    }
    void step() { bullet.world.stepSimulation(btScalar(kDt), 1, btScalar(kDt)); }
};

/// Worst energy drift of an undamped bobbing box over `seconds` at 240 substeps/s, % of its energy above rest.
double energyDriftPct(const btBuoyancySettings& settings, double seconds) {
    const double a = 2, c = 1, b = 2, s = 0.5, rho = 1000, g = 9.81, dt = UndampedBody::kDt;
    const double yEq = c / 2 - s * c;
    UndampedBody u(makeBoxMesh(a, c, b), s, yEq - 0.1, settings);
    btRigidBody* rb = u.body->getRigidBody();
    const double m = 1.0 / double(rb->getInvMass());
    // Mechanical energy: kinetic (the velocity at the current pose: the mean of Bullet's stored v, which holds this
    // substep's buoyancy kick, and v + g dt) + gravity + buoyancy potential ρ g A d²/2 (wall-sided, 0 < d < c).
    auto energy = [&]() {
        const btBuoyancyResult& r = u.action->getLastResult();
        const btVector3 v = rb->getLinearVelocity() +
                            btScalar(0.5 * dt) * (rb->getGravity() - r.buoyancyForce * rb->getInvMass());
        const double y = double(rb->getCenterOfMassPosition().y());
        const double d = c / 2 - y;
        return 0.5 * m * double(v.length2()) + m * g * y + 0.5 * rho * g * a * b * d * d;
    };
    const double dRest = s * c;
    const double eRest = m * g * (c / 2 - dRest) + 0.5 * rho * g * a * b * dRest * dRest;
    u.step();
    const double e0 = energy() - eRest;
    double worst = 0;
    for (long k = 0; k < std::lround(seconds / dt); ++k) {
        u.step();
        worst = std::max(worst, std::abs(energy() - eRest - e0));
    }
    return 100.0 * worst / e0;
}

/// An undamped bobbing sphere (R 0.5 m, 48 × 24, density ratio 0.5, released 0.15 m below equilibrium, 240
/// substeps/s): its heave amplitude over the last 5 s of `seconds` against the first 5 s, % change (a sphere's
/// waterline changes with its draft, so unlike the wall-sided box its restoring force is not linear).
double sphereAmplitudeChangePct(const btBuoyancySettings& settings, double seconds) {
    UndampedBody u(makeSphereMesh(0.5, 48, 24), 0.5, -0.15, settings);
    const long n = std::lround(seconds / UndampedBody::kDt), window = std::lround(5.0 / UndampedBody::kDt);
    double lo1 = 1e300, hi1 = -1e300, lo2 = 1e300, hi2 = -1e300;
    for (long k = 0; k < n; ++k) {
        u.step();
        const double y = double(u.body->getRigidBody()->getCenterOfMassPosition().y());
        if (k < window) lo1 = std::min(lo1, y), hi1 = std::max(hi1, y);
        if (k >= n - window) lo2 = std::min(lo2, y), hi2 = std::max(hi2, y);
    }
    return 100.0 * ((hi2 - lo2) / (hi1 - lo1) - 1.0);
}
}  // namespace

std::vector<TemporalLodRow> runTemporalLod(const TriangleMesh& mesh, const std::string& model,
                                           const TemporalLodOptions& o, std::ostream& log) {
    std::vector<TemporalLodRow> rows;
    const btGerstnerWaterSurface water(p3Sea());
    const double dt = 1.0 / 240.0;
    const double rho = 1000.0, g = 9.81;
    // interval, tolerance, bodies, settle and measured seconds, placed as in the scaling run
    std::vector<std::tuple<int, double, int, double, double, bool>> runs;
    for (const auto& [interval, tolerance] : o.configurations)
        runs.emplace_back(interval, tolerance, o.bodies, o.settleSeconds, o.seconds, false);
    if (o.fleetBodies > 0) runs.emplace_back(0, 0.0, o.fleetBodies, o.fleetSettleSeconds, o.fleetSeconds, true);
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    for (const auto& [interval, tolerance, bodyCount, settleSeconds, seconds, asScalingRun] : runs) {
        btBuoyancySettings settings;
        settings.hydrostaticsInterval = interval;
        if (tolerance > 0) settings.hydrostaticsReuseTolerance = tolerance;
        const auto shape = btBuoyancyShape::create(mesh, settings);
        BulletWorld bullet(g);
        btDiscreteDynamicsWorld& world = bullet.world;
        btBuoyancyWorld buoyancy(&water, rho, g);
        btBuoyantBodySettings bs;
        bs.density = 500.0;
        std::vector<std::unique_ptr<btBuoyantBody>> bodies;
        std::vector<std::unique_ptr<btBuoyancyAction>> actions;
        const double spacing = 4.0 * (hi - lo).maxCoeff();  // the scaling run's layout: four body lengths
        const double floating = asScalingRun ? floatingHeight(mesh, shape->getUnitSolid().volume, bs.density / rho) : 0.0;
        const int side = int(std::ceil(std::sqrt(double(bodyCount))));
        for (int i = 0; i < bodyCount; ++i) {
            btTransform t = btTransform::getIdentity();
            t.setRotation(btQuaternion(btVector3(0, 1, 0), btScalar(0.7 * i)));
            if (asScalingRun) {
                const double x = spacing * (i % side), z = spacing * (i / side);
                t.setOrigin(btVector3(btScalar(x), btScalar(water.height(x, z, 0.0) + floating), btScalar(z)));
            } else {
                t.setOrigin(btVector3(btScalar(17.0 * i), 0, btScalar(5.0 * i)));
            }
            bodies.push_back(std::make_unique<btBuoyantBody>(shape, bs, t));
            world.addRigidBody(bodies.back()->getRigidBody());
            actions.push_back(std::make_unique<btBuoyancyAction>(*bodies.back(), &buoyancy, settings));
            world.addAction(actions.back().get());
        }
        const long settle = std::lround(settleSeconds / dt), measured = std::lround(seconds / dt);
        for (long n = 0; n < settle; ++n) world.stepSimulation(btScalar(dt), 1, btScalar(dt));
        const double scale = rho * g * shape->getUnitSolid().volume;
        const double diameter = 2.0 * shape->getBoundsRadius();
        std::vector<double> forceErrors;
        double torqueMax = 0, wall = 0;
        long predicted = 0;
        for (long n = 0; n < measured; ++n) {
            const auto t0 = Clock::now();
            world.stepSimulation(btScalar(dt), 1, btScalar(dt));
            wall += std::chrono::duration<double>(Clock::now() - t0).count();
            for (std::size_t i = 0; i < actions.size(); ++i) {
                const btBuoyancyResult& r = actions[i]->getLastResult();
                if (r.predicted) ++predicted;
                const btRigidBody* rb = bodies[i]->getRigidBody();
                const Eigen::Isometry3d pose = toEigen(rb->getWorldTransform() * actions[i]->getMeshInComFrame());
                const Eigen::Vector3d com = toEigen(rb->getCenterOfMassPosition());
                const HydrostaticsResult exact = clippedHydrostatics(shape->getMesh(), pose, water, r.time, rho, g, com);
                forceErrors.push_back((toEigen(r.buoyancyForce) - exact.force).norm() / scale);
                torqueMax = std::max(torqueMax, (toEigen(r.buoyancyTorque) - exact.torque).norm() / (scale * diameter));
            }
        }
        for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
        for (auto& a : actions) world.removeAction(a.get());
        std::sort(forceErrors.begin(), forceErrors.end());
        double sum = 0;
        for (double e : forceErrors) sum += e;
        TemporalLodRow row;
        row.model = model;
        row.triangles = mesh.triangleCount();
        row.interval = interval;
        row.tolerance = settings.hydrostaticsReuseTolerance;
        row.energyDriftPct = energyDriftPct(settings, o.energySeconds);
        row.sphereAmplitudeChangePct = sphereAmplitudeChangePct(settings, o.energySeconds);
        row.resolvedInterval = interval > 0 ? interval : btBuoyancyAutomaticInterval(dt);
        row.bodies = bodyCount;
        const double count = double(std::max<std::size_t>(forceErrors.size(), 1));
        row.predictedPct = 100.0 * double(predicted) / count;
        row.nsPerBodySubstep = 1e9 * wall / (double(bodyCount) * double(std::max(measured, 1L)));
        row.forceErrorMeanPct = 100.0 * sum / count;
        row.forceErrorP99Pct = forceErrors.empty() ? 0 : 100.0 * forceErrors[forceErrors.size() * 99 / 100];
        row.forceErrorMaxPct = forceErrors.empty() ? 0 : 100.0 * forceErrors.back();
        row.torqueErrorMaxPct = 100.0 * torqueMax;
        log << "  temporal lod " << model << " x" << bodyCount << " interval " << interval << " tolerance " << row.tolerance
            << " (K = " << row.resolvedInterval
            << "): " << fmt("%.0f", row.nsPerBodySubstep) << " ns/body-substep, predicted " << fmt("%.1f", row.predictedPct)
            << " %, force error mean " << fmt("%.5f", row.forceErrorMeanPct) << " % p99 " << fmt("%.5f", row.forceErrorP99Pct)
            << " % max " << fmt("%.5f", row.forceErrorMaxPct) << " %; undamped box energy drift "
            << fmt("%.3f", row.energyDriftPct) << " %, undamped sphere amplitude " << fmt("%+.3f", row.sphereAmplitudeChangePct)
            << " %\n";
        rows.push_back(row);
    }
    return rows;
}

void writeTemporalLodCsv(const std::string& path, const std::vector<TemporalLodRow>& rows) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error(path + ": cannot write");
    f << "model,triangles,interval,tolerance,resolved_interval,bodies,predicted_pct,ns_per_body_substep,"
         "force_error_mean_pct,force_error_p99_pct,force_error_max_pct,torque_error_max_pct,energy_drift_pct,"
         "sphere_amplitude_change_pct\n";
    for (const auto& r : rows)
        f << r.model << ',' << r.triangles << ',' << r.interval << ',' << r.tolerance << ',' << r.resolvedInterval << ','
          << r.bodies << ','
          << fmt("%.2f", r.predictedPct) << ',' << fmt("%.0f", r.nsPerBodySubstep) << ','
          << fmt("%.6f", r.forceErrorMeanPct) << ',' << fmt("%.6f", r.forceErrorP99Pct) << ','
          << fmt("%.6f", r.forceErrorMaxPct) << ',' << fmt("%.6f", r.torqueErrorMaxPct) << ','
          << fmt("%.4f", r.energyDriftPct) << ',' << fmt("%.4f", r.sphereAmplitudeChangePct) << '\n';
}

std::string temporalLodMarkdown(const std::vector<TemporalLodRow>& rows) {
    std::ostringstream md;
    md << "\n## Temporal level of detail (hydrostaticsInterval; temporal_lod.csv)\n\n"
       << "Hydrostatics and drag evaluated exactly every K-th substep, extrapolated from the last four exact "
          "evaluations (a cubic) in between and moved to the actual pose through the hydrostatic stiffness "
          "(btHydrostaticsHistory). Fleet in the scaling sea at 240 substeps/s, one thread, "
          "Bullet's step included; force error of every applied substep against clipping every triangle with exact "
          "wave queries, % of ρ g V. Energy: an undamped bobbing box, worst drift over 60 s, % of its energy above "
          "rest; an undamped bobbing sphere, its heave amplitude over the last 5 s of 60 against the first 5 s.\n\n"
       << "| interval | tolerance % | K | boats | predicted % | µs / body-substep | force err mean % | p99 % | max % | "
          "torque err max % | box energy drift % | sphere amplitude change % |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& r : rows)
        md << "| " << (r.interval == 0 ? std::string("0 (default)") : std::to_string(r.interval)) << " | "
           << fmt("%.2g", 100.0 * r.tolerance) << " | " << r.resolvedInterval << " | " << r.bodies << " | "
           << fmt("%.1f", r.predictedPct)
           << " | " << fmt("%.1f", 1e-3 * r.nsPerBodySubstep) << " | " << fmt("%.5f", r.forceErrorMeanPct) << " | "
           << fmt("%.5f", r.forceErrorP99Pct) << " | " << fmt("%.4f", r.forceErrorMaxPct) << " | "
           << fmt("%.4f", r.torqueErrorMaxPct) << " | " << fmt("%.3f", r.energyDriftPct) << " | "
           << fmt("%+.3f", r.sphereAmplitudeChangePct) << " |\n";
    return md.str();
}

}  // namespace buoyancy::bench
