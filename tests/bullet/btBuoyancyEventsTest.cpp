// Water events (btBuoyancyEvents.h): enter, leave, fully submerged and surfaced, with hysteresis on the submerged
// fraction, delivered to listeners from the serial part of the step in a documented order; the per-body state getters.
// Oracles: free fall (when a dropped box reaches the water), Archimedes (a box of density ρ_b floats with ρ_b / ρ_w of
// its volume under water, a denser one sinks), the hysteresis rule written out in the test, and the same scene run
// on one thread, on two and without batching.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using Catch::Matchers::Contains;

namespace {

constexpr double kGravity = 9.81;         ///< m/s²
constexpr double kSubstep = 1.0 / 240.0;  ///< s

btDynamicsWorld* withGravity(btDynamicsWorld* world, const btVector3& gravity) {
    world->setGravity(gravity);
    return world;
}

/// A Bullet world (y-up unless another gravity is given) with an unbounded water (or none), and crates with actions.
struct EventsWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btBuoyancyWorld buoyancy;
    std::vector<std::unique_ptr<btBuoyantBody>> bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> actions;

    explicit EventsWorld(const btWaterSurface* water,
                         const btVector3& gravity = btVector3(0, btScalar(-kGravity), 0))
        : buoyancy(withGravity(&world, gravity), water) {}
    ~EventsWorld() {
        for (auto& a : actions) world.removeAction(a.get());
        for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
    }
    /// A 1 × 0.5 × 1 m crate (0.5 m along the mesh's y) of `density`, kg/m³, centred at `at`, m, its mesh axes the
    /// world's; its action is made now and added to the Bullet world when `addAction`.
    std::size_t addCrate(double density, const btVector3& at, bool addAction = true) {
        auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.5, 1.0));
        btBuoyantBodySettings settings;
        settings.density = density;
        bodies.push_back(std::make_unique<btBuoyantBody>(shape, settings, btTransform(btQuaternion::getIdentity(), at)));
        world.addRigidBody(bodies.back()->getRigidBody());
        actions.push_back(std::make_unique<btBuoyancyAction>(*bodies.back(), &buoyancy));
        if (addAction) world.addAction(actions.back().get());
        return bodies.size() - 1;
    }
    void run(double seconds) {
        for (int i = 0; i < int(seconds * 60 + 0.5); ++i)
            world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(kSubstep));
    }
};

/// Every event received, as the listener saw it.
struct Recorder : btBuoyancyEventListener {
    struct Entry {
        btBuoyancyEventType type;
        btBuoyancyEventType callback;  ///< which method received it
        const btRigidBody* body;
        int waterBody;
        std::string waterName;
        double fraction;
        double time;
        std::uint64_t substep;
    };
    std::vector<Entry> entries;

    void record(const btBuoyancyEvent& e, btBuoyancyEventType callback) {
        entries.push_back(Entry{e.type, callback, e.body, e.waterBody, e.water ? e.water->name : std::string(),
                                e.submergedFraction, e.time, e.substep});
    }
    void onEnterWater(const btBuoyancyEvent& e) override { record(e, btBuoyancyEventType::EnterWater); }
    void onLeaveWater(const btBuoyancyEvent& e) override { record(e, btBuoyancyEventType::LeaveWater); }
    void onFullySubmerged(const btBuoyancyEvent& e) override { record(e, btBuoyancyEventType::FullySubmerged); }
    void onSurfaced(const btBuoyancyEvent& e) override { record(e, btBuoyancyEventType::Surfaced); }

    int count(btBuoyancyEventType type, const btRigidBody* body = nullptr) const {
        int n = 0;
        for (const Entry& e : entries) n += e.type == type && (!body || e.body == body);
        return n;
    }
    std::vector<btBuoyancyEventType> typesOf(const btRigidBody* body) const {
        std::vector<btBuoyancyEventType> out;
        for (const Entry& e : entries)
            if (e.body == body) out.push_back(e.type);
        return out;
    }
};

using T = btBuoyancyEventType;

}  // namespace

