// Temporal level of detail (btBuoyancySettings::hydrostaticsInterval, temporal/TemporalLevelOfDetail.h): in a
// simulation the predicted hydrostatics stay within the tolerance of an exact evaluation at the same pose and time
// (the records' extrapolation itself: tests/temporal/HydrostaticsHistoryTest.cpp); contacts/teleports, stiff light
// bodies and bad settings fall back to exact evaluation or a clear error.
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <BulletBuoyancy/integrals/MeshMomentTree.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

using namespace buoyancy_test;
using buoyancy::toEigen;

namespace {

/// Two Gerstner waves the 2 m box rides on (wavelengths 12 and 25 m, amplitudes 0.25 and 0.5 m).
std::vector<btGerstnerWave> testSea() {
    std::vector<btGerstnerWave> w(2);
    w[0] = {0.5, 25.0, 1.0, 0.2, 0.5, 0.0};
    w[1] = {0.25, 12.0, 0.3, 1.0, 0.5, 1.1};
    return w;
}

/// Exact hydrostatics (the exact-mesh evaluation with exact wave queries, no patch) of body i of `w` at its current
/// pose and the water time of its last result.
buoyancy::HydrostaticsResult exactNow(BulletTestWorld& w, std::size_t i, const btWaterSurface& water) {
    const btBuoyancyAction& a = w.action(i);
    const Eigen::Isometry3d pose = toEigen(w.rigid(i)->getWorldTransform() * a.getMeshInComFrame());
    const Eigen::Vector3d com = toEigen(w.rigid(i)->getCenterOfMassPosition());
    return buoyancy::treeHydrostatics(a.getShape()->getMomentTree(), a.getShape()->getMesh(), pose, water,
                                      a.getLastResult().time, 1000.0, 9.81, com, nullptr);
}

btBuoyancySettings intervalSettings(int k) {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactMesh;
    s.waterPatchNodes = 0;  // exact wave queries: the comparison below isolates the temporal error
    s.hydrostaticsInterval = k;
    return s;
}

/// The default (automatic) interval with nothing that removes energy: no drag, no damping, no added mass.
btBuoyancySettings undampedDefaults() {
    btBuoyancySettings s = intervalSettings(0);
    s.dragCoefficient = 0;
    s.linearDamping = 0;
    s.radiationDamping = 0;
    s.addedMass = false;
    return s;
}

}  // namespace

namespace {
/// Three 2 m boxes in the test sea with `settings`, 6 s after 1 s of settling: the share of substeps predicted and
/// the force error of every applied substep against an exact evaluation at the body's pose and time (fraction of
/// ρ g V), split into predicted and exact substeps.
struct WaveRun {
    double fractionPredicted = 0, meanPredicted = 0, p99Predicted = 0, worstPredicted = 0, worstExact = 0;
    std::uint64_t rejected = 0;
};
WaveRun runBoxesInWaves(const btBuoyancySettings& settings, double offset = 0,
                        const std::vector<btGerstnerWave>& waves = testSea()) {
    const btGerstnerWaterSurface sea(waves);
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 0.6, 1.0), settings);
    BulletTestWorld w(&sea);
    btBuoyantBodySettings body;
    body.density = 500;
    for (int i = 0; i < 3; ++i)
        w.add(shape, body, makePose(btVector3(btScalar(offset + 10 * i), 0, btScalar(offset + 3 * i))), settings);
    w.run(1.0);  // settle into the waves
    const double scale = 1000.0 * 9.81 * shape->getUnitSolid().volume;
    double sum = 0;
    long count = 0;
    std::vector<double> errors;
    WaveRun out;
    for (int n = 0; n < 240 * 6; ++n) {
        w.step(1, 1);
        for (std::size_t i = 0; i < w.size(); ++i) {
            const btBuoyancyResult& r = w.action(i).getLastResult();
            REQUIRE(r.applied);
            const double e = (toEigen(r.buoyancyForce) - exactNow(w, i, sea).force).norm() / scale;
            ++count;
            if (r.predicted) {
                sum += e;
                errors.push_back(e);
            } else {
                out.worstExact = std::max(out.worstExact, e);
            }
        }
    }
    REQUIRE(!errors.empty());
    std::sort(errors.begin(), errors.end());
    out.fractionPredicted = double(errors.size()) / double(count);
    out.meanPredicted = sum / double(errors.size());
    out.p99Predicted = errors[errors.size() * 99 / 100];
    out.worstPredicted = errors.back();
    out.rejected = w.rejectedTotal();
    std::printf("%.1f %% of substeps predicted; force error of the predicted ones vs exact: mean %.2e, 99th percentile "
                "%.2e, worst %.2e of rho g V; exact substeps %.1e\n",
                100 * out.fractionPredicted, out.meanPredicted, out.p99Predicted, out.worstPredicted, out.worstExact);
    return out;
}
}  // namespace

