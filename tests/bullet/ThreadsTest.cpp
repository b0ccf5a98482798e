// Threads (btBuoyancyWorld::setThreads, setBatching; bullet/btBuoyancyThreads.cpp): a world's bodies evaluated once per
// substep in parallel give bit-identical results for 1, 2 and N threads, across runs, and against the sequential order
// (each action at its own turn), with the temporal level of detail, drag, flooding and time-varying mass; the order
// with actions that write bodies is the documented one; bodies added or removed between steps are picked up; creating
// an action during the parallel evaluation is refused; the caller's floating-point control state reaches the workers.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>
#include <BulletBuoyancy/bullet/btTimeVaryingMassAction.h>
#include <BulletBuoyancy/graph/WaterIngress.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace {

std::vector<btGerstnerWave> sea() {
    std::vector<btGerstnerWave> w(3);
    w[0] = {0.5, 30.0, 1.0, 0.0, 0.5, 0.0};
    w[1] = {0.3, 17.0, 0.8, 0.6, 0.5, 1.3};
    w[2] = {0.15, 9.0, -0.3, 1.0, 0.5, 2.1};
    return w;
}

/// A thruster: pushes one body along x at its turn in Bullet's action order (writes the body's velocity).
struct Thruster : btActionInterface {
    btRigidBody* body = nullptr;
    void updateAction(btCollisionWorld*, btScalar dt) override {
        body->activate();
        body->applyCentralImpulse(btVector3(btScalar(400.0) * dt, 0, btScalar(150.0) * dt));
    }
    void debugDraw(btIDebugDraw*) override {}
};

/// Where the test's other actions go in Bullet's action array.
enum class Writer { None, BeforeAll, AfterOwn, BetweenOthers };

struct FleetOptions {
    int bodies = 24;
    int threads = 1;
    bool batching = true;
    bool flooding = false;           ///< a flooding action after every third body's buoyancy action
    bool timeVaryingMass = false;    ///< a time-varying mass action before the buoyancy actions, every fourth body
    Writer thruster = Writer::None;  ///< a thruster on body 5
    bool deformable = false;         ///< every sixth body a breathing sampled sphere (btBuoyancyDeformable)
    const btWaterSurface* surface = nullptr;  ///< nullptr: the test's Gerstner sea
    int queriesAhead = -1;           ///< btBuoyancyWorld::setQueriesAhead: 0 off, 1 on, −1 the default
};

/// N boxes in waves, each with its buoyancy action (the library's default settings: temporal level of detail, drag
/// clusters, water patch), plus the options' other actions.
struct Fleet {
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
    std::vector<std::shared_ptr<btBuoyancyDeformable>> skins;  ///< with the rest vertices of each
    std::vector<std::vector<Eigen::Vector3d>> restVertices;
    int frame = 0;
    Thruster thruster;
    std::vector<btActionInterface*> added;

