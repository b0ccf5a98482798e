// Sleeping ("keeps wave-driven bodies awake, lets calm floating bodies sleep"). At rest on the water,
// Bullet's stored velocity is +g·dt (symplectic Euler, design.md 3), above Bullet's usual thresholds at
// 240 Hz; the action judges rest by the real motion of the COM instead.
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>

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

// Bullet's default thresholds (0.8 m/s, 1 rad/s) are far above the speeds of a bobbing body near the top of each
// bob: the action must keep it awake until it really is at rest (energy above equilibrium), whatever they are.
// Oracle: Archimedes — at rest, the submerged volume is s V and the weight is carried (s = density ratio).
TEST_CASE("Bullet's default sleeping thresholds: a body sleeps only at its equilibrium", "[bullet][sleeping]") {
    struct Case {
        const char* name;
        double sx, sy, sz, density, startY;
    };
    // A flat board (s = 0.4, stable flat: GM > 0) dropped from 0.5 m and started at the waterline, and a 1 m cube
    // of s = 0.2 (stable face-down: s < 0.211) dropped from 1 m.
    const Case c = GENERATE(Case{"board dropped", 1.0, 0.4, 0.8, 400, 0.7}, Case{"board at the waterline", 1.0, 0.4, 0.8, 400, 0.2},
                            Case{"cube dropped", 1.0, 1.0, 1.0, 200, 1.5});
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(c.sx, c.sy, c.sz));
    const double volume = c.sx * c.sy * c.sz;
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = c.density;
    body.linearSleepingThreshold = 0.8;  // Bullet's btRigidBodyConstructionInfo defaults
    body.angularSleepingThreshold = 1.0;
    w.add(shape, body, makePose(btVector3(0, btScalar(c.startY), 0)));
    const double s = c.density / 1000.0;
    double sleptAt = -1, volumeAtSleep = 0;
    for (int frame = 0; frame < 60 * 40; ++frame) {
        w.step(1, 4, 1.0 / 240);
        const double submerged = w.action(0).getLastResult().submergedVolume;
        if (!w.rigid(0)->isActive() && sleptAt < 0) {
            sleptAt = (frame + 1) / 60.0;
            volumeAtSleep = submerged;
        }
    }
    INFO(c.name << ": asleep at " << sleptAt << " s, submerged fraction then " << volumeAtSleep / volume << " (s = " << s << ")");
    CHECK(sleptAt > 0);                                      // it does sleep in calm water
    CHECK(volumeAtSleep / volume == Approx(s).epsilon(1e-3)); // and only at its equilibrium (within 0.1 %)
    const double draftCentre = c.sy / 2 - s * c.sy;          // mesh centre height at the draft s · height
    CHECK(w.body(0).getMeshWorldTransform().getOrigin().y() == Approx(draftCentre).margin(0.005 * c.sy));
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