TEST_CASE("interval 4 in waves: three substeps of four predicted, within the tolerance of exact", "[bullet][temporal]") {
    btBuoyancySettings settings = intervalSettings(4);
    const double tolerance = 0.002;
    settings.hydrostaticsReuseTolerance = tolerance;
    std::printf("interval 4, tolerance 0.2 %%, waves: ");
    const WaveRun r = runBoxesInWaves(settings);
    CHECK(r.fractionPredicted > 0.70);
    CHECK(r.fractionPredicted <= 0.75);
    // The evaluation substeps are the exact method itself (the result is stored in btScalar).
    CHECK(r.worstExact < (sizeof(btScalar) == 4 ? 1e-6 : 1e-9));
    CHECK(r.meanPredicted < 1e-4);  // on average ≥ 20× below the tolerance
    CHECK(r.p99Predicted < tolerance);
    // Where a box corner crosses the waterline the force has a kink no polynomial follows: single substeps
    // reach about 1.5× the tolerance before the check at the next evaluation stops predictions.
    CHECK(r.worstPredicted < 2 * tolerance);
    CHECK(r.rejected == 0);
}

TEST_CASE("default temporal level of detail in waves: most substeps predicted, within 0.01 % of exact",
          "[bullet][temporal]") {
    // The defaults at 240 substeps/s: an exact evaluation every 8th substep, tolerance 1e-4 of rho g V.
    btBuoyancySettings settings;
    settings.method = btBuoyancyMethod::ExactMesh;
    settings.waterPatchNodes = 0;  // exact wave queries: the comparison isolates the temporal error
    std::printf("defaults, waves: ");
    const WaveRun r = runBoxesInWaves(settings);
    CHECK(r.fractionPredicted > 0.7);
    CHECK(r.fractionPredicted <= 0.875);
    CHECK(r.meanPredicted < 1e-5);
    CHECK(r.p99Predicted < 1e-4);
    // A box corner crossing the waterline puts a kink in the force that no polynomial follows; the check at the
    // next evaluation catches it, up to an interval (1/30 s) later: single substeps reach ≈ 3.5× the tolerance.
    CHECK(r.worstPredicted < 4e-4);
    CHECK(r.rejected == 0);
}

TEST_CASE("defaults far from the origin: predicted as often and as accurately as at the origin", "[bullet][temporal]") {
    // The same boxes in the same water 700 m along x and z: the test sea's phases are moved by k d·D, so that the
    // water at x + D is the water at x. A single-precision Bullet stores positions there to 61 µm, more than the
    // pose check's tolerance on these boxes (0.01 % of their V / A_waterline, 30 µm): the rounding of the positions
    // must not be taken for contacts.
    const double D = 700.0;
    std::vector<btGerstnerWave> moved = testSea();
    for (btGerstnerWave& wave : moved) {
        const double k = 2 * M_PI / wave.wavelength, n = std::hypot(wave.directionX, wave.directionZ);
        wave.phase -= k * (wave.directionX + wave.directionZ) / n * D;
    }
    {
        const btGerstnerWaterSurface a(testSea()), b(moved);
        for (double x : {-3.0, 0.5, 7.0})
            for (double t : {0.0, 1.3})
                REQUIRE(std::abs(b.height(x + D, x - 1 + D, t) - a.height(x, x - 1, t)) < 1e-8);
    }
    btBuoyancySettings settings;
    settings.method = btBuoyancyMethod::ExactMesh;
    settings.waterPatchNodes = 0;  // exact wave queries: the comparison isolates the temporal error
    std::printf("defaults at the origin: ");
    const WaveRun near = runBoxesInWaves(settings);
    std::printf("defaults 990 m from it: ");
    const WaveRun far = runBoxesInWaves(settings, D, moved);
    // Measured in single precision: without the rounding allowance 35 % of the substeps were predicted there (84 % at
    // the origin); with it 83 %, at a mean error of 1.3e-5 of rho g V (4e-6 at the origin: the drift the allowance
    // accepts is a few roundings of the position over the water's slope, a tenth of the tolerance).
    CHECK(far.fractionPredicted > near.fractionPredicted - 0.03);
    // The bounds of the test at the origin above; the mean within a fifth of the tolerance.
    CHECK(far.meanPredicted < 2e-5);
    CHECK(far.p99Predicted < 1e-4);
    CHECK(far.worstPredicted < 4e-4);
    CHECK(far.rejected == 0);
}

