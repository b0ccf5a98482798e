/// @file btBuoyancyThreads.cpp
/// The parallel evaluation of a btBuoyancyWorld's bodies (declared in bullet/btBuoyancyWorld.h): which actions form
/// the batch of a substep, the threads that evaluate it (oneTBB or OpenMP, or Bullet's task scheduler when it has
/// one), and the helper thread that queries the next substep's wave patch heights while Bullet steps.

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>
#include <BulletBuoyancy/bullet/btTimeVaryingMassAction.h>

#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>
#include <LinearMath/btThreads.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>
#include <stdexcept>
#include <string>

#ifdef BULLET_BUOYANCY_HAS_TBB
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <memory>
#include <thread>
#endif
#ifdef BULLET_BUOYANCY_HAS_OPENMP
#include <omp.h>
#endif
#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#define BT_BUOYANCY_HAS_MXCSR 1
#endif

namespace {

/// Bullet keeps a world's actions in a protected array without an accessor: read it through a member pointer formed
/// in a derived class (never instantiated).
struct WorldActions : btDiscreteDynamicsWorld {
    static const btAlignedObjectArray<btActionInterface*>& of(const btDiscreteDynamicsWorld& world) {
        return world.*(&WorldActions::m_actions);
    }
};

/// The caller's floating-point control state (SSE: flush-to-zero, denormals-are-zero, rounding), carried into every
/// worker for the batch and restored after it, so a body's result does not depend on the thread that evaluates it.
class FpState {
public:
    static unsigned current() {
#ifdef BT_BUOYANCY_HAS_MXCSR
        return _mm_getcsr();
#else
        return 0;
#endif
    }
    explicit FpState(unsigned wanted) : m_saved(current()) {
#ifdef BT_BUOYANCY_HAS_MXCSR
        if (m_saved != wanted) _mm_setcsr(wanted);
#else
        (void)wanted;
#endif
    }
    ~FpState() {
#ifdef BT_BUOYANCY_HAS_MXCSR
        if (current() != m_saved) _mm_setcsr(m_saved);
#endif
    }
    FpState(const FpState&) = delete;
    FpState& operator=(const FpState&) = delete;

private:
    unsigned m_saved;
};

#ifdef BULLET_BUOYANCY_HAS_TBB
/// `threads`, at most as many as oneTBB runs at once (it has that many workers; asking for more only makes it warn).
int arenaThreads(int threads) { return std::max(1, std::min(threads, tbb::info::default_concurrency())); }

/// The calling thread's task arena of `threads` threads (arenaThreads), kept between substeps.
tbb::task_arena* arenaFor(int threads) {
    threads = arenaThreads(threads);
    thread_local std::unique_ptr<tbb::task_arena> arena;
    if (!arena || arena->max_concurrency() != threads) arena = std::make_unique<tbb::task_arena>(threads);
    return arena.get();
}
#endif

/// Bullet's task scheduler, when the Bullet in use has one with more than one thread.
btITaskScheduler* bulletScheduler() {
    btITaskScheduler* scheduler = btGetTaskScheduler();
    return scheduler && scheduler->getNumThreads() > 1 ? scheduler : nullptr;
}

/// A loop body for Bullet's task scheduler, with the caller's floating-point control state.
template <class Item>
struct SchedulerBody : btIParallelForBody {
    const Item* item = nullptr;
    unsigned csr = 0;
    void forLoop(int begin, int end) const override {
        FpState fp(csr);
        for (int i = begin; i < end; ++i) (*item)(i);
    }
};

/// item(0) … item(n − 1), each independent of the others, on Bullet's task scheduler when it has one, else on up to
/// `threads` OpenMP threads (one thread below 4 items: an OpenMP worker spin-waiting between substeps would only take
/// the core Bullet's own step runs on), in chunks of up to 16 handed out as threads free up (an item costs from a few
/// to tens of µs, so static halves leave one thread waiting). Every worker runs with the caller's floating-point
/// control state `csr`.
template <class Item>
void parallelOver(int n, int threads, unsigned csr, const Item& item) {
    if (btITaskScheduler* scheduler = bulletScheduler()) {
        SchedulerBody<Item> body;
        body.item = &item;
        body.csr = csr;
        scheduler->parallelFor(0, n, std::max(1, std::min(16, n / (8 * scheduler->getNumThreads()))), body);
        return;
    }
#ifdef BULLET_BUOYANCY_HAS_TBB
    // oneTBB (BULLET_BUOYANCY_TBB): the same chunks on a task arena of `threads` threads, kept between substeps.
    threads = std::min(threads, n);
    if (threads > 1 && n >= 4) {
        tbb::task_arena* arena = arenaFor(threads);
        const int chunk = std::max(1, std::min(16, n / (8 * threads)));
        arena->execute([&] {
            tbb::parallel_for(
                tbb::blocked_range<int>(0, n, std::size_t(chunk)),
                [&](const tbb::blocked_range<int>& r) {
                    FpState fp(csr);
                    for (int i = r.begin(); i < r.end(); ++i) item(i);
                },
                tbb::simple_partitioner());
        });
        return;
    }
    for (int i = 0; i < n; ++i) item(i);
    return;
#endif
#ifdef BULLET_BUOYANCY_HAS_OPENMP
    threads = std::min(threads, n);
    if (threads > 1 && n >= 4) {
        const int chunk = std::max(1, std::min(16, n / (8 * threads)));
#pragma omp parallel num_threads(threads)
        {
            FpState fp(csr);
#pragma omp for schedule(dynamic, chunk)
            for (int i = 0; i < n; ++i) item(i);
        }
        return;
    }
#else
    (void)threads;
    (void)csr;
#endif
    for (int i = 0; i < n; ++i) item(i);
}

/// Raised while a batch runs (creating or destroying an action then is refused), lowered when it ends.
struct BatchFlag {
    std::atomic<bool>& flag;
    explicit BatchFlag(std::atomic<bool>& f) : flag(f) { flag.store(true); }
    ~BatchFlag() { flag.store(false); }
    BatchFlag(const BatchFlag&) = delete;
    BatchFlag& operator=(const BatchFlag&) = delete;
};

/// The registered actions of one kind (`registered`) that are in the Bullet world's action array, in its order, into
/// `members`; one added to the array twice is left out (it runs at each of its turns, as it would unbatched). Rebuilt
/// only when the array differs from `seen` (the array it was built from) or `dirty` (registrations changed).
template <class Action>
void refreshMembers(const btAlignedObjectArray<btActionInterface*>& actions, const std::vector<Action*>& registered,
                    bool& dirty, std::vector<const btActionInterface*>& seen, std::vector<Action*>& members) {
    const std::size_t count = std::size_t(std::max(actions.size(), 0));
    const btActionInterface* const* now = count > 0 ? &actions[0] : nullptr;
    if (!dirty && seen.size() == count && std::equal(seen.begin(), seen.end(), now)) return;
    seen.assign(now, now + count);
    members.clear();
    for (const btActionInterface* a : seen) {
        const auto mine = std::find(registered.begin(), registered.end(), a);
        if (mine == registered.end()) continue;
        if (std::count(seen.begin(), seen.end(), a) != 1) continue;
        members.push_back(*mine);
    }
    dirty = false;
}

}  // namespace

