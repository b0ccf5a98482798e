// Save and restore (btBuoyancyState.h; btBuoyancyWorld, btBuoyancyAction, btFloodingAction, btTimeVaryingMassAction,
// btBuoyantBody and btInteractiveWaterCoupler saveState / restoreState): a scene in Gerstner waves with the temporal
// level of detail on (the default), water graphs filling through holes and time-varying density maps is run, saved,
// run on, restored and run again: the trajectory after the restore is the first one to the bit (every body's
// transform, velocities and activation state at every substep), in the same scene and in a second scene built the
// same way, in calm water where bodies fall asleep, and in interactive water (its grid and the footprints fed to it
// restored); the water events after the restore are the first ones; leaving out a piece of the state (the world's
// clock, the actions', the interactive water's) gives another trajectory, so the comparison can fail; bad blobs
// (truncated at every length, a wrong magic, version, precision or kind, a corrupted byte, another body's blob) throw
// std::invalid_argument naming the problem and change nothing; a restore from an event callback is refused.
#include "MultiBodyChainScene.h"

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>
#include <BulletBuoyancy/bullet/btBuoyancyImmediate.h>
#include <BulletBuoyancy/bullet/btBuoyancyMultiBodyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>
#include <BulletBuoyancy/bullet/btInteractiveWaterCoupler.h>
#include <BulletBuoyancy/bullet/btMarineHydrodynamics.h>
#include <BulletBuoyancy/bullet/btTimeVaryingMassAction.h>
#include <BulletBuoyancy/graph/WaterIngress.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using Catch::Matchers::Contains;

namespace {

constexpr double kSubstep = 1.0 / 120.0;  ///< s

/// What the user saves of a btRigidBody's own state for a bit-identical restore (docs/integration.md "Save and
/// restore"): the transforms, the velocities, the interpolation state, the activation state, the deactivation time and
/// the sleeping thresholds (the buoyancy action sets these while the body is in the water). Forces need not be saved:
/// stepSimulation clears them before it returns.
struct RigidBodyState {
    btTransform worldTransform, interpolationTransform;
    btVector3 linearVelocity, angularVelocity, interpolationLinearVelocity, interpolationAngularVelocity;
    int activationState = 0;
    btScalar deactivationTime = 0, linearSleepingThreshold = 0, angularSleepingThreshold = 0;

    static RigidBodyState save(const btRigidBody& b) {
        RigidBodyState s;
        s.worldTransform = b.getWorldTransform();
        s.interpolationTransform = b.getInterpolationWorldTransform();
        s.linearVelocity = b.getLinearVelocity();
        s.angularVelocity = b.getAngularVelocity();
        s.interpolationLinearVelocity = b.getInterpolationLinearVelocity();
        s.interpolationAngularVelocity = b.getInterpolationAngularVelocity();
        s.activationState = b.getActivationState();
        s.deactivationTime = b.getDeactivationTime();
        s.linearSleepingThreshold = b.getLinearSleepingThreshold();
        s.angularSleepingThreshold = b.getAngularSleepingThreshold();
        return s;
    }
    /// Call after btBuoyantBody::restoreState where the body's mass properties change (the world inertia follows).
    void restore(btRigidBody& b) const {
        b.setCenterOfMassTransform(worldTransform);  // also updates the world inverse inertia from the restored basis
        b.setInterpolationWorldTransform(interpolationTransform);
        b.setLinearVelocity(linearVelocity);
        b.setAngularVelocity(angularVelocity);
        b.setInterpolationLinearVelocity(interpolationLinearVelocity);
        b.setInterpolationAngularVelocity(interpolationAngularVelocity);
        b.forceActivationState(activationState);
        b.setDeactivationTime(deactivationTime);
        b.setSleepingThresholds(linearSleepingThreshold, angularSleepingThreshold);
        b.clearForces();
    }
};

std::vector<btGerstnerWave> sea() {
    std::vector<btGerstnerWave> w(3);
    w[0] = {0.5, 30.0, 1.0, 0.0, 0.5, 0.0};
    w[1] = {0.3, 17.0, 0.8, 0.6, 0.5, 1.3};
    w[2] = {0.15, 9.0, -0.3, 1.0, 0.5, 2.1};
    return w;
}

/// One water event as recorded by the listener.
struct Recorded {
    btBuoyancyEventType type;
    int body;  ///< index in the scene's bodies
    int waterBody;
    double fraction, time;
    std::uint64_t substep;
    bool operator==(const Recorded& o) const {
        return type == o.type && body == o.body && waterBody == o.waterBody &&
               std::memcmp(&fraction, &o.fraction, sizeof fraction) == 0 &&
               std::memcmp(&time, &o.time, sizeof time) == 0 && substep == o.substep;
    }
};

struct Recorder : btBuoyancyEventListener {
    const std::vector<std::unique_ptr<btBuoyantBody>>* bodies = nullptr;
    std::vector<Recorded> events;
    void record(const btBuoyancyEvent& e) {
        int index = -1;
        for (std::size_t i = 0; i < bodies->size(); ++i)
            if ((*bodies)[i]->getRigidBody() == e.body) index = int(i);
        events.push_back(Recorded{e.type, index, e.waterBody, e.submergedFraction, e.time, e.substep});
    }
    void onEnterWater(const btBuoyancyEvent& e) override { record(e); }
    void onLeaveWater(const btBuoyancyEvent& e) override { record(e); }
    void onFullySubmerged(const btBuoyancyEvent& e) override { record(e); }
    void onSurfaced(const btBuoyancyEvent& e) override { record(e); }
};

/// Everything saved of a scene.
struct Snapshot {
    std::vector<unsigned char> world;
    std::vector<std::vector<unsigned char>> actions, floods, masses, bodies;
    std::vector<unsigned char> coupler;  ///< the interactive water's, when the scene has one
    std::vector<RigidBodyState> rigid;
};

/// What a restore leaves out (to show that the comparison can fail).
enum class Omit { Nothing, WorldClock, Actions, InteractiveWater };

/// Boxes and balls in Gerstner waves with the library's default settings (temporal level of detail, drag clusters,
/// water patch), some dropped from above the water (events), some with a water graph filling through a hole in the
/// bottom, some with a density map that changes every 0.05 s; far enough apart never to touch.
struct Scene {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btGerstnerWaterSurface gerstner{sea()};
    btBuoyancyWorld water;
    std::vector<std::unique_ptr<btBuoyantBody>> bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> actions;
    std::vector<std::unique_ptr<btFloodingAction>> floods;
    std::vector<std::unique_ptr<btTimeVaryingMassAction>> masses;
    std::unique_ptr<btInteractiveWaterCoupler> coupler;
    std::vector<btActionInterface*> added;
    Recorder recorder;

