// Every example scene runs headless (the same classes the browser shows) with no NaN and its
// expected outcome. Expectations come from physics, not from earlier runs: a buoy in waves follows them, water
// entering at the bow pitches the boat bow-down, a uniform ball has no righting moment (buoyancy acts through its
// centre) while a bottom-heavy one does, a balloon lighter than the air it displaces rises, a falling crate sends
// waves outwards.

#include "example_scenes/BalloonExample.h"
#include "example_scenes/ExampleEntries.h"
#include "example_scenes/SceneFileExample.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>

using namespace buoyancy;
using namespace buoyancy::examples;

namespace {

/// Create the example of the table row called `name` and build its world.
std::unique_ptr<SceneFileExample> start(const char* name) {
    const ExampleEntry* e = findExampleEntry(name);
    REQUIRE(e != nullptr);
    REQUIRE(e->createFunc != nullptr);
    ExampleOptions options;  // headless: no gui helper
    std::unique_ptr<ExampleScene> scene(e->createFunc(options));
    auto* file = dynamic_cast<SceneFileExample*>(scene.get());
    REQUIRE(file != nullptr);
    scene.release();
    std::unique_ptr<SceneFileExample> out(file);
    out->initPhysics();
    REQUIRE(out->world() != nullptr);
    return out;
}

/// Every body's pose and velocities are finite.
bool finite(const cli::SceneWorld& w) {
    for (const auto& b : w.bodies) {
        const btRigidBody* rb = b->getRigidBody();
        const btVector3 v[] = {rb->getCenterOfMassPosition(), rb->getLinearVelocity(), rb->getAngularVelocity(),
                               b->getMeshWorldTransform().getBasis()[0], b->getMeshWorldTransform().getBasis()[1]};
        for (const btVector3& x : v)
            if (!std::isfinite(double(x.x())) || !std::isfinite(double(x.y())) || !std::isfinite(double(x.z()))) return false;
    }
    return true;
}

/// Angle between the body's mesh +y axis and world +y, degrees.
double tiltDeg(const btBuoyantBody& b) {
    const btMatrix3x3 m = b.getMeshWorldTransform().getBasis();
    return std::acos(std::clamp(double(m[1][1]), -1.0, 1.0)) * 180.0 / M_PI;
}

/// Pitch of the mesh +x axis above the horizontal, degrees (+: bow up for the boat hull, whose bow is +x).
double pitchDeg(const btBuoyantBody& b) {
    const btMatrix3x3 m = b.getMeshWorldTransform().getBasis();
    return std::asin(std::clamp(double(m[1][0]), -1.0, 1.0)) * 180.0 / M_PI;
}

/// Step whole frames until `seconds` of simulated time, checking finiteness every frame.
template <class F>
void run(SceneFileExample& ex, double seconds, F&& eachFrame) {
    while (ex.time() < seconds - 1e-9) {
        ex.stepFrame();
        REQUIRE(finite(*ex.world()));
        eachFrame();
    }
}

}  // namespace

TEST_CASE("example table: every row with a create function names an existing scene", "[examples]") {
    int examples = 0;
    for (int i = 0; i < exampleEntryCount(); ++i) {
        const ExampleEntry& e = exampleEntry(i);
        CHECK(e.name != nullptr);
        CHECK(std::strlen(e.description) > 10);
        if (!e.createFunc) continue;
        ++examples;
        ExampleOptions options;
        std::unique_ptr<ExampleScene> scene;
        INFO(e.name);
        REQUIRE_NOTHROW(scene.reset(e.createFunc(options)));  // reads and validates its scene file
    }
    CHECK(examples >= 11);
    CHECK(findExampleEntry("no such scene") == nullptr);
}

TEST_CASE("buoy in waves: heaves with the waves and stays afloat", "[examples]") {
    auto ex = start("Buoy in waves");
    double lo = 1e9, hi = -1e9;
    const btBuoyantBody& buoy = *ex->world()->bodies[0];
    run(*ex, 8.0, [&] {
        if (ex->time() < 2.0) return;  // after the start-up transient
        const double y = double(buoy.getRigidBody()->getCenterOfMassPosition().y());
        lo = std::min(lo, y);
        hi = std::max(hi, y);
    });
    // The main wave has amplitude 0.3 m and wavelength 12 m, much longer than the 0.8 m buoy: a body that small
    // follows the surface, so it heaves by about the wave height 2A = 0.6 m (at least half of it).
    CHECK(hi - lo > 0.3);
    CHECK(hi < 1.5);   // afloat: near the surface, neither thrown out nor sunk
    CHECK(lo > -1.5);
    CHECK(ex->history().submerged.size() > 100);
}