    explicit Fleet(const FleetOptions& o) : water(&world, o.surface ? o.surface : &gerstner, 1000.0) {
        world.setGravity(btVector3(0, btScalar(-9.81), 0));
        water.setThreads(o.threads);
        water.setBatching(o.batching);
        if (o.queriesAhead >= 0) water.setQueriesAhead(o.queriesAhead == 1);
        auto box = btBuoyancyShape::create(buoyancy::makeBoxMesh(2.0, 0.8, 1.0));
        auto ball = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.6, 24, 12));
        buoyancy::WaterGraph graph;
        buoyancy::WaterNode node;
        node.name = "hold";
        node.capacity = 0.5;
        graph.nodes = {node};
        for (int i = 0; i < o.bodies; ++i) {
            const auto& shape = i % 5 == 4 ? ball : box;
            btBuoyantBodySettings s;
            s.density = 350.0 + 40.0 * (i % 7);
            btTransform t = btTransform::getIdentity();
            t.setRotation(btQuaternion(btVector3(0.1f, 1, 0.2f).normalized(), btScalar(0.7 * i)));
            // Some dropped from above the water, some placed in it: wet and dry substeps, bodies entering the water.
            t.setOrigin(btVector3(btScalar(4.0 * (i % 6)), btScalar(i % 3 == 0 ? 1.5 : 0.1), btScalar(4.0 * (i / 6))));
            bodies.push_back(std::make_unique<btBuoyantBody>(shape, s, t));
            world.addRigidBody(bodies.back()->getRigidBody());
        }
        thruster.body = bodies.size() > 5 ? bodies[5]->getRigidBody() : nullptr;
        if (o.thruster == Writer::BeforeAll && thruster.body) add(&thruster);
        if (o.timeVaryingMass) {
            for (int i = 0; i < o.bodies; i += 4) {
                btBuoyantBodySettings s;
                s.mass = 400.0;
                masses.push_back(std::make_unique<btTimeVaryingMassAction>(
                    *bodies[std::size_t(i)], &water, s, [](double t) { return std::int64_t(std::floor(t / 0.05)); },
                    [](double t, const Eigen::Vector3d& p) { return 1.0 + 0.8 * std::sin(3.0 * t + p.x()); }));
                add(masses.back().get());
            }
        }
        btBuoyancySettings sampled;
        sampled.method = btBuoyancyMethod::ExactCoverage;
        sampled.textureSize = 32;
        auto breathing = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.6, 16, 8), sampled);
        for (int i = 0; i < o.bodies; ++i) {
            if (o.deformable && i % 6 == 3) {
                actions.push_back(std::make_unique<btBuoyancyAction>(bodies[std::size_t(i)]->getRigidBody(), breathing,
                                                                     &water, sampled));
                skins.push_back(btBuoyancyDeformable::create(*breathing, sampled));
                restVertices.push_back(skins.back()->getVertices());
                actions.back()->setDeformable(skins.back());
            } else {
                actions.push_back(std::make_unique<btBuoyancyAction>(*bodies[std::size_t(i)], &water));
            }
            add(actions.back().get());
            if (o.thruster == Writer::AfterOwn && i == 5) add(&thruster);
            if (o.thruster == Writer::BetweenOthers && i == 2) add(&thruster);
            if (o.flooding && i % 3 == 1) {
                const auto& shape = bodies[std::size_t(i)]->getShape();
                buoyancy::PermeabilityRegion hole;
                hole.centre = Eigen::Vector3d(0.0, -0.4, 0.0);
                hole.radius = 0.3;
                floods.push_back(std::make_unique<btFloodingAction>(
                    *bodies[std::size_t(i)], &water, graph,
                    buoyancy::permeableSamplesFromRegions(shape->getDragSamples(), {hole}, graph)));
                add(floods.back().get());
            }
        }
    }
    void add(btActionInterface* a) {
        world.addAction(a);
        added.push_back(a);
    }
    ~Fleet() {
        for (btActionInterface* a : added) world.removeAction(a);
        for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
    }
    void run(int frames) {
        for (int f = 0; f < frames; ++f, ++frame) {
            // The user animates the deformable bodies between steps: each breathes by ±8 % of its radius.
            for (std::size_t k = 0; k < skins.size(); ++k) {
                const double scale = 1.0 + 0.08 * std::sin(0.2 * frame + double(k));
                std::vector<Eigen::Vector3d> v = restVertices[k];
                for (Eigen::Vector3d& p : v) p *= scale;
                skins[k]->setVertices(v);
            }
            world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        }
    }
    /// Every body's state and every action's last result, as bytes.
    std::vector<unsigned char> fingerprint() const {
        std::vector<btScalar> v;
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
            v.push_back(rb->getInvMass());
            v.push_back(btScalar(rb->getActivationState()));
        }
        std::vector<unsigned char> bytes(v.size() * sizeof(btScalar));
        std::memcpy(bytes.data(), v.data(), bytes.size());
        for (const auto& a : actions) {
            const btBuoyancyResult& r = a->getLastResult();
            const double d[4] = {r.submergedVolume, r.wettedArea, r.addedMass, double(r.predicted)};
            const unsigned char* p = reinterpret_cast<const unsigned char*>(d);
            bytes.insert(bytes.end(), p, p + sizeof d);
        }
        for (const auto& f : floods) {
            const double w = f->getWaterVolume();
            const unsigned char* p = reinterpret_cast<const unsigned char*>(&w);
            bytes.insert(bytes.end(), p, p + sizeof w);
        }
        return bytes;
    }
    int predictedBodies() const {
        int n = 0;
        for (const auto& a : actions) n += a->getLastResult().predicted ? 1 : 0;
        return n;
    }
};