    /// @param surface      the water (nullptr: the Gerstner sea)
    /// @param interactive  the surface is this interactive grid: its coupler is added after every other action
    explicit Scene(const btWaterSurface* surface = nullptr, btInteractiveWaterSurface* interactive = nullptr)
        : water(&world, interactive ? interactive : surface ? surface : &gerstner, 1025.0) {
        world.setGravity(btVector3(0, btScalar(-9.81), 0));
        water.setThreads(1);
        water.addEventListener(&recorder);
        recorder.bodies = &bodies;
        auto box = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 0.8, 1.0));
        auto ball = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.6, 24, 12));
        buoyancy::WaterGraph graph;
        buoyancy::WaterNode node;
        node.name = "hold";
        node.capacity = 0.5;
        graph.nodes = {node};
        const int n = 8;
        for (int i = 0; i < n; ++i) {
            const auto& shape = i % 4 == 3 ? ball : box;
            btBuoyantBodySettings s;
            s.density = 350.0 + 60.0 * (i % 5);
            btTransform t = btTransform::getIdentity();
            t.setRotation(btQuaternion(btVector3(btScalar(0.1), 1, btScalar(0.2)).normalized(), btScalar(0.7 * i)));
            t.setOrigin(btVector3(btScalar(5.0 * (i % 4)), btScalar(i % 2 == 0 ? 1.2 : 0.1), btScalar(5.0 * (i / 4))));
            bodies.push_back(std::make_unique<btBuoyantBody>(shape, s, t));
            world.addRigidBody(bodies.back()->getRigidBody());
        }
        for (int i = 1; i < n; i += 4) {  // density maps on bodies 1 and 5, before the buoyancy actions
            btBuoyantBodySettings s;
            s.mass = 500.0;
            masses.push_back(std::make_unique<btTimeVaryingMassAction>(
                *bodies[std::size_t(i)], &water, s, [](double t) { return std::int64_t(std::floor(t / 0.05)); },
                [](double t, const Eigen::Vector3d& p) { return 1.0 + 0.8 * std::sin(3.0 * t + p.x()); }));
            add(masses.back().get());
        }
        for (int i = 0; i < n; ++i) {
            actions.push_back(std::make_unique<btBuoyancyAction>(*bodies[std::size_t(i)], &water));
            if (i == 4) {  // marine hydrodynamics on body 4: its end-of-step state is carried between substeps
                btBuoyancySettings bs = actions.back()->getSettings();
                bs.addedMass = false;
                actions.back()->setSettings(bs);
                actions.back()->setMarineHydrodynamics(btMarineHydrodynamics::fromDerivatives(
                    {-400.0, -900.0, -900.0, -60.0, -120.0, -120.0}, {-50.0, -80.0, -80.0, -10.0, -10.0, -10.0},
                    {-120.0, -200.0, -200.0, -20.0, -20.0, -20.0}));
            }
            add(actions.back().get());
            if (i % 4 == 2) {  // water graphs on bodies 2 and 6
                buoyancy::PermeabilityRegion hole;
                hole.centre = Eigen::Vector3d(0.0, -0.4, 0.0);
                hole.radius = 0.3;
                floods.push_back(std::make_unique<btFloodingAction>(
                    *bodies[std::size_t(i)], &water, graph,
                    buoyancy::permeableSamplesFromRegions(bodies[std::size_t(i)]->getShape()->getDragSamples(),
                                                          {hole}, graph)));
                add(floods.back().get());
            }
        }
        if (interactive) {
            coupler = std::make_unique<btInteractiveWaterCoupler>(interactive, &water);
            add(coupler.get());
        }
    }
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;
    void add(btActionInterface* a) {
        world.addAction(a);
        added.push_back(a);
    }
    ~Scene() {
        water.removeEventListener(&recorder);
        for (btActionInterface* a : added) world.removeAction(a);
        for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
    }

    /// `substeps` fixed substeps (one per stepSimulation call: Bullet keeps no interpolation remainder), recording every
    /// body's transform, velocities and activation state after each, as bytes.
    std::vector<unsigned char> run(int substeps) {
        std::vector<btScalar> v;
        for (int s = 0; s < substeps; ++s) {
            world.stepSimulation(btScalar(kSubstep), 1, btScalar(kSubstep));
            for (const auto& b : bodies) {
                const btRigidBody* rb = b->getRigidBody();
                const btTransform& t = rb->getWorldTransform();
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) v.push_back(t.getBasis()[r][c]);
                for (int k = 0; k < 3; ++k) {
                    v.push_back(t.getOrigin()[k]);
                    v.push_back(rb->getLinearVelocity()[k]);
                    v.push_back(rb->getAngularVelocity()[k]);
                }
                v.push_back(btScalar(rb->getActivationState()));
            }
        }
        std::vector<unsigned char> bytes(v.size() * sizeof(btScalar));
        if (!v.empty()) std::memcpy(bytes.data(), v.data(), bytes.size());
        return bytes;
    }

    Snapshot save() const {
        Snapshot s;
        s.world = water.saveState();
        for (const auto& a : actions) s.actions.push_back(a->saveState());
        for (const auto& f : floods) s.floods.push_back(f->saveState());
        for (const auto& m : masses) s.masses.push_back(m->saveState());
        if (coupler) s.coupler = coupler->saveState();
        for (const auto& b : bodies) {
            s.bodies.push_back(b->saveState());
            s.rigid.push_back(RigidBodyState::save(*b->getRigidBody()));
        }
        return s;
    }

    void restore(const Snapshot& s, Omit omit = Omit::Nothing) {
        if (omit != Omit::WorldClock) water.restoreState(s.world);
        if (omit != Omit::Actions)
            for (std::size_t i = 0; i < actions.size(); ++i) actions[i]->restoreState(s.actions[i]);
        for (std::size_t i = 0; i < floods.size(); ++i) floods[i]->restoreState(s.floods[i]);
        for (std::size_t i = 0; i < masses.size(); ++i) masses[i]->restoreState(s.masses[i]);
        if (coupler && omit != Omit::InteractiveWater) coupler->restoreState(s.coupler);
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            bodies[i]->restoreState(s.bodies[i]);  // mass properties first: the world inertia follows the body's
            s.rigid[i].restore(*bodies[i]->getRigidBody());
        }
    }

    int predictedBodies() const {
        int n = 0;
        for (const auto& a : actions) n += a->getLastResult().predicted ? 1 : 0;
        return n;
    }
};