TEST_CASE("interval 4: a teleported body is evaluated exactly at once", "[bullet][temporal]") {
    const btGerstnerWaterSurface sea(testSea());
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 0.6, 1.0), intervalSettings(4));
    BulletTestWorld w(&sea);
    btBuoyantBodySettings body;
    body.density = 500;
    w.add(shape, body, makePose(btVector3(0, 0, 0)), intervalSettings(4));
    w.run(1.0);
    // Step until the next substep would be predicted, then move the body 0.1 m down.
    int guard = 0;
    while (!w.action(0).getLastResult().predicted && ++guard < 480) w.step(1, 1);
    REQUIRE(w.action(0).getLastResult().predicted);
    btTransform t = w.rigid(0)->getWorldTransform();
    t.setOrigin(t.getOrigin() - btVector3(0, btScalar(0.1), 0));
    w.rigid(0)->setWorldTransform(t);
    const double scale = 1000.0 * 9.81 * shape->getUnitSolid().volume;
    w.step(1, 1);
    CHECK_FALSE(w.action(0).getLastResult().predicted);
    double worst = 0;
    for (int n = 0; n < 40; ++n) {
        const double e = (toEigen(w.action(0).getLastResult().buoyancyForce) - exactNow(w, 0, sea).force).norm() / scale;
        worst = std::max(worst, e);
        w.step(1, 1);
    }
    std::printf("after a 0.1 m teleport: worst force error over 40 substeps %.2e of rho g V\n", worst);
    CHECK(worst < btBuoyancySettings().hydrostaticsReuseTolerance);
}

TEST_CASE("defaults: a body landing in the waves or surfacing from under them is not extrapolated across the surface",
          "[bullet][temporal]") {
    // A body whose last evaluation found it entirely out of the water (or entirely under it) has records that say
    // nothing of the surface it is about to cross: the force it gets while it lands (or surfaces) must be the exact one.
    // Landing: a box released 1.5 m above the mean level of a swell falls for a while inside the swell's bounds (so it
    // is not culled, and its records say "dry") before it hits the water. Surfacing: a light box released 1.5 m under
    // calm water rises through it (undamped, it then leaves the water and lands again). Oracle: clipping every triangle
    // at the body's pose with exact wave queries.
    const btGerstnerWaterSurface swell(testSea());
    const btFlatWaterSurface calmWater(0.0);
    const btBuoyancySettings s = undampedDefaults();
    for (const double startY : {1.5, -1.5}) {
        const btWaterSurface& calm = startY > 0 ? static_cast<const btWaterSurface&>(swell) : calmWater;
        auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 1.0, 1.0), s);
        BulletTestWorld w(&calm);
        btBuoyantBodySettings body;
        body.density = 500;
        w.add(shape, body, makePose(btVector3(0, btScalar(startY), 0)), s);
        const double scale = 1000.0 * 9.81 * shape->getUnitSolid().volume;
        double worst = 0;
        int crossing = 0, predicted = 0;
        for (int n = 0; n < 480; ++n) {
            w.step(1, 1);
            const btBuoyancyResult& r = w.action(0).getLastResult();
            if (!r.applied) continue;
            const buoyancy::HydrostaticsResult e = exactNow(w, 0, calm);
            const double wet = e.submerged_volume / shape->getUnitSolid().volume;
            if (wet > 1e-6 && wet < 1 - 1e-6) ++crossing;

            predicted += r.predicted;
            worst = std::max(worst, (toEigen(r.buoyancyForce) - e.force).norm() / scale);
        }
        std::printf("box %s: worst force error %.2e of rho g V over 2 s (%d substeps across the surface, %d predicted)\n",
                    startY > 0 ? "landing in a swell from 1.5 m" : "surfacing from 1.5 m under calm water", worst, crossing,
                    predicted);
        CHECK(crossing > 100);
        CHECK(predicted > 0);  // the level of detail is at work once the body floats
        // (The worst, ≈ 1.4e-3 landing in the swell, is a single substep where the box's bottom first meets a crest.)
        CHECK(worst < 2e-3);
    }
}