TEST_CASE("boat holed at the bow sinks bow first, at the stern stern first", "[examples]") {
    for (const char* name : {"Boat holed at the bow", "Boat holed at the stern"}) {
        auto ex = start(name);
        const bool bow = std::strstr(name, "bow") != nullptr;
        const btBuoyantBody& boat = *ex->world()->bodies[0];
        run(*ex, 8.0, [] {});
        INFO(name << ": pitch " << pitchDeg(boat) << " deg, water inside " << ex->world()->floods[0]->getWaterVolume());
        CHECK(ex->world()->floods[0]->getWaterVolume() > 0.1);  // water came in through the hole
        // The water weighs on the holed end: that end goes down (the hull's bow is +x).
        if (bow) CHECK(pitchDeg(boat) < -3.0);
        else CHECK(pitchDeg(boat) > 3.0);
    }
}

TEST_CASE("uniform ball rolls over, bottom-heavy ball stays upright", "[examples]") {
    auto ex = start("Uniform vs bottom-heavy ball");
    const cli::SceneWorld& w = *ex->world();
    REQUIRE(ex->scene().bodies[0].name == "uniform");
    double uniformMax = 0, heavyMaxLate = 0;
    run(*ex, 8.0, [&] {
        uniformMax = std::max(uniformMax, tiltDeg(*w.bodies[0]));
        if (ex->time() > 2.0) heavyMaxLate = std::max(heavyMaxLate, tiltDeg(*w.bodies[1]));
    });
    // Both start tilted 60 degrees and spinning at 1.5 rad/s. The uniform ball's buoyancy passes through its centre
    // (= its centre of mass): no righting moment, it keeps turning past upside-down. The ballasted ball has its
    // centre of mass below the centre of buoyancy: it rights itself and only rocks.
    CHECK(uniformMax > 120.0);
    CHECK(heavyMaxLate < 45.0);
}

TEST_CASE("balloon rises in air and its deformable volume follows the inflation", "[examples]") {
    auto ex = start("Balloon in air");
    auto* balloon = dynamic_cast<BalloonExample*>(ex.get());
    REQUIRE(balloon != nullptr);
    REQUIRE(balloon->deformable() != nullptr);
    const double restVolume = ex->world()->actions[0]->getShape()->getVolume();
    // Inflation scales every length by k: the volume scales by k³ (0.8³ = 0.512 at the start).
    CHECK(balloon->currentVolume() == Approx(std::pow(BalloonExample::inflation(0.0), 3) * restVolume).epsilon(0.01));
    const double y0 = double(ex->world()->bodies[0]->getRigidBody()->getCenterOfMassPosition().y());
    run(*ex, 4.0, [] {});
    CHECK(balloon->currentVolume() == Approx(restVolume).epsilon(0.05));  // fully inflated (stretch ≤ 4 %)
    // Lift ρ_air V g = 1.2 · 0.52 · g exceeds the weight 0.25 g: it goes up.
    const btRigidBody& rb = *ex->world()->bodies[0]->getRigidBody();
    CHECK(double(rb.getCenterOfMassPosition().y()) > y0 + 2.0);
    CHECK(double(rb.getLinearVelocity().y()) > 0.5);
}

TEST_CASE("crate splash: the falling crate sends rings out through the interactive water", "[examples]") {
    auto ex = start("Crate splash");
    const cli::SceneWorld& w = *ex->world();
    REQUIRE(w.interactiveWater != nullptr);
    // Heights on the half ring of radius 2.5 m around the drop point facing away from the buoy (at x = 3.5 m,
    // which bobs a little from its start and makes small waves of its own).
    const int n = 32;
    auto ringDeviation = [&] {
        double worst = 0;
        for (int k = 0; k < n; ++k) {
            const double a = M_PI / 2 + M_PI * k / (n - 1);
            worst = std::max(worst, std::abs(w.water->height(2.5 * std::cos(a), 2.5 * std::sin(a), ex->time())));
        }
        return worst;
    };
    double before = 0;
    run(*ex, 0.4, [&] { before = std::max(before, ringDeviation()); });  // the crate falls from 2.5 m: lands at ~0.6 s
    double ring = 0;
    run(*ex, 3.0, [&] { ring = std::max(ring, ringDeviation()); });
    INFO("ring deviation before the crate lands " << before << " m, after " << ring << " m");
    CHECK(ring > 0.01);          // a wave of a centimetre or more passed the ring
    CHECK(ring > 5 * before);    // and it came from the crate
}