std::string firstDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
    if (a.size() != b.size()) return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) return "first difference at byte " + std::to_string(i) + " of " + std::to_string(a.size());
    return "identical";
}

}  // namespace

TEST_CASE("save and restore: run on after a restore bit-identically in waves with flooding and density maps",
          "[bullet][state]") {
    Scene scene;
    scene.run(60);  // 0.5 s: the dropped bodies are still falling or just entering
    const Snapshot snapshot = scene.save();

    // The temporal level of detail predicts during the run (its records are part of what is restored).
    int predicted = 0;
    std::vector<unsigned char> first;
    for (int s = 0; s < 240; ++s) {
        const std::vector<unsigned char> step = scene.run(1);
        first.insert(first.end(), step.begin(), step.end());
        predicted += scene.predictedBodies();
    }
    INFO("predicted body-substeps: " << predicted);
    CHECK(predicted > 100);
    double water = 0;
    for (const auto& f : scene.floods) water += f->getWaterVolume();
    CHECK(water > 1e-3);  // the holds took water in
    for (const auto& m : scene.masses) CHECK(m->getRecomputeCount() > 30);

    scene.restore(snapshot);
    const std::vector<unsigned char> again = scene.run(240);
    INFO(firstDifference(first, again));
    REQUIRE(first.size() == again.size());
    CHECK(std::memcmp(first.data(), again.data(), first.size()) == 0);
    CHECK(scene.water.getSubstep() == 300);
}