TEST_CASE("interval 4 in flat water: the same equilibrium draft as exact every substep", "[bullet][temporal]") {
    // Oracle: a wall-sided box of density ratio s floats with draft s·c (Archimedes).
    const double a = 2, c = 0.5, b = 1, s = 0.4;
    double draft[2] = {0, 0};
    for (int k : {1, 4}) {
        auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(a, c, b), intervalSettings(k));
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000 * s;
        w.add(shape, body, makePose(btVector3(0, btScalar(0.1), 0)), intervalSettings(k));
        w.run(12.0);
        draft[k == 4] = c / 2 - double(w.body(0).getMeshWorldTransform().getOrigin().y());
        CHECK(w.rejectedTotal() == 0);
    }
    std::printf("flat-water draft: exact every substep %.6f m, interval 4 %.6f m, Archimedes %.6f m\n", draft[0],
                draft[1], s * c);
    CHECK(draft[1] == Approx(s * c).margin(2e-3));      // settled (the slow last 1 mm of a damped bobbing)
    CHECK(draft[1] == Approx(draft[0]).margin(2e-5));   // and the prediction does not move it
}

TEST_CASE("defaults: an undamped bobbing sphere keeps its amplitude (energy) over a minute", "[bullet][temporal]") {
    // Oracle: an undamped oscillator keeps its energy, so its amplitude; the goal allows 1 % of energy a minute
    // (0.5 % of amplitude). The sphere's waterline grows and shrinks with its draft: its restoring force is not
    // the linear part the prediction's heave correction makes exact, so what is left is the extrapolated remainder.
    const btBuoyancySettings s = undampedDefaults();  // the automatic interval: every 8th substep at 240/s
    auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.5, 48, 24), s);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 500;
    w.add(shape, body, makePose(btVector3(0, -0.15f, 0)), s);
    double lo1 = 1e9, hi1 = -1e9, lo2 = 1e9, hi2 = -1e9;
    long predicted = 0;
    const int n = 240 * 60, window = 240 * 5;
    for (int k = 0; k < n; ++k) {
        w.step(1, 1);
        const double y = double(w.rigid(0)->getCenterOfMassPosition().y());
        predicted += w.action(0).getLastResult().predicted ? 1 : 0;
        if (k < window) lo1 = std::min(lo1, y), hi1 = std::max(hi1, y);
        if (k >= n - window) lo2 = std::min(lo2, y), hi2 = std::max(hi2, y);
    }
    const double change = (hi2 - lo2) / (hi1 - lo1) - 1;
    std::printf("undamped sphere, defaults at 240/s: %.1f %% predicted, amplitude %.5f -> %.5f m over 60 s (%+.3f %%)\n",
                100.0 * double(predicted) / n, (hi1 - lo1) / 2, (hi2 - lo2) / 2, 100 * change);
    CHECK(predicted > n / 4);  // the prediction is exercised
    CHECK(std::abs(change) < 0.005);
    CHECK(w.rejectedTotal() == 0);
}