std::vector<unsigned char> runFleet(FleetOptions o, int frames, int* batchSize = nullptr, int* predicted = nullptr) {
    Fleet fleet(o);
    int predictions = 0;
    for (int f = 0; f < frames; ++f) {
        fleet.run(1);
        predictions += fleet.predictedBodies();
    }
    if (batchSize) *batchSize = fleet.water.getLastBatchSize();
    if (predicted) *predicted = predictions;
    return fleet.fingerprint();
}

/// The fleet of `o` batched on 3 and on 1 thread gives the bytes of the sequential order (batching off), `frames`
/// frames on.
void checkBatchedAsSequential(FleetOptions o, int frames) {
    o.batching = true;
    o.threads = 3;
    const auto batched = runFleet(o, frames);
    o.threads = 1;
    const auto batchedOne = runFleet(o, frames);
    o.batching = false;
    const auto sequential = runFleet(o, frames);
    CHECK(batched == sequential);
    CHECK(batchedOne == sequential);
}
}  // namespace

TEST_CASE("threads: bodies bit-identical for 1, 2 and 4 threads, across runs and against the sequential order",
          "[bullet][threads]") {
    FleetOptions o;
    const int frames = 90;  // 1.5 s, 360 substeps: the temporal level of detail predicts and checks
    o.threads = 1;
    int batch = -1, predicted = 0;
    const auto one = runFleet(o, frames, &batch, &predicted);
    CHECK(batch == o.bodies);  // every body evaluated in the batch
    CHECK(predicted > 0);      // the temporal level of detail's turn-taking is part of what is compared
    o.threads = 2;
    const auto two = runFleet(o, frames, &batch);
    CHECK(batch == o.bodies);
    o.threads = 4;
    const auto four = runFleet(o, frames);
    const auto fourAgain = runFleet(o, frames);
    o.batching = false;
    const auto sequential = runFleet(o, frames, &batch);
    CHECK(batch == 0);
    REQUIRE(one.size() == two.size());
    CHECK(one == two);
    CHECK(one == four);
    CHECK(four == fourAgain);
    CHECK(one == sequential);
    // (The comparison can fail: see the thruster between buoyancy actions below.)
}

TEST_CASE("threads: flooding and time-varying mass give the sequential order's results", "[bullet][threads]") {
    // The documented order: a time-varying mass action added before the buoyancy actions, a flooding action after its
    // body's buoyancy action. Batched on 1 and 3 threads == each action at its own turn.
    FleetOptions o;
    o.flooding = true;
    o.timeVaryingMass = true;
    const int frames = 60;
    checkBatchedAsSequential(o, frames);
    o.batching = false;
    // Water got in (the flooding is part of what is compared), and the flooding actions flowed in the world's batch
    // (8 of them, every third body's: on 3 threads) or at their own turns (batching off).
    Fleet f(o);
    f.run(frames);
    double water = 0;
    for (const auto& fl : f.floods) water += fl->getWaterVolume();
    CHECK(water > 0.01);
    CHECK(f.water.getLastFloodingBatchSize() == 0);
    CHECK(f.water.getLastTimeVaryingMassBatchSize() == 0);
    o.batching = true;
    o.threads = 3;
    Fleet g(o);
    g.run(1);
    CHECK(g.water.getLastFloodingBatchSize() == 8);
    // The six time-varying mass actions (every fourth body's) checked their maps in one batch, and the maps changed
    // (every 0.05 s) and were recomputed: the recompute is part of what is compared above.
    CHECK(g.water.getLastTimeVaryingMassBatchSize() == 6);
    g.run(frames);
    long long recomputes = 0;
    for (const auto& m : g.masses) recomputes += m->getRecomputeCount();
    CHECK(recomputes >= 6 * 20);
}