TEST_CASE("save and restore: bodies coming to rest in calm water fall asleep at the same substeps", "[bullet][state]") {
    // In calm water the action decides when a floating body is at rest (its energy above the hydrostatic equilibrium,
    // from the centre of mass's motion since the last substep) and opens Bullet's sleeping thresholds: the sleep state
    // is part of what is restored, and the bodies fall asleep during the run after the save.
    const btFlatWaterSurface flat(0.0);
    Scene scene(&flat);
    scene.run(360);
    const Snapshot snapshot = scene.save();
    int awakeAtSave = 0;
    for (const auto& b : scene.bodies) awakeAtSave += b->getRigidBody()->isActive() ? 1 : 0;
    const std::vector<unsigned char> first = scene.run(1680);
    int asleep = 0;
    for (const auto& b : scene.bodies) asleep += b->getRigidBody()->getActivationState() == ISLAND_SLEEPING ? 1 : 0;
    INFO("awake at the save: " << awakeAtSave << ", asleep at the end: " << asleep);
    CHECK(awakeAtSave >= 6);
    CHECK(asleep >= 1);
    scene.restore(snapshot);
    const std::vector<unsigned char> again = scene.run(1680);
    INFO(firstDifference(first, again));
    REQUIRE(first.size() == again.size());
    CHECK(std::memcmp(first.data(), again.data(), first.size()) == 0);
}

TEST_CASE("save and restore: the interactive water's grid and footprints are restored with the bodies",
          "[bullet][state]") {
    // The bodies push the grid's water aside and read the water they pushed: without the grid's state and the
    // footprints last fed to it the run after the restore differs; with them it is the first run.
    for (const Omit omit : {Omit::Nothing, Omit::InteractiveWater}) {
        btInteractiveWaterSurface grid(30.0, 15.0, 90, 2.0, 0.1, 0.0, 7.5, 2.5);
        Scene scene(nullptr, &grid);
        scene.run(60);
        const Snapshot snapshot = scene.save();
        const std::vector<unsigned char> first = scene.run(240);
        double lo = 0, hi = 0;
        grid.heightBounds(-7.5, -5.0, 22.5, 10.0, 0.0, lo, hi);
        CHECK(hi - lo > 1e-3);  // the bodies made waves
        scene.restore(snapshot, omit);
        const std::vector<unsigned char> again = scene.run(240);
        REQUIRE(first.size() == again.size());
        if (omit == Omit::Nothing) {
            INFO(firstDifference(first, again));
            CHECK(std::memcmp(first.data(), again.data(), first.size()) == 0);
        } else {
            CHECK(std::memcmp(first.data(), again.data(), first.size()) != 0);
        }
    }
}

TEST_CASE("save and restore: a second scene built the same way continues the first one bit-identically",
          "[bullet][state]") {
    Scene a;
    a.run(90);
    const Snapshot snapshot = a.save();
    const std::vector<unsigned char> first = a.run(180);

    Scene b;
    b.run(7);  // a different history before the restore: everything it carries is replaced
    b.restore(snapshot);
    const std::vector<unsigned char> replay = b.run(180);
    INFO(firstDifference(first, replay));
    REQUIRE(first.size() == replay.size());
    CHECK(std::memcmp(first.data(), replay.data(), first.size()) == 0);
}

