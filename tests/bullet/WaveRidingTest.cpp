// Bodies that ride the waves (design.md 2.7, "The water's acceleration"): a small neutrally buoyant body under a
// long wave moves with the water's orbital motion, whose speed at mean depth z (negative) is a ω e^(k z) in linear
// (Airy) theory and for a trochoidal (Gerstner, Q = 1) wave alike.
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace buoyancy_test;

namespace {
/// The measured motion of the sphere's centre of mass over the measurement window.
struct RidingMotion {
    double horizontalAmplitude = 0;  ///< amplitude of the velocity along the wave's direction, m/s
    double verticalAmplitude = 0;    ///< amplitude of the vertical velocity, m/s
    double meanDepth = 0;            ///< mean height of the centre below the mean water level (negative), m
    double depthDrift = 0;           ///< mean height over the last two periods minus over the first two, m
};

/// A sphere of radius R and the water's density, centred one radius below the trough of one Gerstner wave
/// (amplitude a, wavelength λ, steepness Q = 1: circular orbits), started with the water's velocity there; drag off
/// (or the default drag and damping with `drag`), added mass on (C_a = ½) with the water's acceleration taken as `model` says. Settles for two periods, then
/// measures four.
RidingMotion rideOneWave(btWaterAccelerationForce model, bool drag = false) {
    const double a = 0.25, lambda = 30.0, g = 9.81, R = 0.1;
    const double k = 2 * M_PI / lambda, omega = std::sqrt(g * k), period = 2 * M_PI / omega;
    btGerstnerWave wave;
    wave.amplitude = a;
    wave.wavelength = lambda;
    wave.steepness = 1.0;
    wave.phase = M_PI;  // the particle at rest position x₀ = 0 is at the trough at t = 0
    btGerstnerWaterSurface water({wave}, 0.0, g);
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    if (!drag) {
        bs.dragCoefficient = 0;
        bs.skinFriction = 0;
        bs.linearDamping = 0;
        bs.radiationDamping = 0;
    }
    bs.addedMass = true;
    bs.addedMassCoefficient = 0.5;
    bs.waterAcceleration = model;
    auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(R, 32, 16), bs);
    BulletTestWorld w(&water, g);
    btBuoyantBodySettings body;
    body.density = 1000;  // the water's: neutrally buoyant when submerged
    const double y0 = -a - R;
    w.add(shape, body, makePose(btVector3(0, btScalar(y0), 0)), bs);
    // The water's velocity there: the particle at the bottom of its orbit, whose centre (rest height) yc solves
    // y0 = yc − a e^(k yc) (a fixed point, contraction a k), moves backwards at a ω e^(k yc).
    double yc = y0;
    for (int i = 0; i < 100; ++i) yc = y0 + a * std::exp(k * yc);
    w.rigid(0)->setLinearVelocity(btVector3(btScalar(-a * omega * std::exp(k * yc)), 0, 0));
    const double dt = 1.0 / 240.0;
    const int settle = int(std::lround(2 * period / dt)), measure = int(std::lround(4 * period / dt));
    w.step(settle, 1, dt);
    std::vector<double> x, y;
    for (int i = 0; i <= measure + 1; ++i) {
        const btVector3 c = w.rigid(0)->getCenterOfMassPosition();
        x.push_back(double(c.x()));
        y.push_back(double(c.y()));
        w.step(1, 1, dt);
    }
    // Velocities by central differences of the positions; amplitude √2 × the RMS about the mean (a sinusoid's).
    RidingMotion out;
    double sumVx = 0, sumVy = 0, sumVx2 = 0, sumVy2 = 0, sumY = 0, sumFirst = 0, sumLast = 0;
    for (int i = 1; i <= measure; ++i) {
        (2 * i <= measure ? sumFirst : sumLast) += y[std::size_t(i)];
        const double vx = (x[std::size_t(i + 1)] - x[std::size_t(i - 1)]) / (2 * dt);
        const double vy = (y[std::size_t(i + 1)] - y[std::size_t(i - 1)]) / (2 * dt);
        sumVx += vx;
        sumVy += vy;
        sumVx2 += vx * vx;
        sumVy2 += vy * vy;
        sumY += y[std::size_t(i)];
    }
    const double n = measure;
    out.horizontalAmplitude = std::sqrt(2 * std::max(sumVx2 / n - (sumVx / n) * (sumVx / n), 0.0));
    out.verticalAmplitude = std::sqrt(2 * std::max(sumVy2 / n - (sumVy / n) * (sumVy / n), 0.0));
    out.meanDepth = sumY / n;
    out.depthDrift = sumLast / (measure - measure / 2) - sumFirst / (measure / 2);
    return out;
}
}  // namespace