TEST_CASE("defaults: an undamped rolling box keeps its roll amplitude (energy) over a minute", "[bullet][temporal]") {
    // Oracle: an undamped roll keeps its energy, so its amplitude. Roll is restored through the waterplane's second
    // moment (ρ g ∫z² dA) and the turned centre of buoyancy; the prediction follows the actual roll angle through
    // them (hydrostaticStiffnessCorrection), so only the remainder is extrapolated. A 2 × 0.5 × 1 m box at density
    // ratio 0.5 (GM = 0.21 m, ω ≈ 4.4 rad/s) rolled 0.08 rad about its long axis.
    const btBuoyancySettings s = undampedDefaults();
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 0.5, 1.0), s);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 500;
    btTransform start = makePose(btVector3(0, 0, 0));
    start.setRotation(btQuaternion(btVector3(1, 0, 0), btScalar(0.08)));
    w.add(shape, body, start, s);
    auto roll = [&w]() {
        const btMatrix3x3& R = w.rigid(0)->getWorldTransform().getBasis();
        return std::atan2(double(R[2][1]), double(R[1][1]));
    };
    double lo1 = 1e9, hi1 = -1e9, lo2 = 1e9, hi2 = -1e9;
    long predicted = 0;
    const int n = 240 * 60, window = 240 * 5;
    for (int k = 0; k < n; ++k) {
        w.step(1, 1);
        const double a = roll();
        predicted += w.action(0).getLastResult().predicted ? 1 : 0;
        if (k < window) lo1 = std::min(lo1, a), hi1 = std::max(hi1, a);
        if (k >= n - window) lo2 = std::min(lo2, a), hi2 = std::max(hi2, a);
    }
    const double change = (hi2 - lo2) / (hi1 - lo1) - 1;
    std::printf("undamped rolling box, defaults at 240/s: %.1f %% predicted, roll amplitude %.5f -> %.5f rad over 60 s "
                "(%+.3f %%)\n",
                100.0 * double(predicted) / n, (hi1 - lo1) / 2, (hi2 - lo2) / 2, 100 * change);
    CHECK(predicted > n / 2);  // the prediction is exercised
    CHECK(std::abs(change) < 0.005);
    CHECK(w.rejectedTotal() == 0);
}

TEST_CASE("interval 8: a light, stiff body is never predicted and stays bounded", "[bullet][temporal]") {
    // A 7 cm cube at density ratio 0.05 heaves at ω = sqrt(ρ g A / m_eff) ≈ 40 rad/s: ω · 8 · dt ≈ 1.3 > 0.3.
    const double side = 0.07;
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(side, side, side), intervalSettings(8));
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 50;
    w.add(shape, body, makePose(btVector3(0, 0.05f, 0)), intervalSettings(8));
    long predicted = 0;
    for (int n = 0; n < 240 * 3; ++n) {
        w.step(1, 1);
        if (w.action(0).getLastResult().predicted) ++predicted;
    }
    const double y = double(w.body(0).getMeshWorldTransform().getOrigin().y());
    std::printf("light cube, interval 8: %ld predicted substeps, centre at y = %.4f m\n", predicted, y);
    CHECK(predicted == 0);
    CHECK(std::abs(y - (side / 2 - 0.05 * side)) < 0.01);
    CHECK(w.rejectedTotal() == 0);
}

TEST_CASE("the automatic interval evaluates exactly at least every 1/30 s", "[bullet][temporal]") {
    CHECK(btBuoyancyAutomaticInterval(1.0 / 30.0) == 1);
    CHECK(btBuoyancyAutomaticInterval(1.0 / 60.0) == 2);
    CHECK(btBuoyancyAutomaticInterval(1.0 / 120.0) == 4);
    CHECK(btBuoyancyAutomaticInterval(double(btScalar(1.0 / 240.0))) == 8);  // as Bullet passes it, in float too
    CHECK(btBuoyancyAutomaticInterval(1.0 / 480.0) == 16);
    CHECK(btBuoyancyAutomaticInterval(1e-5) == 16);
    CHECK(btBuoyancyAutomaticInterval(1.0 / 240.0, 1.0 / 120.0) == 2);
    CHECK(btBuoyancyAutomaticInterval(0.0) == 1);
    CHECK(btBuoyancyAutomaticInterval(std::numeric_limits<double>::quiet_NaN()) == 1);
    // In a simulation at 240 substeps/s the default predicts up to seven substeps of eight (waves, a slow body).
    const btGerstnerWaterSurface sea(testSea());
    btBuoyancySettings defaults;
    defaults.method = btBuoyancyMethod::ExactMesh;
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 0.6, 1.0), defaults);
    BulletTestWorld w(&sea);
    btBuoyantBodySettings body;
    body.density = 500;
    w.add(shape, body, makePose(btVector3(0, 0, 0)), defaults);
    w.run(1.0);
    long predicted = 0;
    for (int n = 0; n < 480; ++n) {
        w.step(1, 1);
        predicted += w.action(0).getLastResult().predicted ? 1 : 0;
    }
    std::printf("default settings at 240 substeps/s in waves: %ld of 480 substeps predicted\n", predicted);
    CHECK(predicted > 240);
    CHECK(predicted <= 420);  // at most seven substeps of eight
}