TEST_CASE("water events: the hysteresis rule on a sequence of submerged fractions", "[bullet][events]") {
    const btBuoyancyEventSettings settings;  // enter 0.01, leave 0.001, submerged 0.99, surfaced 0.97
    btBuoyancyWaterState state;
    btBuoyancyEventType types[btBuoyancyWaterState::kMaxEvents];
    int bodies[btBuoyancyWaterState::kMaxEvents];
    std::vector<btBuoyancyEventType> seen;
    const auto feed = [&](double f, int body = -1) {
        const int n = state.update(f, body, settings, types, bodies);
        for (int i = 0; i < n; ++i) seen.push_back(types[i]);
        return n;
    };
    SECTION("a fraction jittering around the enter threshold enters once") {
        for (int i = 0; i < 1000; ++i) feed(0.01 + (i % 2 ? 0.004 : -0.004));  // crosses 0.01 every substep
        CHECK(seen == std::vector<T>{T::EnterWater});
        CHECK(state.inWater);
        feed(0.0);
        CHECK(seen == std::vector<T>{T::EnterWater, T::LeaveWater});
    }
    SECTION("a fraction jittering around the submerged threshold submerges once") {
        for (int i = 0; i < 1000; ++i) feed(0.99 + (i % 2 ? 0.005 : -0.005));
        CHECK(seen == std::vector<T>{T::EnterWater, T::FullySubmerged});
        CHECK(state.submerged);
    }
    SECTION("swings across both thresholds of a pair fire each time") {
        // 0.5 → 1 → 0.5 ten times: ten submerged and ten surfaced events, alternating.
        for (int i = 0; i < 10; ++i) {
            feed(0.5);
            feed(1.0);
        }
        feed(0.5);
        REQUIRE(seen.size() == 21);
        CHECK(seen[0] == T::EnterWater);
        for (std::size_t i = 1; i < seen.size(); ++i)
            CHECK(seen[i] == (i % 2 ? T::FullySubmerged : T::Surfaced));
    }
    SECTION("from dry to fully under water and back in one step each") {
        CHECK(feed(1.0) == 2);
        feed(0.0);
        CHECK(seen == std::vector<T>{T::EnterWater, T::FullySubmerged, T::Surfaced, T::LeaveWater});
        CHECK_FALSE(state.inWater);
        CHECK_FALSE(state.submerged);
    }
    SECTION("moving into another water body while in the water leaves the old one and enters the new one") {
        feed(1.0, 0);
        seen.clear();
        REQUIRE(feed(1.0, 1) == 4);
        CHECK(seen == std::vector<T>{T::Surfaced, T::LeaveWater, T::EnterWater, T::FullySubmerged});
        CHECK(bodies[0] == 0);
        CHECK(bodies[1] == 0);
        CHECK(bodies[2] == 1);
        CHECK(bodies[3] == 1);
        CHECK(state.waterBody == 1);
    }
    SECTION("a non-finite fraction changes nothing and a fraction out of range is clamped") {
        feed(std::nan(""));
        CHECK(seen.empty());
        feed(7.0);
        CHECK(seen == std::vector<T>{T::EnterWater, T::FullySubmerged});
        feed(-3.0);
        CHECK(seen.back() == T::LeaveWater);
    }
}

TEST_CASE("water events: the settings are validated with a message naming the field", "[bullet][events]") {
    btFlatWaterSurface water(0.0);
    EventsWorld w(&water);
    const btBuoyancyEventSettings good;
    const auto refused = [&](btBuoyancyEventSettings s, const char* field) {
        CHECK_THROWS_AS(w.buoyancy.setEventSettings(s), std::invalid_argument);
        CHECK_THROWS_WITH(w.buoyancy.setEventSettings(s), Contains(field));
        CHECK(w.buoyancy.getEventSettings().enterFraction == good.enterFraction);  // unchanged
    };
    btBuoyancyEventSettings s;
    s.enterFraction = std::nan("");
    refused(s, "enterFraction");
    s = good;
    s.leaveFraction = -0.1;
    refused(s, "leaveFraction");
    s = good;
    s.submergedFraction = 1.5;
    refused(s, "submergedFraction");
    s = good;
    s.leaveFraction = s.enterFraction;  // no hysteresis
    refused(s, "leaveFraction");
    s = good;
    s.surfacedFraction = s.submergedFraction;
    refused(s, "surfacedFraction");
    s = good;
    s.enterFraction = 0.995;  // above submergedFraction
    refused(s, "submergedFraction");
    s = good;
    s.leaveFraction = 0.5;
    s.enterFraction = 0.6;
    s.surfacedFraction = 0.4;  // below leaveFraction
    refused(s, "surfacedFraction");
    s = good;
    s.enterFraction = 0.2;
    w.buoyancy.setEventSettings(s);
    CHECK(w.buoyancy.getEventSettings().enterFraction == 0.2);
    CHECK_THROWS_AS(w.buoyancy.addEventListener(nullptr), std::invalid_argument);
}

