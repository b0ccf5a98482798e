// Sleeping (issue 4: "keeps wave-driven bodies awake, lets calm floating bodies sleep"). At rest on the water,
// Bullet's stored velocity is +g·dt (symplectic Euler, DESIGN-NOTES 3), above Bullet's usual thresholds at
// 240 Hz; the action judges rest by the real motion of the COM instead.
#include "oracles/BulletTestWorld.h"
#include "mesh/PrimitiveMeshes.h"
#include "water/btGerstnerWaterSurface.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace buoyancy_test;

TEST_CASE("a calm floating body falls asleep at its draft, at 60 and 240 Hz", "[bullet][sleeping]") {
    const double hz = GENERATE(60.0, 240.0);
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.8));
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 400;  // s = 0.4, draft 0.16: GM = KB + BM − KG = 0.08 + 0.8²/(12·0.16) − 0.2 > 0, stable flat
    w.add(shape, body, makePose(btVector3(0, 0.3, 0)));
    double sleptAt = -1;
    for (int frame = 0; frame < int(30 * hz / 4); ++frame) {
        w.step(1, 4, 1.0 / hz);
        if (sleptAt < 0 && !w.rigid(0)->isActive()) sleptAt = (frame + 1) * 4 / hz;
    }
    INFO("rate " << hz << " Hz, asleep at " << sleptAt << " s");
    CHECK(sleptAt > 2.0);   // not before it settles (Bullet needs 2 s below the thresholds)
    CHECK(sleptAt < 25.0);  // but it does sleep
    CHECK_FALSE(w.rigid(0)->isActive());
    // Asleep at the analytic draft d = s c (mesh centre at c/2 − d = 0.2 − 0.16 = 0.04).
    CHECK(w.body(0).getMeshWorldTransform().getOrigin().y() == Approx(0.04).margin(0.4 * 0.005));
}

TEST_CASE("a body in waves is kept awake", "[bullet][sleeping]") {
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.8));
    BulletTestWorld w;
    btGerstnerWave wave;
    wave.amplitude = 0.05;
    wave.wavelength = 20;
    wave.steepness = 0.3;
    btGerstnerWaterSurface sea({wave});
    w.water().setWater(&sea);
    btBuoyantBodySettings body;
    body.density = 400;
    w.add(shape, body, makePose(btVector3(0, 0.04, 0)));
    bool everAsleep = false;
    for (int frame = 0; frame < 60 * 15; ++frame) {
        w.step(1, 4, 1.0 / 240);
        everAsleep = everAsleep || !w.rigid(0)->isActive();
    }
    CHECK_FALSE(everAsleep);
    w.water().setWater(nullptr);
}