TEST_CASE("a small neutrally buoyant sphere under a long wave follows its orbital velocity",
          "[bullet][dynamics][waves]") {
    const double a = 0.25, lambda = 30.0, g = 9.81, ca = 0.5;
    const double k = 2 * M_PI / lambda, omega = std::sqrt(g * k);
    const btWaterAccelerationForce model = GENERATE(btWaterAccelerationForce::AddedMassAndFroudeKrylov,
                                                    btWaterAccelerationForce::AddedMass, btWaterAccelerationForce::None);
    const RidingMotion m = rideOneWave(model);
    // Linear (Airy) theory: the particles at mean depth z move on circles of radius a e^(k z) at ω.
    const double decay = std::exp(k * m.meanDepth);
    const double orbital = a * omega * decay;
    const double horizontal = m.horizontalAmplitude / orbital, vertical = m.verticalAmplitude / orbital;
    std::printf("riding (water acceleration %d): mean depth %.4f m, orbital speed %.5f m/s, horizontal %.5f m/s "
                "(%.4f of it), vertical %.5f m/s (%.4f), depth drift over two periods %.4f m\n",
                int(model), m.meanDepth, orbital, m.horizontalAmplitude, horizontal, m.verticalAmplitude, vertical,
                m.depthDrift);
    if (model == btWaterAccelerationForce::AddedMassAndFroudeKrylov) {
        // (m + m_a) dv/dt = (ρ V + m_a) Du/Dt with m = ρ V: the body moves with the water.
        CHECK(std::abs(horizontal - 1) < 0.05);
        CHECK(std::abs(vertical - 1) < 0.05);
        CHECK(std::abs(m.depthDrift) < 0.02);  // it keeps its depth (measured −0.009 m; the diameter is 0.2 m)
    } else {
        // The hydrostatic pressure below the local surface pushes a submerged body sideways with the surface's
        // slope, ρ V g ∇η, whose amplitude is the surface particles' acceleration a ω² (no decay with depth), and not
        // vertically at all. With m_a Du/Dt (at depth: a ω² e^(k z)) the velocity amplitudes over the orbital speed
        // are (e^(−k z) + C_a) / (1 + C_a) and C_a / (1 + C_a); without it 1 / ((1 + C_a) e^(k z)) and 0.
        const bool withAddedMass = model == btWaterAccelerationForce::AddedMass;
        const double expectedHorizontal = withAddedMass ? (1 / decay + ca) / (1 + ca) : 1 / ((1 + ca) * decay);
        const double expectedVertical = withAddedMass ? ca / (1 + ca) : 0.0;
        CHECK(horizontal == Approx(expectedHorizontal).epsilon(0.03));
        CHECK(vertical == Approx(expectedVertical).margin(0.01));
        CHECK(std::abs(vertical - 1) > 0.05);  // it does not ride the wave
    }
}