TEST_CASE("water events: a box dropped onto still water enters once and fires nothing else while it bobs to rest",
          "[bullet][events]") {
    btFlatWaterSurface water(0.0);
    EventsWorld w(&water);
    Recorder rec;
    w.buoyancy.addEventListener(&rec);
    w.buoyancy.addEventListener(&rec);  // twice: ignored
    // A crate of density 400 kg/m³ released with its bottom 2 cm above the water. Archimedes: it floats with a draft
    // of 0.4 × 0.5 m = 0.2 m; released from d above, it plunges to the draft x where ½ ρ_w g A x² = m g (d + x),
    // 0.42 m (under 0.99 × 0.5 m: it does not go under) and, damped, bobs back up without leaving the water (undamped
    // it would rise back to 2 cm above it). It enters at a draft of enterFraction × 0.5 m: under gravity alone (no
    // water touches it before) symplectic Euler puts it at y0 − g dt² n(n+1)/2 after n substeps.
    const double drop = 0.02, enterDraft = w.buoyancy.getEventSettings().enterFraction * 0.5;
    const std::size_t crate = w.addCrate(400.0, btVector3(0, btScalar(drop + 0.25), 0));
    const btRigidBody* body = w.bodies[crate]->getRigidBody();
    w.run(20.0);
    REQUIRE(rec.entries.size() == 1);
    const Recorder::Entry& e = rec.entries[0];
    CHECK(e.type == T::EnterWater);
    CHECK(e.callback == T::EnterWater);
    CHECK(e.body == body);
    CHECK(e.waterBody == -1);
    CHECK(e.waterName.empty());
    CHECK(e.fraction >= 0.01);
    int n = 0;  // the first substep whose free fall reaches the enter draft: the earliest entry
    while (kGravity * kSubstep * kSubstep * 0.5 * double(n) * double(n + 1) < drop + enterDraft) ++n;
    // The latest: on touching the water (substep nTouch, speed g dt nTouch) the crate takes on its bottom's heave added
    // mass c_wp ρ A^(3/2) (design.md 2.7: 200 kg, as much as its own) with the momentum of the water entry, slowing to
    // m / (m + m_a) of its speed; heavier than the water it displaces down to the enter draft, it does not slow further.
    int nTouch = 0;
    while (kGravity * kSubstep * kSubstep * 0.5 * double(nTouch) * double(nTouch + 1) < drop) ++nTouch;
    const double m = 400.0 * 0.5, ma = btBuoyancySettings().addedMassWaterplaneCoefficient * 1000.0 * 1.0;
    const double latest = nTouch * kSubstep + enterDraft / (kGravity * kSubstep * nTouch * m / (m + ma));
    INFO("entered at " << e.time << " s, free fall " << n * kSubstep << " s, latest " << latest << " s");
    CHECK(e.time >= (n - 1.5) * kSubstep);
    CHECK(e.time <= latest + 1.5 * kSubstep);
    CHECK(e.substep == std::uint64_t(std::lround(e.time / kSubstep)));
    const btBuoyancyAction& action = *w.actions[crate];
    CHECK(action.isInWater());
    CHECK_FALSE(action.isFullySubmerged());
    CHECK(action.getWaterBody() == -1);
    // Archimedes: 400 / 1000 of its volume under water at rest.
    CHECK(action.getSubmergedFraction() == Approx(0.4).margin(0.005));
}