TEST_CASE("save and restore: a restore that leaves out a piece of the state gives another trajectory",
          "[bullet][state]") {
    // The comparison of the other tests can fail: without the world's clock, or without the actions' state (the
    // temporal level-of-detail records, warm starts, sleep and event states), the run after the restore differs.
    for (const Omit omit : {Omit::WorldClock, Omit::Actions}) {
        Scene scene;
        scene.run(60);
        const Snapshot snapshot = scene.save();
        const std::vector<unsigned char> first = scene.run(120);
        scene.restore(snapshot, omit);
        const std::vector<unsigned char> again = scene.run(120);
        INFO("omitted: " << (omit == Omit::WorldClock ? "the world's clock" : "the actions' state"));
        REQUIRE(first.size() == again.size());
        CHECK(std::memcmp(first.data(), again.data(), first.size()) != 0);
    }
}

TEST_CASE("save and restore: the water events after a restore are the first run's", "[bullet][state]") {
    Scene scene;
    scene.run(30);  // 0.25 s: the bodies dropped from 1.2 m are still falling
    const Snapshot snapshot = scene.save();
    std::vector<bool> inWaterAtSave;
    for (const auto& a : scene.actions) inWaterAtSave.push_back(a->isInWater());
    const std::size_t before = scene.recorder.events.size();
    scene.run(300);
    const std::vector<Recorded> first(scene.recorder.events.begin() + std::ptrdiff_t(before), scene.recorder.events.end());
    int enters = 0;
    for (const Recorded& e : first) enters += e.type == btBuoyancyEventType::EnterWater ? 1 : 0;
    CHECK(enters >= 2);  // dropped bodies that were still above the waves at the save
    REQUIRE(first.size() >= 2);
    std::vector<bool> inWater;
    for (const auto& a : scene.actions) inWater.push_back(a->isInWater());

    scene.restore(snapshot);
    // The events' states are restored with the actions: the getters say what they said at the save.
    for (std::size_t i = 0; i < scene.actions.size(); ++i) CHECK(scene.actions[i]->isInWater() == inWaterAtSave[i]);
    scene.recorder.events.clear();
    scene.run(300);
    REQUIRE(scene.recorder.events.size() == first.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
        INFO("event " << i << ": " << btBuoyancyEventTypeName(first[i].type) << " of body " << first[i].body);
        CHECK(scene.recorder.events[i] == first[i]);
    }
    for (std::size_t i = 0; i < scene.actions.size(); ++i) CHECK(scene.actions[i]->isInWater() == inWater[i]);
}

TEST_CASE("save and restore: bad blobs throw a clear error and change nothing", "[bullet][state]") {
    Scene scene;
    scene.run(40);
    btBuoyancyAction& action = *scene.actions[0];
    const std::vector<unsigned char> blob = action.saveState();
    const std::vector<unsigned char> world = scene.water.saveState();
    REQUIRE(blob.size() > 100);
    scene.run(5);  // the state now differs from the blob's
    const std::vector<unsigned char> current = action.saveState();
    const std::vector<unsigned char> currentWorld = scene.water.saveState();
    REQUIRE(current != blob);

    SECTION("truncated at every length") {
        for (std::size_t n = 0; n < blob.size(); ++n) {
            INFO("length " << n);
            CHECK_THROWS_AS(action.restoreState(blob.data(), n), std::invalid_argument);
            CHECK_THROWS_WITH(action.restoreState(blob.data(), n), Contains("truncated"));
        }
        for (std::size_t n = 0; n < world.size(); ++n)
            CHECK_THROWS_WITH(scene.water.restoreState(world.data(), n), Contains("truncated"));
        std::vector<unsigned char> longer = blob;
        longer.push_back(0);
        CHECK_THROWS_WITH(action.restoreState(longer), Contains("trailing"));
    }
    SECTION("a wrong magic") {
        std::vector<unsigned char> bad = blob;
        bad[0] ^= 0xFF;
        CHECK_THROWS_AS(action.restoreState(bad), std::invalid_argument);
        CHECK_THROWS_WITH(action.restoreState(bad), Contains("btBuoyancyAction::restoreState") && Contains("magic"));
    }
    SECTION("another format version") {
        std::vector<unsigned char> bad = blob;
        bad[4] = static_cast<unsigned char>(bad[4] + 1);
        CHECK_THROWS_WITH(action.restoreState(bad),
                          Contains("format version " + std::to_string(btBuoyancyStateFormatVersion + 1)));
    }
    SECTION("the other precision") {
        std::vector<unsigned char> bad = blob;
        bad[6] = sizeof(btScalar) == 8 ? 4 : 8;
        CHECK_THROWS_WITH(action.restoreState(bad), Contains("precision"));
        CHECK_THROWS_WITH(action.restoreState(bad), Contains("(btScalar of " + std::to_string(bad[6]) + " bytes)"));
    }
    SECTION("another kind of blob") {
        CHECK_THROWS_WITH(action.restoreState(world), Contains("btBuoyancyWorld state") && Contains("expected a btBuoyancyAction"));
        CHECK_THROWS_WITH(scene.water.restoreState(blob), Contains("expected a btBuoyancyWorld"));
        CHECK_THROWS_WITH(scene.floods[0]->restoreState(blob), Contains("expected a btFloodingAction"));
        CHECK_THROWS_WITH(scene.masses[0]->restoreState(blob), Contains("expected a btTimeVaryingMassAction"));
        CHECK_THROWS_WITH(scene.bodies[0]->restoreState(blob), Contains("expected a btBuoyantBody"));
    }
    SECTION("a corrupted payload byte") {
        std::vector<unsigned char> bad = blob;
        bad[blob.size() / 2] ^= 0x01;
        CHECK_THROWS_WITH(action.restoreState(bad), Contains("checksum"));
    }
    SECTION("a body with another mesh") {
        // Body 3 is a ball: other samples, vertices and drag clusters than the box of body 0.
        CHECK_THROWS_WITH(scene.actions[3]->restoreState(blob), Contains("vertex count is 8 in the blob"));
        const std::vector<unsigned char> flood = scene.floods[0]->saveState();
        buoyancy::WaterGraph graph;
        buoyancy::WaterNode a, b;
        a.name = "fore";
        b.name = "aft";
        a.capacity = b.capacity = 0.2;
        b.position = Eigen::Vector3d(0.5, 0, 0);
        graph.nodes = {a, b};
        graph.edges = {buoyancy::WaterEdge{0, 1, 0.05, 0.5, 1.0}};
        btFloodingAction other(*scene.bodies[2], &scene.water, graph);
        CHECK_THROWS_WITH(other.restoreState(flood), Contains("node count is 1 in the blob, 2 here"));
    }
    // Nothing changed by any of the failures.
    CHECK(action.saveState() == current);
    CHECK(scene.water.saveState() == currentWorld);
    // And the good blobs restore.
    action.restoreState(blob);
    CHECK(action.saveState() == blob);
    scene.water.restoreState(world);
    CHECK(scene.water.saveState() == world);
}