TEST_CASE("threads: deformable bodies re-baked on the worker threads give the sequential order's results",
          "[bullet][threads]") {
    // setVertices between steps only stores the vertices; the samples are re-baked when the body is evaluated: in the
    // batch, on the worker threads. Batched on 1 and 3 threads == each action at its own turn.
    FleetOptions o;
    o.deformable = true;
    checkBatchedAsSequential(o, 60);
    // The breathing is part of what is compared: a deformable body's submerged volume follows its size. Its samples
    // enclose the scaled mesh's volume (the re-bake happened): the rest mesh's volume × scale³.
    o.batching = true;
    o.threads = 3;
    Fleet f(o);
    f.run(7);
    REQUIRE(!f.skins.empty());
    const double scale = 1.0 + 0.08 * std::sin(0.2 * 6 + 0.0);  // the last frame's (frame 6, skin 0)
    const double rest = f.actions[3]->getShape()->getVolume();
    CHECK(f.skins[0]->getVolume() == Approx(rest * scale * scale * scale).epsilon(1e-6));
}

TEST_CASE("threads: a flooding action added to the Bullet world twice flows at each of its turns", "[bullet][threads]") {
    // Unbatched, an action added twice runs twice a substep; the batch leaves it out so that it still does (the other
    // 7 flooding actions flow in the batch), and the results equal the sequential order's.
    FleetOptions o;
    o.flooding = true;
    o.threads = 2;
    const auto twice = [](FleetOptions opt, int frames, int* batch) {
        Fleet f(opt);
        f.add(f.floods.front().get());
        f.run(frames);
        if (batch) *batch = f.water.getLastFloodingBatchSize();
        return f.fingerprint();
    };
    int batch = -1;
    const auto batched = twice(o, 30, &batch);
    CHECK(batch == 7);
    o.batching = false;
    CHECK(twice(o, 30, nullptr) == batched);
}

TEST_CASE("threads: an action that writes a body, in the documented order and between buoyancy actions",
          "[bullet][threads]") {
    FleetOptions o;
    o.threads = 2;
    const int frames = 30;
    for (Writer w : {Writer::BeforeAll, Writer::AfterOwn}) {
        o.thruster = w;
        o.batching = true;
        const auto batched = runFleet(o, frames);
        o.batching = false;
        const auto sequential = runFleet(o, frames);
        CHECK(batched == sequential);
    }
    // A thruster of body 5 between the buoyancy actions of bodies 2 and 3: the batch evaluated body 5 before the
    // thrust of the substep, the sequential order after it (btBuoyancyWorld::setBatching says so).
    o.thruster = Writer::BetweenOthers;
    o.batching = true;
    const auto batched = runFleet(o, frames);
    o.batching = false;
    const auto sequential = runFleet(o, frames);
    CHECK(batched != sequential);
}

TEST_CASE("threads: bodies added and removed between steps are picked up", "[bullet][threads]") {
    auto script = [](int threads, bool batching) {
        FleetOptions o;
        o.bodies = 12;
        o.threads = threads;
        o.batching = batching;
        Fleet f(o);
        std::vector<int> sizes;
        f.run(10);
        sizes.push_back(f.water.getLastBatchSize());
        // Remove three actions (and one body), then add one action back, between steps.
        f.world.removeAction(f.actions[3].get());
        f.world.removeAction(f.actions[7].get());
        f.world.removeAction(f.actions[8].get());
        f.world.removeRigidBody(f.bodies[8]->getRigidBody());
        f.run(10);
        sizes.push_back(f.water.getLastBatchSize());
        f.world.addAction(f.actions[7].get());
        f.world.addRigidBody(f.bodies[8]->getRigidBody());
        // A new body and action.
        f.bodies.push_back(std::make_unique<btBuoyantBody>(f.bodies[0]->getShape(), btBuoyantBodySettings(),
                                                           btTransform(btQuaternion::getIdentity(), btVector3(40, 0, 40))));
        f.world.addRigidBody(f.bodies.back()->getRigidBody());
        f.actions.push_back(std::make_unique<btBuoyancyAction>(*f.bodies.back(), &f.water));
        f.add(f.actions.back().get());
        f.run(10);
        sizes.push_back(f.water.getLastBatchSize());
        return std::make_pair(sizes, f.fingerprint());
    };
    const auto two = script(2, true);
    const auto sequential = script(1, false);
    CHECK(two.first == std::vector<int>{12, 9, 11});
    CHECK(two.second == sequential.second);
}