TEST_CASE("an error budget lengthens the automatic interval, and the pick is described", "[bullet][temporal]") {
    // The temporal model (btBuoyancyEvaluationPeriod's doc): 33 ms 0.21 %, 50 ms 0.24 %, 67 ms 0.28 % worst force
    // error; a period is allowed when twice its error fits the budget.
    btBuoyancySettings s;
    const double dt = 1.0 / 240.0;
    CHECK(btBuoyancyEvaluationPeriod(s) == Approx(1.0 / 30.0));
    CHECK(btBuoyancyResolveInterval(s, dt) == 8);
    CHECK(btBuoyancyResolveReuseTolerance(s) == 1e-4);
    s.errorBudget = 0.01;  // below every model point: the default period and tolerance
    CHECK(btBuoyancyResolveInterval(s, dt) == 8);
    CHECK(btBuoyancyResolveReuseTolerance(s) == 1e-4);
    s.errorBudget = 0.45;  // 2 × 0.21 fits (33 ms, the default period anyway), 2 × 0.24 does not
    CHECK(btBuoyancyEvaluationPeriod(s) == Approx(8.0 / 240.0));
    CHECK(btBuoyancyResolveInterval(s, dt) == 8);
    CHECK(btBuoyancyResolveReuseTolerance(s) == Approx(2.25e-3));  // half the budget, as a fraction
    s.errorBudget = 0.5;   // 2 × 0.24 fits: 50 ms
    CHECK(btBuoyancyResolveInterval(s, dt) == 12);
    s.errorBudget = 0.6;   // every point fits: 1/15 s
    double modelError = 0;
    CHECK(btBuoyancyEvaluationPeriod(s, &modelError) == Approx(16.0 / 240.0));
    CHECK(modelError == Approx(0.28));
    CHECK(btBuoyancyResolveInterval(s, dt) == 16);
    CHECK(btBuoyancyResolveInterval(s, 1.0 / 60.0) == 4);
    CHECK(btBuoyancyResolveReuseTolerance(s) == Approx(3e-3));
    const btBuoyancyLevelOfDetail lod = btBuoyancyPickLevelOfDetail(s, 3400);
    CHECK(lod.evaluationPeriod == Approx(16.0 / 240.0));
    CHECK_THAT(lod.description, Catch::Contains("exact hydrostatics every 66.7 ms"));
    s.hydrostaticsInterval = 3;  // an explicit interval wins over the budget, and keeps its own tolerance
    CHECK(btBuoyancyResolveInterval(s, dt) == 3);
    CHECK(btBuoyancyResolveReuseTolerance(s) == 1e-4);
    CHECK(btBuoyancyPickLevelOfDetail(s, 3400).evaluationPeriod == 0);
}