TEST_CASE("gerstner demo, variable-density ball and plush toy run without NaN", "[examples]") {
    for (const char* name : {"Gerstner demo", "Variable-density ball", "Plush toy soaking"}) {
        INFO(name);
        auto ex = start(name);
        run(*ex, 1.0, [] {});
        render::RenderFrame& f = ex->frame();
        ex->renderScene();  // headless: builds the frame only
        CHECK(f.bodies.size() == ex->world()->bodies.size());
    }
}

TEST_CASE("boat onto a beach: waves and its speed carry it up the slope until it grounds", "[examples][slow]") {
    auto ex = start("Boat onto a beach");
    const cli::SceneWorld& w = *ex->world();
    REQUIRE(w.ground != nullptr);
    const double x0 = double(w.bodies[0]->getRigidBody()->getCenterOfMassPosition().x());
    bool touched = false;
    run(*ex, 12.0, [&] {
        const btDispatcher* d = w.world.getDispatcher();
        for (int i = 0; i < d->getNumManifolds(); ++i) {
            const btPersistentManifold* m = const_cast<btDispatcher*>(d)->getManifoldByIndexInternal(i);
            const bool ground = m->getBody0() == w.ground.get() || m->getBody1() == w.ground.get();
            if (ground && m->getNumContacts() > 0) touched = true;
        }
    });
    const double x = double(w.bodies[0]->getRigidBody()->getCenterOfMassPosition().x());
    CHECK(x > x0 + 3.0);  // moved up the beach
    CHECK(touched);       // and rests on it
    // The beach plane n·p = h n_y; the boat's centre stays above it (no tunnelling).
    const Eigen::Vector3d c(x, double(w.bodies[0]->getRigidBody()->getCenterOfMassPosition().y()), 0.0);
    CHECK(w.groundNormal.dot(c) > w.groundOffset);
}

TEST_CASE("FFT fleet: 200 bodies float for a second without NaN", "[examples][slow]") {
    auto ex = start("FFT fleet");
    REQUIRE(ex->world()->bodies.size() == 200);
    run(*ex, 1.0, [] {});
    int afloat = 0;
    for (const auto& b : ex->world()->bodies)
        if (std::abs(double(b->getRigidBody()->getCenterOfMassPosition().y())) < 2.0) ++afloat;
    CHECK(afloat == 200);  // every body is lighter than water
}

TEST_CASE("Z-up plank: in a world with gravity along -z the plank floats at its draft along z and stays level",
          "[examples]") {
    auto ex = start("Z-up plank");
    const btBuoyantBody& plank = *ex->world()->bodies[0];
    double lo = 1e9, hi = -1e9, leastLevel = 1;
    run(*ex, 6.0, [&] {
        if (ex->time() < 2.0) return;
        const btRigidBody& b = *plank.getRigidBody();
        const double z = double(b.getCenterOfMassPosition().z());
        lo = std::min(lo, z);
        hi = std::max(hi, z);
        leastLevel = std::min(leastLevel, double(b.getWorldTransform().getBasis().getColumn(2).z()));
    });
    // Density 500 in water 1000: draft half of the 0.4 m thickness, so the centre rides at the water (z = 0), heaving
    // with waves of amplitude 0.1 m (12 m long, against a 2 m plank: it follows them). A y-up reading of the scene
    // would sink it along z or push it along y.
    INFO("centre height " << lo << " .. " << hi << ", smallest up component of the plank's normal " << leastLevel);
    CHECK(lo > -0.2);
    CHECK(hi < 0.2);
    CHECK(hi - lo > 0.02);  // it rides the waves
    CHECK(leastLevel > 0.9);
    CHECK(std::abs(double(plank.getRigidBody()->getCenterOfMassPosition().y())) < 0.5);
}