namespace {
/// Flat water whose queries record the caller's floating-point control state, and try to create an action (which the
/// world must refuse while it evaluates its bodies).
class ProbeWater : public btFlatWaterSurface {
public:
    mutable std::mutex mutex;
    mutable std::set<unsigned> csr;
    mutable std::atomic<int> refused{0}, created{0};
    mutable std::string message;
    btBuoyancyWorld* world = nullptr;
    btRigidBody* body = nullptr;
    std::shared_ptr<const btBuoyancyShape> shape;
    mutable std::atomic<bool> tryCreate{false};
    void heights(const double* x, const double* z, std::size_t n, double t, double* out) const override {
        record();
        btFlatWaterSurface::heights(x, z, n, t, out);
    }
    void heightBounds(double x0, double z0, double x1, double z1, double t, double& lo, double& hi) const override {
        record();
        if (waitForSecond) meetSecondThread();
        if (tryCreate.exchange(false)) {
            try {
                btBuoyancyAction extra(body, shape, world);
                ++created;
            } catch (const std::logic_error& e) {
                std::lock_guard<std::mutex> lock(mutex);
                message = e.what();
                ++refused;
            }
        }
        btFlatWaterSurface::heightBounds(x0, z0, x1, z1, t, lo, hi);
    }
    void record() const {
        std::lock_guard<std::mutex> lock(mutex);
        threads.insert(std::this_thread::get_id());
#if defined(__SSE__)
        csr.insert(_mm_getcsr() & ~0x3fu);  // the control bits (not the sticky exception flags, bits 0-5)
#endif
    }
    mutable std::set<std::thread::id> threads;
    /// Until two threads have queried, hold the callers (up to 10 s): with one thread only, the wait times out.
    void meetSecondThread() const {
        std::unique_lock<std::mutex> lock(mutex);
        threads.insert(std::this_thread::get_id());
        met.notify_all();
        met.wait_for(lock, std::chrono::seconds(10), [this] { return threads.size() >= 2; });
    }
    mutable std::condition_variable met;
    mutable std::atomic<bool> waitForSecond{false};
};
}  // namespace

TEST_CASE("threads: an action created during the parallel evaluation is refused with a message", "[bullet][threads]") {
    ProbeWater probe;
    FleetOptions o;
    o.bodies = 8;
    o.threads = 2;
    o.surface = &probe;
    Fleet f(o);
    probe.world = &f.water;
    probe.body = f.bodies[0]->getRigidBody();
    probe.shape = f.bodies[0]->getShape();
    f.run(1);
    probe.tryCreate = true;
    f.run(1);
    CHECK(probe.refused == 1);
    CHECK(probe.created == 0);
    CHECK(probe.message.find("between steps") != std::string::npos);
    CHECK(f.water.getActions().size() == 8);
    // Between steps it is allowed.
    probe.tryCreate = true;
    double lo, hi;
    probe.heightBounds(0, 0, 1, 1, 0, lo, hi);
    CHECK(probe.created == 1);
}

#if defined(__SSE__)
TEST_CASE("threads: the caller's flush-to-zero and denormals-are-zero reach the worker threads", "[bullet][threads]") {
    ProbeWater probe;
    FleetOptions o;
    o.bodies = 16;
    o.threads = 2;
    o.surface = &probe;
    Fleet f(o);
    const unsigned saved = _mm_getcsr();
    const unsigned ftz = saved | 0x8040u;  // FTZ (bit 15) and DAZ (bit 6)
    _mm_setcsr(ftz);
    f.run(3);
    _mm_setcsr(saved);
    CHECK(probe.csr == std::set<unsigned>{ftz & ~0x3fu});
    probe.csr.clear();
    f.run(1);
    CHECK(probe.csr == std::set<unsigned>{saved & ~0x3fu});  // and restored in the workers afterwards
}
#endif