/// The patch heights queried ahead (btBuoyancyWorldPrebuildPatch; design.md 3 "Queries ahead") for the members of the
/// last batch: taken one by one by the helper thread while Bullet steps, and by the calling thread for what is left
/// when the next substep begins. Each body's query writes only that body's prebuild record, so who takes it changes
/// nothing.
struct btBuoyancyWorld::PrebuildJob {
    /// A copy of a surface the world's bodies are in (btWaterSurface::cloneForQueriesAhead): the queries ahead read
    /// only copies, never the user's surface, which may change or go between stepSimulation calls.
    struct SurfaceCopy {
        const btWaterSurface* surface = nullptr;
        std::uint64_t revision = 0;
        std::shared_ptr<const btWaterSurface> copy;  ///< nullptr: the surface has none
    };
    std::vector<SurfaceCopy> copies;
    std::atomic<int> next{0};           ///< the next member to take
    std::atomic<int> done{0};           ///< members finished
    std::atomic<int> queried{0};        ///< members whose heights were queried
    std::atomic<bool> queued{false};    ///< the helper's run of this job has not returned (nor been withdrawn)
    int n = 0;
    btBuoyancyAction* const* list = nullptr;
    unsigned csr = 0;
    bool active = false;
    /// The helper thread that runs work() once per start(), asleep in between (a thread of its own: an OpenMP or oneTBB
    /// task would have to be joined before the batch returns to Bullet).
    std::thread helper;
    std::mutex mutex;
    std::condition_variable wake;
    std::uint64_t generation = 0;  ///< start()s so far (guarded by mutex)
    std::uint64_t taken = 0;       ///< the last generation the helper took or the caller withdrew (guarded by mutex)
    bool stop = false;             ///< (guarded by mutex)
    void start() {
        if (!helper.joinable()) helper = std::thread([this] { serve(); });
        {
            const std::lock_guard<std::mutex> lock(mutex);
            ++generation;
        }
        wake.notify_one();
    }
    void serve() {
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(mutex);
                wake.wait(lock, [&] { return stop || generation != taken; });
                if (stop) return;
                taken = generation;
            }
            work();
            queued.store(false, std::memory_order_release);
        }
    }
    /// The caller's: a start() the helper has not taken yet is withdrawn (the caller does its work), so a helper that
    /// got no core in time (a busy machine) is never waited for.
    void withdraw() {
        const std::lock_guard<std::mutex> lock(mutex);
        if (taken == generation) return;
        taken = generation;
        queued.store(false, std::memory_order_release);
    }
    ~PrebuildJob() {
        if (!helper.joinable()) return;
        {
            const std::lock_guard<std::mutex> lock(mutex);
            stop = true;
        }
        wake.notify_one();
        helper.join();
    }
    void work() {
        FpState fp(csr);
        for (;;) {
            const int i = next.fetch_add(1, std::memory_order_acq_rel);
            if (i >= n) break;
            if (btBuoyancyWorldPrebuildPatch(*list[i])) queried.fetch_add(1, std::memory_order_relaxed);
            done.fetch_add(1, std::memory_order_acq_rel);
        }
    }
};