TEST_CASE("save and restore: a restore from an event callback is refused", "[bullet][state]") {
    Scene scene;
    scene.run(2);
    const std::vector<unsigned char> world = scene.water.saveState();
    const std::vector<unsigned char> action = scene.actions[0]->saveState();
    struct Restorer : btBuoyancyEventListener {
        btBuoyancyWorld* water = nullptr;
        btBuoyancyAction* action = nullptr;
        const std::vector<unsigned char>* worldBlob = nullptr;
        const std::vector<unsigned char>* actionBlob = nullptr;
        std::vector<std::string> messages;
        void onEnterWater(const btBuoyancyEvent&) override {
            try {
                water->restoreState(*worldBlob);
            } catch (const std::logic_error& e) {
                messages.push_back(e.what());
            }
            try {
                action->restoreState(*actionBlob);
            } catch (const std::logic_error& e) {
                messages.push_back(e.what());
            }
        }
    } restorer;
    restorer.water = &scene.water;
    restorer.action = scene.actions[0].get();
    restorer.worldBlob = &world;
    restorer.actionBlob = &action;
    scene.water.addEventListener(&restorer);
    scene.run(120);
    scene.water.removeEventListener(&restorer);
    REQUIRE(restorer.messages.size() >= 2);
    CHECK_THAT(restorer.messages[0], Contains("btBuoyancyWorld::restoreState") && Contains("between stepSimulation calls"));
    CHECK_THAT(restorer.messages[1], Contains("btBuoyancyAction::restoreState") && Contains("event callback"));
}

namespace {

/// Append the bytes of `v` to `out` (a trajectory compared with memcmp).
template <class T>
void appendBytes(std::vector<unsigned char>& out, const T& v) {
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    out.insert(out.end(), p, p + sizeof v);
}

/// A user's own loop with btBuoyancyImmediate: a tilted box in Gerstner waves (temporal level of detail on).
struct OwnLoop {
    btGerstnerWaterSurface water{sea()};
    btBoxShape box{btVector3(0.6f, 0.25f, 0.4f)};
    std::unique_ptr<btRigidBody> body;
    std::unique_ptr<btBuoyancyImmediate> buoyancy;
    double time = 0;
    const btVector3 gravity{0, btScalar(-9.81), 0};