TEST_CASE("water events: a dense body sinking fires fully submerged once", "[bullet][events]") {
    btFlatWaterSurface water(0.0);
    EventsWorld w(&water);
    Recorder rec;
    w.buoyancy.addEventListener(&rec);
    const std::size_t stone = w.addCrate(2000.0, btVector3(0, 0.75, 0));
    w.run(5.0);
    const btRigidBody* body = w.bodies[stone]->getRigidBody();
    CHECK(rec.typesOf(body) == std::vector<T>{T::EnterWater, T::FullySubmerged});
    REQUIRE(rec.entries.size() == 2);
    CHECK(rec.entries[1].fraction >= 0.99);
    CHECK(rec.entries[1].time > rec.entries[0].time);
    const btBuoyancyAction& action = *w.actions[stone];
    CHECK(action.isFullySubmerged());
    CHECK(action.getSubmergedFraction() == Approx(1.0).margin(1e-9));  // wholly under flat water
    CHECK(double(body->getCenterOfMassPosition().y()) < -5.0);          // still sinking
}

TEST_CASE("water events: a body lifted out of a pool leaves it once", "[bullet][events]") {
    btFlatWaterSurface pool(0.0);
    EventsWorld w(nullptr);
    w.buoyancy.addWaterBody(btWaterBodyInfo{"pool", &pool, 1000.0, btVector3(-5, -3, -5), btVector3(5, 1, 5)});
    Recorder rec;
    w.buoyancy.addEventListener(&rec);
    const std::size_t crate = w.addCrate(500.0, btVector3(0, 0.3, 0));
    w.run(3.0);
    btRigidBody* body = w.bodies[crate]->getRigidBody();
    CHECK(rec.typesOf(body) == std::vector<T>{T::EnterWater});
    CHECK(w.actions[crate]->getWaterBody() == 0);
    // A crane lifts it 3 m above the water and holds it there (no gravity, no velocity).
    body->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 3, 0)));
    body->setLinearVelocity(btVector3(0, 0, 0));
    body->setAngularVelocity(btVector3(0, 0, 0));
    body->setGravity(btVector3(0, 0, 0));
    body->activate(true);
    const std::uint64_t liftedAt = w.buoyancy.getSubstep();
    w.run(1.0);
    REQUIRE(rec.entries.size() == 2);
    const Recorder::Entry& leave = rec.entries[1];
    CHECK(leave.type == T::LeaveWater);
    CHECK(leave.callback == T::LeaveWater);
    CHECK(leave.waterBody == 0);
    CHECK(leave.waterName == "pool");
    CHECK(leave.fraction == 0.0);
    CHECK(leave.substep == liftedAt + 1);  // the first substep after the lift
    CHECK_FALSE(w.actions[crate]->isInWater());
    CHECK(w.actions[crate]->getWaterBody() == -1);
    CHECK(w.actions[crate]->getSubmergedFraction() == 0.0);
}