const btWaterSurface* btBuoyancyWorld::surfaceForQueriesAhead(const btWaterSurface* water) const {
    if (!m_prebuildJob) return nullptr;
    for (const PrebuildJob::SurfaceCopy& c : m_prebuildJob->copies)
        if (c.surface == water) return c.revision == water->getRevision() ? c.copy.get() : nullptr;
    return nullptr;
}

void btBuoyancyWorld::preparePrebuilds(int batchSize) {
    m_prebuildPatches = false;
    // Only where a core is free while Bullet steps: on by setQueriesAhead, two or more threads of the library's own
    // (Bullet's task scheduler, when there is one, runs Bullet's own step on them).
    if (!m_queriesAhead || bulletScheduler() || std::min(getThreads(), batchSize) < 2 || batchSize < 4) return;
    if (!m_prebuildJob) m_prebuildJob = std::make_shared<PrebuildJob>();
    PrebuildJob& job = *m_prebuildJob;
    // The surfaces the bodies may be in: the unbounded water and the water bodies'. A copy is made for a surface (or
    // revision) new to the world; those no longer in it are dropped.
    const auto keep = [&](const btWaterSurface* s, std::vector<PrebuildJob::SurfaceCopy>& into) {
        if (!s) return;
        for (const PrebuildJob::SurfaceCopy& c : into)
            if (c.surface == s) return;
        for (PrebuildJob::SurfaceCopy& c : job.copies)
            if (c.surface == s && c.revision == s->getRevision()) {
                into.push_back(std::move(c));
                c.surface = nullptr;
                return;
            }
        PrebuildJob::SurfaceCopy c;
        c.surface = s;
        c.revision = s->getRevision();
        try {
            c.copy = s->cloneForQueriesAhead();
        } catch (...) {
            c.copy = nullptr;  // (a user's copy that throws: no queries ahead on that surface)
        }
        into.push_back(std::move(c));
    };
    bool same = job.copies.size() == m_waterBodies.size() + (m_water ? 1 : 0);
    for (std::size_t i = 0; same && i < job.copies.size(); ++i) {
        const btWaterSurface* s = i == 0 && m_water ? m_water : m_waterBodies[i - (m_water ? 1 : 0)].surface;
        same = job.copies[i].surface == s && job.copies[i].revision == s->getRevision();
    }
    if (!same) {  // (no allocation while the surfaces stay the same)
        std::vector<PrebuildJob::SurfaceCopy> next;
        keep(m_water, next);
        for (const btWaterBody& b : m_waterBodies) keep(b.surface, next);
        job.copies = std::move(next);
    }
    for (const PrebuildJob::SurfaceCopy& c : job.copies)
        if (c.copy) m_prebuildPatches = true;
}