// btBuoyancySettings::waterPatchNodesPerWavelength: in waves short against the body the patch would need
// more nodes than the body has points; the action then queries the surface exactly, so its result is the exact clip
// at its pose (an 8-vertex box in 1.5 m waves: 16 nodes per wavelength over its 1.4 m footprint is a 19×19 patch).
TEST_CASE("short waves: a low-poly body is queried exactly, not through a larger patch", "[bullet][lod]") {
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.8));
    btGerstnerWave wave;
    wave.amplitude = 0.05;
    wave.wavelength = 1.5;
    wave.steepness = 0.3;
    const btGerstnerWaterSurface sea({wave});
    BulletTestWorld w(&sea);
    btBuoyantBodySettings body;
    body.density = 400;
    btBuoyancySettings settings;
    settings.dragCoefficient = 0;  // no drag clusters: the points are the 8 vertices
    settings.linearDamping = 0;
    settings.radiationDamping = 0;
    settings.hydrostaticsInterval = 1;  // every substep evaluated: the comparison below is per substep
    w.add(shape, body, makePose(btVector3(0, 0.02, 0)), settings);
    const int nodes = btBuoyancyWaterPatchNodes(settings, shape->getBoundsRadius(), sea.shortestWavelength());
    REQUIRE(nodes * nodes >= int(shape->getMesh().vertices.size()));
    for (int substep = 0; substep < 30; ++substep) {
        w.step(1, 1, 1.0 / 240);
        const btBuoyancyResult& r = w.action(0).getLastResult();
        REQUIRE(r.applied);
        const Eigen::Isometry3d pose = buoyancy::toEigen(w.rigid(0)->getWorldTransform() * w.body(0).getMeshInComFrame());
        const buoyancy::MeshMomentTree& tree = shape->getMomentTree();
        const double thickness = std::abs(tree.nodes[0].m1.trace()) / 3.0 / tree.nodes[0].area;
        const buoyancy::HydrostaticsResult exact = buoyancy::curvedHydrostatics(
            shape->getMesh(), tree.edges, pose, sea, r.time, 1000, 9.81, pose.translation(), thickness, nullptr);
        // Exact queries: the same evaluation (a 19×19 patch would differ by its interpolation error, ~1e-5 of V). To
        // 1e-7 of V, not to rounding: a float build's rotation is orthonormal only to float precision (~6e-8).
        CHECK(std::abs(r.submergedVolume - exact.submerged_volume) <= 1e-7 * 0.32);
    }
}

// The drag clusters decide about the wave patch for the drag alone: a body with fewer heights to query than the patch
// has nodes keeps exact heights for its hydrostatics even when its drag probes use the patch.
TEST_CASE("waves: drag probes do not put a low-poly body's hydrostatics on the patch", "[bullet][lod]") {
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.8));
    btGerstnerWave wave;
    wave.amplitude = 0.3;
    wave.wavelength = 8.0;
    wave.steepness = 0.5;
    const btGerstnerWaterSurface sea({wave});
    BulletTestWorld w(&sea);
    btBuoyantBodySettings body;
    body.density = 400;
    btBuoyancySettings settings;  // default drag: its clusters are queried through the patch
    settings.hydrostaticsInterval = 1;
    w.add(shape, body, makePose(btVector3(0, 0.25, 0)), settings);
    const int nodes = btBuoyancyWaterPatchNodes(settings, shape->getBoundsRadius(), sea.shortestWavelength());
    const buoyancy::MeshMomentTree& tree = shape->getMomentTree();
    // The box's 8 vertices: fewer than the patch's nodes.
    REQUIRE(nodes * nodes >= int(shape->getMesh().vertices.size()));
    double patchDifference = 0;
    for (int substep = 0; substep < 30; ++substep) {
        w.step(1, 1, 1.0 / 240);
        const btBuoyancyResult& r = w.action(0).getLastResult();
        REQUIRE(r.applied);
        const Eigen::Isometry3d pose = buoyancy::toEigen(w.rigid(0)->getWorldTransform() * w.body(0).getMeshInComFrame());
        const double thickness = std::abs(tree.nodes[0].m1.trace()) / 3.0 / tree.nodes[0].area;
        const buoyancy::HydrostaticsResult exact = buoyancy::curvedHydrostatics(
            shape->getMesh(), tree.edges, pose, sea, r.time, 1000, 9.81, pose.translation(), thickness, nullptr);
        // The same water through a patch like the drag's, to show the check below can tell them apart.
        buoyancy::WaterPatch patch;
        btWaterQueryCache cache;
        patch.build(sea, pose.translation().x(), pose.translation().z(), shape->getBoundsRadius(), r.time, nodes, cache);
        const buoyancy::HydrostaticsResult viaPatch = buoyancy::curvedHydrostatics(
            shape->getMesh(), tree.edges, pose, sea, r.time, 1000, 9.81, pose.translation(), thickness, &patch);
        patchDifference = std::max(patchDifference, std::abs(viaPatch.submerged_volume - exact.submerged_volume));
        CHECK(std::abs(r.submergedVolume - exact.submerged_volume) <= 1e-7 * 0.32);
    }
    INFO("largest difference of the patch's evaluation " << patchDifference << " m^3");
    CHECK(patchDifference > 1e-6 * 0.32);
}