TEST_CASE("water events: a body bobbing about a threshold fires a few events and not one per substep",
          "[bullet][events]") {
    // A crate of density 980 kg/m³ (Archimedes: 98 % under water at rest) without drag, released at rest with 97.5 %
    // of its volume under water: it bobs about 98 % with an amplitude of 0.5 % of its volume for ever, crossing 0.98
    // twice per bob. The fully submerged threshold is put at 0.98, the surfaced one at 0.97 (a gap wider than the
    // bob): it becomes fully submerged once and stays so. With a gap of 1e-4 instead it fires at every crossing.
    const auto runBobbing = [](const btBuoyancyEventSettings& settings, int& crossings, int& substeps) {
        btFlatWaterSurface water(0.0);
        EventsWorld w(&water);
        w.buoyancy.setEventSettings(settings);
        Recorder rec;
        w.buoyancy.addEventListener(&rec);
        const double height = 0.5, startDraft = 0.975 * height;
        const std::size_t crate = w.addCrate(980.0, btVector3(0, btScalar(0.5 * height - startDraft), 0));
        btBuoyancySettings undamped;
        undamped.dragCoefficient = 0;
        undamped.linearDamping = 0;
        undamped.radiationDamping = 0;
        w.actions[crate]->setSettings(undamped);
        const btBuoyancyAction& action = *w.actions[crate];
        crossings = substeps = 0;
        double last = 0;
        for (int i = 0; i < 240 * 20; ++i) {
            w.world.stepSimulation(btScalar(kSubstep), 1, btScalar(kSubstep));
            const double f = action.getSubmergedFraction();
            if (i > 0 && (f >= 0.98) != (last >= 0.98)) ++crossings;
            CHECK(f > 0.97);  // the bob stays within the default gap
            last = f;
            ++substeps;
        }
        CHECK(rec.count(T::EnterWater) == 1);
        CHECK(rec.count(T::LeaveWater) == 0);
        CHECK(rec.count(T::FullySubmerged) - rec.count(T::Surfaced) >= 0);
        CHECK(rec.count(T::FullySubmerged) - rec.count(T::Surfaced) <= 1);
        return rec.entries.size();
    };
    btBuoyancyEventSettings wide;
    wide.submergedFraction = 0.98;
    wide.surfacedFraction = 0.97;
    int crossings = 0, substeps = 0;
    const std::size_t events = runBobbing(wide, crossings, substeps);
    btBuoyancyEventSettings narrow = wide;
    narrow.surfacedFraction = 0.9799;
    int narrowCrossings = 0;
    const std::size_t narrowEvents = runBobbing(narrow, narrowCrossings, substeps);
    INFO("gap 0.01: " << events << " events, " << crossings << " crossings of 0.98; gap 1e-4: " << narrowEvents
                      << " events, " << narrowCrossings << " crossings");
    CHECK(crossings >= 20);  // it does bob about the threshold: about 13 bobs in 20 s
    CHECK(events == 2);      // enter, then fully submerged once
    CHECK(int(narrowEvents) >= narrowCrossings - 1);  // without hysteresis: nearly one event per crossing
    CHECK(int(narrowEvents) * 10 < substeps);         // (still not one per substep: the bob is smooth)
}

TEST_CASE("water events: in two water bodies each body reports its own", "[bullet][events]") {
    btFlatWaterSurface pool(0.0), lake(1.5);
    EventsWorld w(nullptr);
    w.buoyancy.addWaterBody(btWaterBodyInfo{"pool", &pool, 1000.0, btVector3(-6, -3, -3), btVector3(-1, 1, 3)});
    w.buoyancy.addWaterBody(btWaterBodyInfo{"lake", &lake, 1025.0, btVector3(1, -3, -3), btVector3(9, 2.5, 3)});
    Recorder rec;
    w.buoyancy.addEventListener(&rec);
    // Released 2 cm above each water (density 400: they do not go under nor jump out, see the dropped crate).
    const std::size_t inPool = w.addCrate(400.0, btVector3(-3.5, btScalar(0.27), 0));
    const std::size_t inLake = w.addCrate(400.0, btVector3(5, btScalar(1.77), 0));
    const std::size_t onLand = w.addCrate(400.0, btVector3(20, btScalar(0.27), 0));
    w.run(15.0);
    CHECK(w.actions[inPool]->getWaterBody() == 0);
    CHECK(w.actions[inLake]->getWaterBody() == 1);
    CHECK(w.actions[onLand]->getWaterBody() == -1);
    CHECK_FALSE(w.actions[onLand]->isInWater());
    CHECK(w.actions[onLand]->getSubmergedFraction() == 0.0);
    REQUIRE(rec.entries.size() == 2);
    for (const Recorder::Entry& e : rec.entries) {
        CHECK(e.type == T::EnterWater);
        if (e.body == w.bodies[inPool]->getRigidBody()) {
            CHECK(e.waterBody == 0);
            CHECK(e.waterName == "pool");
        } else {
            CHECK(e.body == w.bodies[inLake]->getRigidBody());
            CHECK(e.waterBody == 1);
            CHECK(e.waterName == "lake");
        }
    }
    // Archimedes in each water: 400/1000 and 400/1025 of the volume under water.
    CHECK(w.actions[inPool]->getSubmergedFraction() == Approx(0.4).margin(0.005));
    CHECK(w.actions[inLake]->getSubmergedFraction() == Approx(400.0 / 1025.0).margin(0.005));
}