void btBuoyancyWorld::startPrebuilds(unsigned csr) {
    if (!m_prebuildPatches || m_batch.empty()) return;
    PrebuildJob& job = *m_prebuildJob;
    job.n = int(m_batch.size());
    job.list = m_batch.data();
    job.csr = csr;
    job.next.store(0, std::memory_order_relaxed);
    job.done.store(0, std::memory_order_relaxed);
    job.queried.store(0, std::memory_order_relaxed);
    job.queued.store(true, std::memory_order_release);
    job.active = true;
    job.start();
}

btBuoyancyWorld::~btBuoyancyWorld() { finishPrebuilds(); }

bool btBuoyancyWorld::queriesAheadByDefault() {
#ifdef BULLET_BUOYANCY_HAS_TBB
    return true;  // oneTBB's idle worker sleeps soon: the helper gets the core while Bullet steps
#else
    return false;  // OpenMP's waiting thread spins through Bullet's step (measured slower with the helper)
#endif
}

void btBuoyancyWorld::finishPrebuilds() {
    if (!m_prebuildJob || !m_prebuildJob->active) {
        m_lastQueriedAhead = 0;
        return;
    }
    PrebuildJob& job = *m_prebuildJob;
    job.withdraw();  // not started by the helper yet: done here
    job.work();      // what the helper has not taken yet
    while (job.done.load(std::memory_order_acquire) < job.n || job.queued.load(std::memory_order_acquire))
        std::this_thread::yield();
    job.active = false;
    m_lastQueriedAhead = std::size_t(job.queried.load(std::memory_order_relaxed));
}

void btBuoyancyWorld::setThreads(int n) {
    if (n < 0)
        throw std::invalid_argument("threads: must be >= 1, or 0 for the hardware's (got " + std::to_string(n) + ")");
    m_threads = n;
}

int btBuoyancyWorld::getThreads() const {
    if (btITaskScheduler* scheduler = bulletScheduler()) return scheduler->getNumThreads();
#ifdef BULLET_BUOYANCY_HAS_TBB
    return m_threads > 0 ? m_threads : std::max(1, int(std::thread::hardware_concurrency()));
#endif
#ifdef BULLET_BUOYANCY_HAS_OPENMP
    return m_threads > 0 ? m_threads : std::max(1, omp_get_num_procs());
#else
    return 1;
#endif
}

void btBuoyancyWorld::refreshBatch(const btActionInterface* const* worldActions, int count) {
    const std::size_t n = std::size_t(std::max(count, 0));
    if (!m_batchDirty && m_seenWorldActions.size() == n &&
        std::equal(m_seenWorldActions.begin(), m_seenWorldActions.end(), worldActions))
        return;  // the usual case: nothing added or removed since the last substep (no allocation)
    m_seenWorldActions.assign(worldActions, worldActions + n);
    std::vector<const btActionInterface*> mine(m_actions.begin(), m_actions.end());
    std::sort(mine.begin(), mine.end());
    m_batch.clear();
    std::vector<const btActionInterface*> taken;  // an action added twice to the world is evaluated once
    for (const btActionInterface* a : m_seenWorldActions) {
        if (!std::binary_search(mine.begin(), mine.end(), a)) continue;
        if (std::find(taken.begin(), taken.end(), a) != taken.end()) continue;
        taken.push_back(a);
        m_batch.push_back(static_cast<btBuoyancyAction*>(const_cast<btActionInterface*>(a)));
    }
    m_batchDirty = false;
}