TEST_CASE("with the default drag the small sphere rides the wave too", "[bullet][dynamics][waves]") {
    const double a = 0.25, lambda = 30.0, g = 9.81;
    const double k = 2 * M_PI / lambda, omega = std::sqrt(g * k);
    const RidingMotion m = rideOneWave(btWaterAccelerationForce::AddedMassAndFroudeKrylov, true);
    const double orbital = a * omega * std::exp(k * m.meanDepth);
    std::printf("riding with drag: mean depth %.4f m, horizontal %.4f, vertical %.4f of the orbital speed, depth drift "
                "%.4f m\n",
                m.meanDepth, m.horizontalAmplitude / orbital, m.verticalAmplitude / orbital, m.depthDrift);
    CHECK(std::abs(m.horizontalAmplitude / orbital - 1) < 0.05);
    CHECK(std::abs(m.verticalAmplitude / orbital - 1) < 0.05);
}

namespace {
/// Flat water that counts its acceleration queries.
class CountingFlatWater : public btFlatWaterSurface {
public:
    using btFlatWaterSurface::btFlatWaterSurface;
    mutable int queries = 0;
    void accelerations(const double* x, const double* y, const double* z, std::size_t n, double t, double* outAx,
                       double* outAy, double* outAz) const override {
        ++queries;
        btFlatWaterSurface::accelerations(x, y, z, n, t, outAx, outAy, outAz);
    }
};

/// Gerstner waves that count their acceleration queries.
class CountingWaves : public btGerstnerWaterSurface {
public:
    using btGerstnerWaterSurface::btGerstnerWaterSurface;
    mutable int queries = 0;
    void accelerations(const double* x, const double* y, const double* z, std::size_t n, double t, double* outAx,
                       double* outAy, double* outAz) const override {
        ++queries;
        btGerstnerWaterSurface::accelerations(x, y, z, n, t, outAx, outAy, outAz);
    }
};

/// The centre of mass and velocity of a floating box dropped into `water` after 2 s, with `model`.
std::vector<double> dropBox(const btWaterSurface& water, btWaterAccelerationForce model, bool addedMass = true) {
    btBuoyancySettings bs;
    bs.addedMass = addedMass;
    bs.waterAcceleration = model;
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.5, 0.8), bs);
    BulletTestWorld w(&water);
    btBuoyantBodySettings body;
    body.density = 600;
    w.add(shape, body, makePose(btVector3(btScalar(0.2), 0, btScalar(-0.1)), btVector3(1, 0, 1), 20), bs);
    w.run(2.0);
    const btVector3 c = w.rigid(0)->getCenterOfMassPosition(), v = w.rigid(0)->getLinearVelocity();
    return {double(c.x()), double(c.y()), double(c.z()), double(v.x()), double(v.y()), double(v.z())};
}
}  // namespace

TEST_CASE("the water's acceleration is not queried in flat water and changes nothing there",
          "[bullet][dynamics][waves]") {
    CountingFlatWater flat(0.0, 0.3, 0.1);
    const std::vector<double> none = dropBox(flat, btWaterAccelerationForce::None);
    const std::vector<double> addedMass = dropBox(flat, btWaterAccelerationForce::AddedMass);
    const std::vector<double> froudeKrylov = dropBox(flat, btWaterAccelerationForce::AddedMassAndFroudeKrylov);
    CHECK(flat.queries == 0);
    CHECK(addedMass == none);  // bit for bit
    CHECK(froudeKrylov == none);
}

TEST_CASE("the water's acceleration is queried once per substep only when a term uses it",
          "[bullet][dynamics][waves]") {
    btGerstnerWave wave;
    wave.amplitude = 0.3;
    wave.wavelength = 20.0;
    CountingWaves waves({wave});
    dropBox(waves, btWaterAccelerationForce::None);
    CHECK(waves.queries == 0);
    dropBox(waves, btWaterAccelerationForce::AddedMass, false);  // no added mass: nothing to apply
    CHECK(waves.queries == 0);
    dropBox(waves, btWaterAccelerationForce::AddedMass);
    CHECK(waves.queries == 480);  // 2 s at 240 substeps/s, the body wet from the first
}