#ifdef BUOYANCY_TEST_THREADS
TEST_CASE("threads: the batch runs on the threads asked for", "[bullet][threads]") {
    for (int threads : {1, 2, 3}) {
        ProbeWater probe;
        FleetOptions o;
        o.bodies = 16;
        o.threads = threads;
        o.surface = &probe;
        Fleet f(o);
        f.run(1);
        probe.threads.clear();
        if (threads > 1) probe.waitForSecond = true;  // each body's query waits until a second thread queried too
        const auto t0 = std::chrono::steady_clock::now();
        f.run(2);
        INFO("threads " << threads);
        CHECK(int(probe.threads.size()) >= std::min(threads, 2));  // a third may find no body left: not required
        CHECK(int(probe.threads.size()) <= threads);
        CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(9));
    }
}
#endif

TEST_CASE("threads: setThreads and getThreads", "[bullet][threads]") {
    btFlatWaterSurface flat;
    btBuoyancyWorld w(&flat);
    CHECK(w.getThreads() >= 1);  // 0 (default): the hardware's
    w.setThreads(3);
#ifdef BUOYANCY_TEST_THREADS
    CHECK(w.getThreads() == 3);
#endif
    w.setThreads(1);
    CHECK(w.getThreads() == 1);
    CHECK_THROWS_AS(w.setThreads(-1), std::invalid_argument);
    CHECK(w.getThreads() == 1);
    CHECK(w.getBatching());
}

namespace {
/// A task scheduler as a user's threaded Bullet would install one: parallelFor on two std::threads, counting its calls.
class TwoThreadScheduler : public btITaskScheduler {
public:
    TwoThreadScheduler() : btITaskScheduler("test two threads") {}
    int getMaxNumThreads() const override { return 2; }
    int getNumThreads() const override { return 2; }
    void setNumThreads(int) override {}
    void parallelFor(int begin, int end, int grain, const btIParallelForBody& body) override {
        ++calls;
        const int mid = begin + std::max(grain, (end - begin) / 2);
        std::thread other([&] { body.forLoop(std::min(mid, end), end); });
        body.forLoop(begin, std::min(mid, end));
        other.join();
    }
    btScalar parallelSum(int begin, int end, int, const btIParallelSumBody& body) override {
        return body.sumLoop(begin, end);
    }
    std::atomic<int> calls{0};
};
}  // namespace

TEST_CASE("threads: a Bullet task scheduler with threads runs the batch, with the same results", "[bullet][threads]") {
    FleetOptions o;
    o.threads = 1;  // the scheduler's thread count applies instead
    const int frames = 30;
    const auto reference = runFleet(o, frames);
    TwoThreadScheduler scheduler;
    btITaskScheduler* previous = btGetTaskScheduler();
    btSetTaskScheduler(&scheduler);
    std::vector<unsigned char> withScheduler;
    int threads = 0;
    {
        Fleet f(o);
        threads = f.water.getThreads();
        f.run(frames);
        withScheduler = f.fingerprint();
    }
    btSetTaskScheduler(previous);
    CHECK(threads == 2);
    CHECK(scheduler.calls == frames * 4);  // one batch per substep
    CHECK(withScheduler == reference);
}

namespace {
/// A Gerstner sea that answers 0.3 m higher (a subclass overriding a query, without a copy of its own).
struct RaisedWaves : btGerstnerWaterSurface {
    using btGerstnerWaterSurface::btGerstnerWaterSurface;
    void heightsCached(const double* x, const double* z, std::size_t n, double t, double* out,
                       btWaterQueryCache& cache) const override {
        btGerstnerWaterSurface::heightsCached(x, z, n, t, out, cache);
        for (std::size_t i = 0; i < n; ++i) out[i] += 0.3;
    }
};

/// The fleet of `o` run `frames` frames; the most bodies whose patch heights were queried ahead in one substep.
std::vector<unsigned char> runCountingQueriesAhead(const FleetOptions& o, int frames, int& most) {
    Fleet f(o);
    most = 0;
    for (int i = 0; i < frames; ++i) {
        f.run(1);
        most = std::max(most, f.water.getLastQueriedAhead());
    }
    return f.fingerprint();
}
}  // namespace