TEST_CASE("water events: a Z-up world", "[bullet][events]") {
    // Gravity along −z: the water frame's up is +z, the flat water the plane z = 0.5. The crate's mesh is 1 m along
    // z here; of density 400 and released 2 cm above the water it enters once and floats with 40 % of its volume
    // under water: a draft of 0.4 m, its centre at 0.5 − 0.4 + 0.5 = 0.6 m.
    btFlatWaterSurface water(0.5);
    EventsWorld w(&water, btVector3(0, 0, btScalar(-kGravity)));
    Recorder rec;
    w.buoyancy.addEventListener(&rec);
    const double drop = 0.02;
    const std::size_t crate = w.addCrate(400.0, btVector3(2, 3, btScalar(1.0 + drop)));
    w.run(15.0);
    CHECK(rec.typesOf(w.bodies[crate]->getRigidBody()) == std::vector<T>{T::EnterWater});
    // It enters after falling the drop plus the enter draft (1 % of 1 m).
    REQUIRE(rec.entries.size() == 1);
    const double fall = drop + 0.01;
    CHECK(std::abs(rec.entries[0].time - std::sqrt(2 * fall / kGravity)) <= 2 * kSubstep);
    CHECK(w.actions[crate]->getSubmergedFraction() == Approx(0.4).margin(0.005));
    const double z = double(w.bodies[crate]->getRigidBody()->getCenterOfMassPosition().z());
    CHECK(z == Approx(0.6).margin(0.01));
}

TEST_CASE("water events: the same events in the same order on one thread on two and without batching",
          "[bullet][events]") {
    // Crates of several densities, some dropped, some lifted out later: the events (type, body, water body, substep)
    // do not depend on how the bodies were evaluated.
    const auto runScene = [](int threads, bool batching) {
        btFlatWaterSurface water(0.0);
        EventsWorld w(&water);
        w.buoyancy.setThreads(threads);
        w.buoyancy.setBatching(batching);
        Recorder rec;
        w.buoyancy.addEventListener(&rec);
        const double densities[6] = {300, 600, 900, 985, 1500, 3000};
        for (int i = 0; i < 6; ++i) w.addCrate(densities[i], btVector3(btScalar(3 * i), btScalar(0.5 + 0.3 * i), 0));
        w.run(2.0);
        btRigidBody* lifted = w.bodies[1]->getRigidBody();
        lifted->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(3, 2, 0)));
        lifted->activate(true);
        w.run(2.0);
        std::vector<std::string> out;
        for (const Recorder::Entry& e : rec.entries) {
            std::size_t index = 0;
            while (w.bodies[index]->getRigidBody() != e.body) ++index;
            out.push_back(std::string(btBuoyancyEventTypeName(e.type)) + " body " + std::to_string(index) + " at " +
                          std::to_string(e.substep));
        }
        return out;
    };
    const std::vector<std::string> one = runScene(1, true);
    CHECK(one.size() >= 10);  // six enters, two submerged, the lifted body's leave and re-entry
    CHECK(runScene(2, true) == one);
    CHECK(runScene(1, false) == one);
}

TEST_CASE("water events: listeners in registration order and bodies in the Bullet world's action order",
          "[bullet][events]") {
    btFlatWaterSurface water(0.0);
    EventsWorld w(&water);
    struct Tagged : btBuoyancyEventListener {
        std::vector<std::string>* log;
        std::string tag;
        void onEnterWater(const btBuoyancyEvent& e) override {
            log->push_back(tag + ":" + std::to_string(e.body->getUserIndex()));
        }
    };
    std::vector<std::string> log;
    Tagged first, second;
    first.log = second.log = &log;
    first.tag = "first";
    second.tag = "second";
    w.buoyancy.addEventListener(&second);
    w.buoyancy.addEventListener(&first);
    // Two crates dropped side by side enter in the same substep; their actions are added to the Bullet world in the
    // opposite order of their creation.
    const std::size_t a = w.addCrate(500.0, btVector3(0, 0.5, 0), false);
    const std::size_t b = w.addCrate(500.0, btVector3(3, 0.5, 0), false);
    w.bodies[a]->getRigidBody()->setUserIndex(0);
    w.bodies[b]->getRigidBody()->setUserIndex(1);
    w.world.addAction(w.actions[b].get());
    w.world.addAction(w.actions[a].get());
    w.run(1.0);
    CHECK(log == std::vector<std::string>{"second:1", "first:1", "second:0", "first:0"});
}