TEST_CASE("hydrostaticsInterval and hydrostaticsReuseTolerance are validated", "[bullet][temporal]") {
    btBuoyancySettings s;
    s.hydrostaticsInterval = -1;
    CHECK_THROWS_WITH(s.validate(), Catch::Contains("hydrostaticsInterval") && Catch::Contains("1..16"));
    s.hydrostaticsInterval = 0;  // automatic
    CHECK_NOTHROW(s.validate());
    s.hydrostaticsInterval = 17;
    CHECK_THROWS_WITH(s.validate(), Catch::Contains("hydrostaticsInterval"));
    s.hydrostaticsInterval = 16;
    CHECK_NOTHROW(s.validate());
    for (double bad : {0.0, -1e-3, 1.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        s.hydrostaticsReuseTolerance = bad;
        CHECK_THROWS_WITH(s.validate(), Catch::Contains("hydrostaticsReuseTolerance"));
    }
}

TEST_CASE("defaults at 240 Hz: an undamped heave keeps its energy within 0.01 % a minute and linear theory's period",
          "[bullet][temporal]") {
    // Oracles: an undamped oscillator keeps its energy; a body of waterplane area A and mass m (+ added mass m_a)
    // heaves with T = 2π sqrt((m + m_a) / (ρ g A)) at small amplitude. Bodies at density ratio 0.5 (centre of mass at
    // the water level, by symmetry), released 1-2 cm below it, no drag or damping, the default interval:
    // - a wall-sided 2 × 0.5 × 1 m box (linear restoring force), without and with the default added mass;
    // - a sphere of radius 0.5 m (48 × 24 mesh): A = π R², m = ρ (2/3) π R³, so T = 2π sqrt(2R / (3 g)); its
    //   restoring force is not linear, 2 cm of 0.5 m shifts the period by less than 0.01 %.
    // Amplitudes from the peaks and troughs refined by a parabola through three samples; the period from the upward
    // zero crossings (interpolated).
    struct Case {
        const char* name;
        buoyancy::TriangleMesh mesh;
        bool addedMass;
        double start, period;
    };
    const double rho = 1000, g = 9.81;
    // The heave added mass (design.md 2.7): the larger of C_a ρ V_sub (V_sub = 0.5 m³) and c_wp ρ A^(3/2).
    const double boxM = 500, boxA = 2;
    const double boxMa = std::max(0.5 * rho * 0.5, btBuoyancySettings().addedMassWaterplaneCoefficient * rho * std::pow(boxA, 1.5));
    const Case cases[] = {
        {"box", buoyancy::makeBoxMesh(2.0, 0.5, 1.0), false, -0.01, 2 * M_PI * std::sqrt(boxM / (rho * g * boxA))},
        {"box with added mass", buoyancy::makeBoxMesh(2.0, 0.5, 1.0), true, -0.01,
         2 * M_PI * std::sqrt((boxM + boxMa) / (rho * g * boxA))},
        {"sphere", buoyancy::makeSphereMesh(0.5, 48, 24), false, -0.02, 2 * M_PI * std::sqrt(2 * 0.5 / (3 * g))},
    };
    for (const Case& c : cases) {
        btBuoyancySettings s = undampedDefaults();
        s.addedMass = c.addedMass;
        auto shape = btBuoyancyShape::create(c.mesh, s);
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 500;
        w.add(shape, body, makePose(btVector3(0, btScalar(c.start), 0)), s);
        const int n = 240 * 60, window = 240 * 5;
        std::vector<double> y(static_cast<std::size_t>(n));
        for (int k = 0; k < n; ++k) {
            w.step(1, 1);
            y[std::size_t(k)] = double(w.rigid(0)->getCenterOfMassPosition().y());
        }
        // Mean height of the refined extremes within [from, to): of the maxima (sign +1) or the minima (−1).
        const auto extremes = [&](int from, int to, double sign) {
            double sum = 0;
            int count = 0;
            for (int k = std::max(from, 1); k < std::min(to, n - 1); ++k) {
                const double a = sign * y[std::size_t(k - 1)], b = sign * y[std::size_t(k)], d = sign * y[std::size_t(k + 1)];
                if (!(a < b && b >= d)) continue;
                sum += sign * (b + (d - a) * (d - a) / (8 * (2 * b - a - d)));
                ++count;
            }
            REQUIRE(count >= 3);
            return sum / count;
        };
        const double first = extremes(0, window, 1) - extremes(0, window, -1);
        const double last = extremes(n - window, n, 1) - extremes(n - window, n, -1);
        const double energyChange = (last / first) * (last / first) - 1;
        std::vector<double> ups;
        for (int k = 1; k < n; ++k)
            if (y[std::size_t(k - 1)] < 0 && y[std::size_t(k)] >= 0)
                ups.push_back((k - 1 + -y[std::size_t(k - 1)] / (y[std::size_t(k)] - y[std::size_t(k - 1)])) / 240.0);
        REQUIRE(ups.size() > 10);
        const double period = (ups.back() - ups.front()) / double(ups.size() - 1);
        std::printf("undamped heave at 240 Hz, %s: amplitude %.6f -> %.6f m in a minute (energy %+.4f %%), period %.5f s "
                    "against %.5f s (%+.3f %%)\n",
                    c.name, first / 2, last / 2, 100 * energyChange, period, c.period, 100 * (period / c.period - 1));
        CHECK(std::abs(energyChange) < 1e-4);
        CHECK(period == Approx(c.period).epsilon(0.005));
        CHECK(w.rejectedTotal() == 0);
    }
}