TEST_CASE("threads: wave patch heights queried ahead while Bullet steps change no result", "[bullet][threads]") {
    // With two threads the world's helper thread queries the heights of the next exact evaluations' wave patches while
    // Bullet's own step runs; each body uses them only if its patch then has the same nodes, time and surface, so the
    // results are bit for bit those of one thread (which queries nothing ahead) and of queries ahead switched off.
    FleetOptions o;
    const int frames = 60;
    int mostTwo = 0, mostOne = 0, mostOff = 0;
    o.threads = 2;
    o.queriesAhead = 1;
    const auto two = runCountingQueriesAhead(o, frames, mostTwo);
    o.queriesAhead = 0;
    const auto off = runCountingQueriesAhead(o, frames, mostOff);
    o.threads = 1;
    o.queriesAhead = 1;
    const auto one = runCountingQueriesAhead(o, frames, mostOne);
    CHECK(mostOne == 0);
    CHECK(mostOff == 0);
#ifdef BUOYANCY_TEST_THREADS
    CHECK(mostTwo > 0);  // (the comparison below covers the heights queried ahead)
#endif
    CHECK(two == one);
    CHECK(two == off);
    // A subclass that overrides a query and has no copy of its own: nothing is queried ahead on it (a copy of the base
    // class would answer 0.3 m lower).
    RaisedWaves raised(sea());
    o.surface = &raised;
    o.threads = 2;
    const auto raisedTwo = runCountingQueriesAhead(o, frames / 2, mostTwo);
    CHECK(mostTwo == 0);
    o.threads = 1;
    CHECK(raisedTwo == runCountingQueriesAhead(o, frames / 2, mostOne));
}

TEST_CASE("threads: queries ahead are on by default with oneTBB's threads, off with OpenMP's", "[bullet][threads]") {
    btFlatWaterSurface flat;
    btBuoyancyWorld w(&flat);
#ifdef BUOYANCY_TEST_QUERIES_AHEAD
    CHECK(w.getQueriesAhead());
#else
    CHECK_FALSE(w.getQueriesAhead());
#endif
    w.setQueriesAhead(false);
    CHECK_FALSE(w.getQueriesAhead());
    w.setQueriesAhead(true);
    CHECK(w.getQueriesAhead());
    CHECK(w.getLastQueriedAhead() == 0);
}

TEST_CASE("threads: a surface changed, replaced or destroyed between steps while heights are queried ahead",
          "[bullet][threads]") {
    // The heights of the last substep's next patches may still be queried after stepSimulation returns: on a copy of
    // the surface, so the user may change or destroy theirs; a changed surface (a new revision) or another one at the
    // same address is queried again, never answered from the old one. Each sequence on 2 threads == on 1 thread.
    std::vector<btGerstnerWave> steeper = sea();
    for (btGerstnerWave& w : steeper) w.amplitude *= 1.5;
    const auto sequence = [&](int threads, int& most) {
        FleetOptions o;
        o.threads = threads;
        o.queriesAhead = 1;
        Fleet f(o);
        most = 0;
        const auto frames = [&](int n) {
            for (int i = 0; i < n; ++i) {
                f.run(1);
                most = std::max(most, f.water.getLastQueriedAhead());
            }
        };
        frames(15);
        // A setter that changes the answers' last bits (the SIMD width of the solve) renews the revision.
        const int lanes = f.gerstner.simdLanes();
        f.gerstner.setSimdLanes(lanes == 2 ? 8 : 2);
        frames(15);
        // Another surface, then that one destroyed right after a step and a third made at once (often at its address).
        auto other = std::make_unique<btGerstnerWaterSurface>(steeper);
        f.water.setWater(other.get());
        frames(15);
        other.reset();
        other = std::make_unique<btGerstnerWaterSurface>(sea());
        f.water.setWater(other.get());
        frames(15);
        return f.fingerprint();
    };
    int mostTwo = 0, mostOne = 0;
    const auto two = sequence(2, mostTwo);
    const auto one = sequence(1, mostOne);
#ifdef BUOYANCY_TEST_THREADS
    CHECK(mostTwo > 0);
#endif
    CHECK(mostOne == 0);
    CHECK(two == one);
}