void btBuoyancyWorld::evaluateBatch(const btCollisionWorld* from, double dt) {
    // The batch: this context's actions in the array of the Bullet world being stepped, in its order. Without a
    // discrete dynamics world at hand (actions stepped by hand), each action evaluates at its own turn.
    const auto* world = dynamic_cast<const btDiscreteDynamicsWorld*>(from);
    if (!world) {
        m_lastBatchSize = 0;
        return;
    }
    const btAlignedObjectArray<btActionInterface*>& actions = WorldActions::of(*world);
    refreshBatch(actions.size() > 0 ? &actions[0] : nullptr, actions.size());
    const int n = int(m_batch.size());
    m_lastBatchSize = m_batch.size();
    if (n == 0) return;
    const BatchFlag inBatch(m_inBatch);
    // The results do not depend on which thread takes which body (everything a body evaluation writes is the body's
    // own: its action's state, caches and scratch).
    btBuoyancyAction* const* batch = m_batch.data();
    preparePrebuilds(n);
    parallelOver(n, getThreads(), FpState::current(),
                 [batch, from, dt, n](int i) {
                     // Two stages ahead: the next action's object, then (its lines arrived) what it points to.
                     if (i + 2 < n) btBuoyancyWorldPrefetch(*batch[i + 2], false);
                     if (i + 1 < n) btBuoyancyWorldPrefetch(*batch[i + 1], true);
                     btBuoyancyWorldEvaluate(*batch[i], from, dt);
                 });
    startPrebuilds(FpState::current());
}

void btBuoyancyWorld::evaluateFloodingBatch(const btCollisionWorld* from, double dt, const btFloodingAction* caller) {
    // Off, or without a discrete dynamics world at hand (actions stepped by hand): each flooding action flows at its
    // own turn.
    const auto* world = m_batching ? dynamic_cast<const btDiscreteDynamicsWorld*>(from) : nullptr;
    if (!world || m_floodingActions.empty()) {
        m_lastFloodingBatchSize = 0;
        return;
    }
    refreshMembers(WorldActions::of(*world), m_floodingActions, m_floodingBatchDirty, m_seenFloodingWorldActions,
                   m_floodingBatch);
    // Only a member starts the batch (the first one called in the substep): one left out flows on its own.
    if (std::find(m_floodingBatch.begin(), m_floodingBatch.end(), caller) == m_floodingBatch.end()) return;
    const int n = int(m_floodingBatch.size());
    m_lastFloodingBatchSize = m_floodingBatch.size();
    const BatchFlag inBatch(m_inBatch);
    // Each flow writes only its own action's water graph and scratch (the body is written at the action's turn).
    btFloodingAction* const* batch = m_floodingBatch.data();
    parallelOver(n, getThreads(), FpState::current(), [batch, dt](int i) { batch[i]->flowForBatch(dt); });
}

void btBuoyancyWorld::evaluateTimeVaryingMassBatch(const btCollisionWorld* from, const btTimeVaryingMassAction* caller) {
    // Off, or without a discrete dynamics world at hand (actions stepped by hand): each action recomputes at its turn.
    const auto* world = m_batching ? dynamic_cast<const btDiscreteDynamicsWorld*>(from) : nullptr;
    if (!world || m_massActions.empty()) {
        m_lastMassBatchSize = 0;
        return;
    }
    refreshMembers(WorldActions::of(*world), m_massActions, m_massBatchDirty, m_seenMassWorldActions, m_massBatch);
    // Only a member starts the batch (the first one called in the substep): one left out recomputes on its own.
    if (std::find(m_massBatch.begin(), m_massBatch.end(), caller) == m_massBatch.end()) return;
    m_lastMassBatchSize = m_massBatch.size();
    // Which maps changed: decided here, on the calling thread, in the world's order (the maps' version functions are
    // called where they would be unbatched); only the changed ones are recomputed across the threads.
    const double time = getTime();
    m_massRecomputes.clear();
    for (btTimeVaryingMassAction* a : m_massBatch)
        if (a->prepareForBatch(time)) m_massRecomputes.push_back(a);
    const int n = int(m_massRecomputes.size());
    if (n == 0) return;
    const BatchFlag inBatch(m_inBatch);
    // Each computation reads its body's shape and map and writes only its own action's pending result (the body is
    // written at the action's turn).
    btTimeVaryingMassAction* const* batch = m_massRecomputes.data();
    parallelOver(n, getThreads(), FpState::current(), [batch](int i) { batch[i]->computeForBatch(); });
}