    explicit OwnLoop(const btVector3& half = btVector3(0.6f, 0.25f, 0.4f)) : box(half) {
        const btScalar mass = btScalar(450.0 * 8 * double(half.x() * half.y() * half.z()));
        btVector3 inertia;
        box.calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &box, inertia);
        info.m_startWorldTransform.setOrigin(btVector3(0.3f, 0.4f, -0.2f));
        info.m_startWorldTransform.setRotation(btQuaternion(btVector3(1, 0.2f, 0.4f).normalized(), btScalar(0.5)));
        body = std::make_unique<btRigidBody>(info);
        buoyancy = std::make_unique<btBuoyancyImmediate>(body.get());
    }
    /// `n` steps of the loop; the body's transform and velocities after each, as bytes.
    std::vector<unsigned char> run(int n) {
        std::vector<unsigned char> out;
        for (int i = 0; i < n; ++i) {
            body->setLinearVelocity(body->getLinearVelocity() + gravity * btScalar(kSubstep));
            time += kSubstep;
            buoyancy->applyBuoyancyImpulse(water, gravity, 1000.0, time, kSubstep);
            btTransform next;
            body->predictIntegratedTransform(btScalar(kSubstep), next);
            body->proceedToTransform(next);
            appendBytes(out, body->getWorldTransform());
            appendBytes(out, body->getLinearVelocity());
            appendBytes(out, body->getAngularVelocity());
        }
        return out;
    }
};

/// A chain of three boxes joined by hinges in a multibody world (MultiBodyChainScene.h), in Gerstner waves; no contacts.
struct ChainInWaves {
    buoyancy_test::ChainScene scene{3, btVector3(0.5f, 0.2f, 0.3f), 500.0, start()};
    btGerstnerWaterSurface water{sea()};
    btBuoyancyWorld buoyancy{&scene.world, &water, 1000.0};
    btMultiBody* chain = scene.chain.get();
    std::vector<std::unique_ptr<btMultiBodyLinkCollider>>& colliders = scene.colliders;
    std::unique_ptr<btBuoyancyMultiBodyAction> action;

    static btTransform start() {
        btTransform t = btTransform::getIdentity();
        t.setOrigin(btVector3(0, 0.3f, 0));
        t.setRotation(btQuaternion(btVector3(0, 1, 0), btScalar(0.4)));
        return t;
    }
    ChainInWaves() {
        chain->setJointPos(0, btScalar(0.2));
        chain->setJointPos(1, btScalar(-0.3));
        syncColliders();
        action = std::make_unique<btBuoyancyMultiBodyAction>(chain, &buoyancy);
        scene.world.addAction(action.get());
    }
    ~ChainInWaves() { scene.world.removeAction(action.get()); }
    void syncColliders() {
        btAlignedObjectArray<btQuaternion> q;
        btAlignedObjectArray<btVector3> o;
        chain->updateCollisionObjectWorldTransforms(q, o);
    }
    /// `n` substeps; every part's transform and the joint velocities after each, as bytes.
    std::vector<unsigned char> run(int n) {
        std::vector<unsigned char> out;
        for (int i = 0; i < n; ++i) {
            scene.world.stepSimulation(btScalar(kSubstep), 1, btScalar(kSubstep));
            for (const auto& c : colliders) appendBytes(out, c->getWorldTransform());
            appendBytes(out, chain->getBaseVel());
            for (int j = 0; j < 2; ++j) appendBytes(out, chain->getJointVel(j));
        }
        return out;
    }
    /// The multibody's own state, as a user saves it: base position and orientation (as Bullet stores them: a
    /// transform would round the quaternion), velocities, joint positions and velocities.
    struct Own {
        btVector3 basePos, baseVel, baseOmega;
        btQuaternion worldToBase;
        btScalar jointPos[2], jointVel[2];
    };
    Own saveOwn() const {
        Own s{chain->getBasePos(), chain->getBaseVel(), chain->getBaseOmega(), chain->getWorldToBaseRot(), {}, {}};
        for (int j = 0; j < 2; ++j) {
            s.jointPos[j] = chain->getJointPos(j);
            s.jointVel[j] = chain->getJointVel(j);
        }
        return s;
    }
    void restoreOwn(const Own& s) {
        chain->setBasePos(s.basePos);
        chain->setWorldToBaseRot(s.worldToBase);
        chain->setBaseVel(s.baseVel);
        chain->setBaseOmega(s.baseOmega);
        for (int j = 0; j < 2; ++j) {
            chain->setJointPos(j, s.jointPos[j]);
            chain->setJointVel(j, s.jointVel[j]);
        }
        syncColliders();
    }
};

}  // namespace