TEST_CASE("water events: what a callback may and may not do", "[bullet][events]") {
    btFlatWaterSurface water(0.0);
    EventsWorld w(&water);
    struct Meddler : btBuoyancyEventListener {
        EventsWorld* w = nullptr;
        btBuoyancyEventListener* late = nullptr;
        std::vector<std::string> refusals;
        int calls = 0;
        void onEnterWater(const btBuoyancyEvent& e) override {
            ++calls;
            try {
                btBuoyancyAction action(e.body, e.action->getShape(), &w->buoyancy);
            } catch (const std::logic_error& error) {
                refusals.push_back(error.what());
            }
            btFlatWaterSurface other(0.0);
            try {
                w->buoyancy.addWaterBody(btWaterBodyInfo{"tank", &other, 1000.0, btVector3(0, 0, 0), btVector3(1, 1, 1)});
            } catch (const std::logic_error& error) {
                refusals.push_back(error.what());
            }
            try {
                w->buoyancy.removeAllWaterBodies();
            } catch (const std::logic_error& error) {
                refusals.push_back(error.what());
            }
            CHECK(w->buoyancy.isDispatchingEvents());
            w->buoyancy.removeEventListener(this);  // once is enough: no further event
            w->buoyancy.addEventListener(late);     // from the next event on
            e.body->applyCentralImpulse(btVector3(0, 1, 0));  // allowed
        }
    };
    Recorder late;
    Meddler meddler;
    meddler.w = &w;
    meddler.late = &late;
    w.buoyancy.addEventListener(&meddler);
    w.addCrate(2000.0, btVector3(0, 0.5, 0));  // enters, then fully submerged
    w.run(3.0);
    CHECK(meddler.calls == 1);
    REQUIRE(meddler.refusals.size() == 3);
    CHECK_THAT(meddler.refusals[0], Contains("btBuoyancyAction") && Contains("water event callback"));
    CHECK_THAT(meddler.refusals[1], Contains("addWaterBody") && Contains("water event callback"));
    CHECK_THAT(meddler.refusals[2], Contains("removeAllWaterBodies") && Contains("water event callback"));
    CHECK(w.buoyancy.getActions().size() == 1);
    CHECK(w.buoyancy.getWaterBodies().empty());
    // The late listener did not receive the enter event it was added in, but the next one.
    CHECK(late.typesOf(w.bodies[0]->getRigidBody()) == std::vector<T>{T::FullySubmerged});
    CHECK(w.buoyancy.getEventListeners() == std::vector<btBuoyancyEventListener*>{&late});
    CHECK_FALSE(w.buoyancy.isDispatchingEvents());
}

TEST_CASE("water events: an exception thrown by a callback leaves stepSimulation and the world usable",
          "[bullet][events]") {
    btFlatWaterSurface water(0.0);
    EventsWorld w(&water);
    struct Thrower : btBuoyancyEventListener {
        void onEnterWater(const btBuoyancyEvent&) override { throw std::runtime_error("game logic failed"); }
    } thrower;
    w.buoyancy.addEventListener(&thrower);
    w.addCrate(500.0, btVector3(0, 0.3, 0));
    bool thrown = false;
    for (int i = 0; i < 60 && !thrown; ++i) {
        try {
            w.world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(kSubstep));
        } catch (const std::runtime_error& error) {
            thrown = std::string(error.what()) == "game logic failed";
        }
    }
    CHECK(thrown);
    CHECK_FALSE(w.buoyancy.isDispatchingEvents());
    w.buoyancy.removeEventListener(&thrower);
    CHECK_NOTHROW(w.addCrate(500.0, btVector3(3, 0.3, 0)));  // creating actions works again
    CHECK(w.actions[0]->isInWater());  // the state advanced before the callback threw
}