TEST_CASE("save and restore: immediate mode in a user's own loop runs on bit-identically", "[bullet][state]") {
    OwnLoop loop;
    loop.run(60);
    const std::vector<unsigned char> blob = loop.buoyancy->saveState();
    const RigidBodyState body = RigidBodyState::save(*loop.body);  // the user's own body, as they save it
    const double time = loop.time;
    const std::vector<unsigned char> first = loop.run(240);

    const auto restoreBody = [&] {
        body.restore(*loop.body);
        loop.time = time;
    };
    restoreBody();
    loop.buoyancy->restoreState(blob);
    const std::vector<unsigned char> second = loop.run(240);
    INFO(firstDifference(first, second));
    CHECK(first == second);

    // Without the immediate object's state (its level-of-detail history and caches) the run is another one.
    restoreBody();
    const std::vector<unsigned char> third = loop.run(240);
    CHECK(third != first);
}

TEST_CASE("save and restore: immediate mode refuses bad blobs and keeps its state", "[bullet][state]") {
    OwnLoop loop;
    loop.run(30);
    const std::vector<unsigned char> blob = loop.buoyancy->saveState();
    loop.run(5);
    const std::vector<unsigned char> current = loop.buoyancy->saveState();
    REQUIRE(current != blob);
    for (std::size_t n = 0; n < blob.size(); n += 7)
        CHECK_THROWS_WITH(loop.buoyancy->restoreState(blob.data(), n), Contains("btBuoyancyImmediate::restoreState"));
    // An action's blob is not an immediate one.
    const std::vector<unsigned char> actionBlob = loop.buoyancy->getAction().saveState();
    CHECK_THROWS_WITH(loop.buoyancy->restoreState(actionBlob), Contains("expected a btBuoyancyImmediate state"));
    // Another body's state: the context part would apply, the evaluation part is refused; nothing changes.
    OwnLoop other(btVector3(0.3f, 0.3f, 0.3f));
    other.run(10);
    CHECK_THROWS_AS(loop.buoyancy->restoreState(other.buoyancy->saveState()), std::invalid_argument);
    CHECK(loop.buoyancy->saveState() == current);
}

TEST_CASE("save and restore: a btMultiBody chain in waves runs on bit-identically", "[bullet][state][multibody]") {
    ChainInWaves scene;
    scene.run(60);
    const std::vector<unsigned char> world = scene.buoyancy.saveState();
    const std::vector<unsigned char> action = scene.action->saveState();
    const ChainInWaves::Own own = scene.saveOwn();
    const std::vector<unsigned char> first = scene.run(240);
    REQUIRE(scene.action->getSubmergedVolume() > 0);

    scene.restoreOwn(own);
    scene.buoyancy.restoreState(world);
    scene.action->restoreState(action);
    const std::vector<unsigned char> second = scene.run(240);
    INFO(firstDifference(first, second));
    CHECK(first == second);

    // Leaving out the action's state (its parts' histories) gives another run.
    scene.restoreOwn(own);
    scene.buoyancy.restoreState(world);
    const std::vector<unsigned char> third = scene.run(240);
    CHECK(third != first);

    // Bad blobs: refused by name, nothing changed.
    const std::vector<unsigned char> current = scene.action->saveState();
    CHECK_THROWS_WITH(scene.action->restoreState(world), Contains("expected a btBuoyancyMultiBodyAction state"));
    std::vector<unsigned char> corrupt = action;
    corrupt[corrupt.size() / 2] ^= 0x40;
    CHECK_THROWS_WITH(scene.action->restoreState(corrupt), Contains("checksum"));
    CHECK(scene.action->saveState() == current);
}

TEST_CASE("btBuoyancyStateWriter writes the core's format with this build's btScalar size as the precision",
          "[bullet][state]") {
    btBuoyancyStateWriter layer(btBuoyancyStateKind::Flooding);
    buoyancy::StateWriter core(std::uint8_t(btBuoyancyStateKind::Flooding), std::uint8_t(sizeof(btScalar)));
    for (buoyancy::StateWriter* out : {static_cast<buoyancy::StateWriter*>(&layer), &core}) {
        out->u32(3);
        out->f64(0.25);
    }
    const std::vector<unsigned char> blob = layer.bytes();
    CHECK(blob == core.bytes());
    CHECK(blob[6] == sizeof(btScalar));
    CHECK(blob[7] == std::uint8_t(btBuoyancyStateKind::Flooding));
    btBuoyancyStateReader in(blob.data(), blob.size(), btBuoyancyStateKind::Flooding, "test");
    CHECK(in.u32("count") == 3);
    CHECK(in.f64("value") == 0.25);
    CHECK_NOTHROW(in.finish());
}
