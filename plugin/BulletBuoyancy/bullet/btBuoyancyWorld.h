#pragma once
/// @file btBuoyancyWorld.h
/// The per-world buoyancy context shared by every btBuoyancyAction of one btDynamicsWorld: the water
/// surface (injected, not owned), the fluid, the world's gravity and the water's clock. Actions register with it,
/// so a batching backend (threads, OpenCL) can compute every body when the first action of a substep is called
/// and let the others read their result.
///
/// Threads (docs/integration.md, design.md): at the first btBuoyancyAction of the world called in a substep, every
/// body whose action is in the Bullet world is evaluated once, in parallel (setThreads); each action then applies
/// its own impulses at its own turn in Bullet's action order. Results are bit-identical for any thread count.
///
/// Gravity is the world's: the context reads it from the btDynamicsWorld every substep, so a change at run time is
/// followed. The pressure gradient belongs to the water, so buoyancy uses the world's gravity; a body's own gravity
/// (btRigidBody::setGravity) is its weight only (design.md 3). "Up" is −ĝ of the world: the water surface is a height
/// field along up in the context's water frame (btWaterFrame: by default derived from the world's gravity, or set
/// explicitly). A frame whose up is not antiparallel to the world's gravity (beyond 1e-6 rad) is refused; gravity
/// turned away from it later gives the bodies no buoyancy, with a status saying why.

#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>
#include <BulletBuoyancy/bullet/btWaterBody.h>
#include <BulletBuoyancy/bullet/btWaterFrame.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class btWaterSurface;
class btBuoyancyAction;
class btFloodingAction;
class btTimeVaryingMassAction;
class btBuoyancyDeviceBackend;
class btBuoyancyDeviceBody;
class btActionInterface;
class btCollisionWorld;
class btDynamicsWorld;
class btIDebugDraw;

/// Why the bodies of a world got no buoyancy in a substep although they may be in the water
/// (btBuoyancyResult::status, btBuoyancyWorld::getGravityStatus).
enum class btBuoyancyStatus {
    Ok,                     ///< buoyancy computed (or nothing to compute: dry, asleep)
    NoGravity,              ///< the world's gravity is zero: no pressure gradient, so no buoyancy
    GravityNotAlongWaterUp, ///< the world's gravity does not point down the water frame's up axis (or is not finite)
};

/// One sentence for logs and messages, e.g. "the world's gravity is zero: no buoyancy".
const char* btBuoyancyStatusMessage(btBuoyancyStatus status);

/// Where the sampled bodies of a world are computed (docs/opencl.md).
enum class btBuoyancyCompute {
    Cpu,    ///< each action on the CPU (default)
    OpenCl, ///< every body of the world in one batched launch set per substep on an OpenCL device
};

/// Shared buoyancy context of one dynamics world.
class btBuoyancyWorld {
public:
    /// The context of `world`: its gravity is read from the world at every substep.
    /// @param world         the dynamics world the actions are added to; not owned, must outlive the context
    /// @param water         the water surface; not owned, must outlive the context (nullptr: no water)
    /// @param fluidDensity  ρ_w, kg/m³ (fresh water 1000, sea water 1025), > 0
    /// The water frame is the default one of the world's gravity (btWaterFrame::fromGravity: up = −ĝ, first
    /// horizontal axis +x whenever up ⟂ x); in a world without gravity at construction, it is derived from the first
    /// non-zero gravity read at a substep.
    /// @throws std::invalid_argument for a null world, a bad density or a non-finite gravity
    btBuoyancyWorld(btDynamicsWorld* world, const btWaterSurface* water, double fluidDensity = 1000.0);
    /// The context of `world` with an explicit water frame (the surface is a height field along frame.up()).
    /// @throws std::invalid_argument for a null world, a bad density, or a frame whose up is not antiparallel to the
    ///         world's non-zero gravity within 1e-6 rad (the message names both vectors)
    btBuoyancyWorld(btDynamicsWorld* world, const btWaterSurface* water, const btWaterFrame& frame,
                    double fluidDensity = 1000.0);
    /// A context without its dynamics world at hand. `gravity` (the magnitude g of (0, −g, 0), m/s², ≥ 0) is used
    /// until the first substep; from then on the gravity of the world the actions are stepped in is read every
    /// substep, as with the other constructor (the two can no longer disagree). Prefer the other constructor.
    /// @throws std::invalid_argument naming a bad parameter
    explicit btBuoyancyWorld(const btWaterSurface* water, double fluidDensity = 1000.0, double gravity = 9.81);
    ~btBuoyancyWorld();
    btBuoyancyWorld(const btBuoyancyWorld&) = delete;
    btBuoyancyWorld& operator=(const btBuoyancyWorld&) = delete;

    /// The unbounded water surface (may be nullptr: no unbounded water; see the water bodies below).
    const btWaterSurface* getWater() const { return m_water; }
    /// Replace the unbounded water surface (not owned; nullptr: none).
    /// @throws std::invalid_argument for a non-null surface while the world has water bodies (one or the other)
    void setWater(const btWaterSurface* water);
    /// ρ_w of the unbounded water, kg/m³ (each water body has its own: btWaterBody::fluidDensity).
    double getFluidDensity() const { return m_fluidDensity; }

    ///@name Water bodies (btWaterBody.h, design.md 2.9): several bounded waters instead of the unbounded one
    /// Add a bounded water body: a surface inside a region (an axis-aligned box of the world, a footprint polygon
    /// extruded along up, or a closed convex mesh: btWaterRegionKind), with its own density. A body takes
    /// its buoyancy and drag from the water bodies its bounding sphere reaches (none: no buoyancy, no drag); a body
    /// straddling a region's side or bottom, or two regions, takes each part of its wetted surface from the water of
    /// the region it is in (btBuoyancyAction, design.md 2.9). Add water bodies between steps.
    /// @return the index of the new water body in getWaterBodies()
    /// @throws std::invalid_argument naming the problem, the world unchanged: a null surface, a non-positive or
    ///         non-finite density, a non-finite corner or one whose min is not below its max on an axis (the message
    ///         names regionMin/regionMax and the axis), a degenerate or self-intersecting footprint or bottom >= top
    ///         (the message names footprint, bottom or top), an open, inward or non-convex region mesh, a region
    ///         overlapping another water body's (the message names both bodies and their regions; regions that only
    ///         touch are accepted: an exact separating-axis test between their convex pieces), or a world with an
    ///         unbounded water (construct it with water = nullptr, or setWater(nullptr) first)
    int addWaterBody(const btWaterBodyInfo& info);
    /// The water bodies, in the order added (empty: the unbounded water of getWater() applies).
    const std::vector<btWaterBody>& getWaterBodies() const { return m_waterBodies; }
    /// Remove every water body (between steps).
    void removeAllWaterBodies();
    /// True when some water body's surface changes over time (bodies near it are kept awake).
    bool isAnyWaterBodyTimeVarying() const { return m_anyWaterBodyTimeVarying; }
    /// The water body nearest `point` among those whose region the sphere (`centre`, `radius`) reaches, or −1 when the
    /// sphere reaches none; ties go to the lower index. Points, world, m; radius, m, ≥ 0. O(number of water bodies).
    int findWaterBody(const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& point) const;
    ///@}
    /// @throws std::invalid_argument for a non-positive or non-finite density
    void setFluidDensity(double density);
    /// g, m/s²: the magnitude of the world's gravity in the current substep (0 when its status is not Ok).
    double getGravity() const { return m_gravity; }
    /// The world's gravity vector last read, m/s², world ((0, −g, 0) until a world was read, for the constructor
    /// without one).
    const Eigen::Vector3d& getGravityVector() const { return m_gravityVector; }

    ///@name Water frame (btWaterFrame.h, design.md 3)
    /// The frame the water surface is a height field in: every body's pose and velocities are mapped into it and its
    /// forces and torques back; a surface's heights are measured along its up, its x, z coordinates are the frame's
    /// horizontal axes.
    const btWaterFrame& getWaterFrame() const { return m_frame; }
    /// Set the water frame explicitly (it no longer follows the first gravity read). The dynamics world's gravity is
    /// read now (so set the world's gravity first when turning a whole scene).
    /// @throws std::invalid_argument when the world's gravity is known, non-zero and not antiparallel to frame.up()
    ///         within 1e-6 rad (the message names both vectors); the frame is then unchanged
    void setWaterFrame(const btWaterFrame& frame);
    /// True when the frame was set explicitly or derived from a gravity already (false: it is still the default
    /// y-up frame waiting for the first non-zero gravity).
    bool isWaterFrameFixed() const { return m_frameFixed; }
    /// Counts the changes of the water frame (set explicitly or derived from gravity): what an action evaluated in
    /// the old frame (its temporal level-of-detail records, water-query caches) is dropped when it changes.
    std::uint64_t getWaterFrameVersion() const { return m_frameVersion; }
    ///@}
    /// Set g, m/s², for actions stepped without a dynamics world; overwritten at the next substep by the gravity of
    /// the world the actions are stepped in. @throws std::invalid_argument for a negative or non-finite value
    void setGravity(double g);
    /// Whether the world's gravity allows buoyancy in the current substep, and if not why.
    btBuoyancyStatus getGravityStatus() const { return m_gravityStatus; }
    /// The status as a sentence naming the gravity and the water frame's up, e.g. "the world's gravity
    /// (0, 0, -9.81) m/s^2 does not point down the water frame's up axis (0, 1, 0): no buoyancy".
    std::string getGravityStatusMessage() const;
    /// The dynamics world given to the constructor (nullptr for the constructor without one).
    btDynamicsWorld* getDynamicsWorld() const { return m_dynamicsWorld; }

    /// Time of the water surface at the end of the current substep, s. Advanced by dt once per substep by
    /// the actions themselves (see beginSubstepIfNew), so no callback or action order is needed.
    double getTime() const { return m_time; }
    /// Set the water's clock, s (e.g. to start a wave scene at t0).
    void setTime(double t) { m_time = t; }
    /// Number of substeps seen so far.
    std::uint64_t getSubstep() const { return m_substep; }

    ///@name Save and restore (btBuoyancyState.h, docs/integration.md "Save and restore")
    /// The world's state as a versioned blob of bytes: the water's clock (getTime), the substep counter (getSubstep),
    /// the water frame with its version and whether it is fixed, the gravity last read with its status, and the last
    /// batch's size. With each body's btBuoyancyAction::saveState (and btFloodingAction, btTimeVaryingMassAction,
    /// btBuoyantBody and btInteractiveWaterCoupler where used) and the Bullet bodies' own state, a replay or a rollback
    /// goes on bit-identically. Not saved: the configuration (surfaces, densities, water bodies, event settings and
    /// listeners, threads, batching, compute backend: build the world the same way); the interactive water's grid is
    /// saved by its coupler (btInteractiveWaterCoupler::saveState), the state of other surfaces that keep their own is
    /// not. Call between stepSimulation calls.
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote (into this world or one built the same way). Read and checked whole before
    /// anything changes.
    /// @param data, size  the blob (size in bytes)
    /// @throws std::invalid_argument naming the problem, the world unchanged: not a state blob (wrong magic), another
    ///         format version, a blob of the other precision, another kind of blob, truncated or corrupted
    /// @throws std::logic_error when called during a step (from an event callback or the batch)
    void restoreState(const unsigned char* data, std::size_t size);
    /// restoreState of a whole vector. @throws std::invalid_argument, std::logic_error (see above)
    void restoreState(const std::vector<unsigned char>& blob) { restoreState(blob.data(), blob.size()); }
    ///@}

    /// Registered actions (every btBuoyancyAction built with this context, in or out of a world).
    const std::vector<btBuoyancyAction*>& getActions() const { return m_actions; }
    /// The same bodies as a batching backend sees them (btBuoyancyDeviceBackend), in the same order.
    const std::vector<btBuoyancyDeviceBody*>& getDeviceBodies() const { return m_deviceBodies; }

    /// Called by each action at the start of its updateAction. A new substep has begun when the calling
    /// action was already called in the current one (Bullet calls every action once per substep): the
    /// clock advances by dt, and a batching backend would compute every registered body here.
    /// At a new substep the world's gravity is read again (getGravity, getGravityStatus).
    /// @param lastSeen  the action's own record of the substep it last ran in (updated)
    /// @param from      the world the calling action is stepped in (Bullet's updateAction argument); its gravity
    ///                  is used when the context was made without a dynamics world (nullptr: keep the last g)
    void beginSubstepIfNew(std::uint64_t& lastSeen, double dt, const btCollisionWorld* from = nullptr);

    ///@name Compute backend (docs/opencl.md)
    /// Select where the sampled bodies of this world are computed. OpenCl: one batched launch set per substep on
    /// the first OpenCL GPU, else the first device (env BULLET_BUOYANCY_OPENCL_DEVICE=n picks device n), double
    /// precision when the device has cl_khr_fp64. When the library was built without OpenCL, or no platform or
    /// device works, the CPU path stays selected and `message` says why: never an exception for that.
    /// @param message  optional: the reason of a failure, or the device and precision chosen
    /// @return true when `compute` is now in use
    bool setCompute(btBuoyancyCompute compute, std::string* message = nullptr);
    /// The backend in use.
    btBuoyancyCompute getCompute() const { return m_device ? btBuoyancyCompute::OpenCl : btBuoyancyCompute::Cpu; }
    /// Install a backend built by hand (e.g. btOpenClBuoyancyBackend::create with options); owned. nullptr: CPU.
    void setDeviceBackend(std::unique_ptr<btBuoyancyDeviceBackend> backend);
    /// The installed backend, or nullptr (CPU).
    btBuoyancyDeviceBackend* getDeviceBackend() const { return m_device.get(); }
    ///@}

    ///@name Threads: every body of the world evaluated once per substep, in parallel
    /// The number of threads the bodies are evaluated on, ≥ 1; 0 (the default) = the hardware's (the cores the process
    /// may use). Results are bit-identical for every value: one thread runs the same batched schedule in order. When
    /// the Bullet in use has a task scheduler with more than one thread (btGetTaskScheduler()), its parallelFor runs
    /// the batch on its pool and its thread count applies instead (one pool for the library and Bullet).
    /// Without threads at build time (BULLET_BUOYANCY_THREADS=OFF) the batch runs on the calling thread.
    /// @throws std::invalid_argument for n < 0
    void setThreads(int n);
    /// The number of threads the next batch runs on, ≥ 1 (setThreads's 0 resolved to the hardware's; 1 when built
    /// without threads; the scheduler's when Bullet's task scheduler runs the batch).
    int getThreads() const;
    /// Queries ahead: at the end of each batch, a helper thread of the world's own queries the wave heights of the
    /// patches the bodies' next exact evaluations will build (btBuoyancySettings::waterPatchNodes; the temporal level
    /// of detail's schedule says which bodies), on a copy of the surface (btWaterSurface::cloneForQueriesAhead), while
    /// Bullet's own step runs on the calling thread; the next substep uses them where its patch has the same nodes, time
    /// and surface, so the results are bit for bit those without. Only with 2 or more threads (getThreads) and no
    /// Bullet task scheduler. The last substep's queries may still run after stepSimulation returns: they read only the
    /// world's copy and the actions, and the world waits for them before anything they read changes (the next substep,
    /// removing an action, restoreState, the destructor). Default: on when the library's threads are oneTBB's, off with
    /// OpenMP's (its waiting thread spins through Bullet's step and would take the helper's core).
    void setQueriesAhead(bool on) { m_queriesAhead = on; }
    /// Whether queries ahead are on (setQueriesAhead).
    bool getQueriesAhead() const { return m_queriesAhead; }
    /// Batching on (default): at the first btBuoyancyAction of the world called in a substep, every body whose
    /// action is in the Bullet world is evaluated (water, hydrostatics, drag, temporal level of detail, decisions),
    /// and each action applies its impulses at its own turn. Off: each action evaluates and applies at its own turn
    /// on the calling thread, one after the other (the order of Bullet's action array). The two give bit-identical
    /// results unless another action writes a buoyant body after the world's first buoyancy action and before that
    /// body's own action in the same substep (then the batch saw the body before that write): add such actions
    /// (vehicles, thrusters, user mass changes) before the buoyancy actions, or after each body's own buoyancy action,
    /// or switch batching off. Ignored (per-action) while a device backend is installed (setCompute).
    void setBatching(bool on) { m_batching = on; }
    /// Whether batching is on (setBatching).
    bool getBatching() const { return m_batching; }
    /// Bodies evaluated in the last batch (0 when the last substep ran per action).
    int getLastBatchSize() const { return int(m_lastBatchSize); }
    /// Wave patch heights queried ahead in the last batch: the bodies whose next exact evaluation's patch heights were
    /// queried on another thread while Bullet stepped (0 with one thread, without a surface copy, or before the first
    /// batch). The results are the same with or without (each body's patch is bit for bit the one it would query).
    int getLastQueriedAhead() const { return int(m_lastQueriedAhead); }
    /// Internal (btBuoyancyAction): whether the actions of this substep's batch ask for their next exact evaluation's
    /// patch heights (queried on another thread while Bullet steps).
    bool prebuildsPatches() const { return m_prebuildPatches; }
    /// Internal (btBuoyancyAction): the copy of `water` the heights are queried ahead on, or nullptr.
    const btWaterSurface* surfaceForQueriesAhead(const btWaterSurface* water) const;
    /// Internal: wait for the heights being queried ahead (prebuildsPatches); nothing when none are. Called before
    /// anything the queries read is changed: a new substep, an action's removal, a state restore, the destructor.
    void finishPrebuilds();
    /// Flooding actions (btFloodingAction) whose water moved in the last flooding batch (0 when they flowed per
    /// action: batching off, or no discrete dynamics world stepping them).
    int getLastFloodingBatchSize() const { return int(m_lastFloodingBatchSize); }
    /// Time-varying mass actions (btTimeVaryingMassAction) whose maps were checked in the last mass batch (their
    /// changed ones recomputed across the threads; 0 when they ran at their own turns: batching off, or not in a
    /// discrete dynamics world).
    int getLastTimeVaryingMassBatchSize() const { return int(m_lastMassBatchSize); }
    ///@}

    ///@name Events and queries for game logic (btBuoyancyEvents.h, docs/integration.md "Events and queries")
    /// Register a listener of every body's water events (enter, leave, fully submerged, surfaced); not owned, must
    /// stay alive while registered. Listeners are called in the order registered; adding one twice is ignored.
    /// Callable at any time, also from a callback (then it receives events from the next one on).
    /// @throws std::invalid_argument for nullptr
    void addEventListener(btBuoyancyEventListener* listener);
    /// Unregister a listener (unknown ones are ignored); from a callback, it receives no further event.
    void removeEventListener(btBuoyancyEventListener* listener);
    /// The registered listeners, in registration order (during a dispatch a listener removed by a callback is a
    /// nullptr entry until the dispatch ends).
    const std::vector<btBuoyancyEventListener*>& getEventListeners() const { return m_listeners; }
    /// The hysteresis of the events (thresholds on each body's submerged fraction; defaults in btBuoyancyEventSettings).
    /// @throws std::invalid_argument naming the field (the settings unchanged)
    void setEventSettings(const btBuoyancyEventSettings& settings);
    /// The event thresholds in use.
    const btBuoyancyEventSettings& getEventSettings() const { return m_eventSettings; }
    /// True while listeners are being called (inside stepSimulation).
    bool isDispatchingEvents() const { return m_dispatching; }
    /// What the water is at `point` (world, m) at the water's current time (getTime): whether water lies above or
    /// below it and which (a water body whose region holds the point, else one whose region's sides hold it and whose
    /// bottom is below it, the lowest index first; or the unbounded water), the surface's height along the water frame's up and
    /// the point's depth, the surface's normal (by central differences of the heights over 1/1000 of the shortest
    /// wavelength, 1 mm when the surface has none) and the water's velocity, all in world coordinates. Five height
    /// queries and one velocity query; no allocation. Safe from several threads at once between steps (surfaces
    /// answer const calls concurrently), and from event callbacks; not from another thread during stepSimulation.
    /// @throws std::invalid_argument for a non-finite point
    btWaterQueryResult queryWater(const btVector3& point) const;
    /// Draw each water surface as a grid of line segments through `drawer` (drawLine), at the surface's height at
    /// each grid point at the water's current time, in the water frame: a water body's grid covers its region's
    /// footprint, the unbounded water's a square of side 2 × halfSize centred below `centre`.
    /// @param drawer        the user's btIDebugDraw (not owned)
    /// @param centre        world point the unbounded water's grid is centred on (e.g. the camera), m
    /// @param halfSize      half the side of the unbounded water's grid, m, finite and > 0
    /// @param cellsPerSide  grid cells along each side, 1..1024 ((cellsPerSide + 1)² surface points per surface)
    /// @param colour        the lines' colour (RGB in 0..1)
    /// @throws std::invalid_argument for a null drawer, a bad halfSize or cellsPerSide
    void debugDrawWater(btIDebugDraw* drawer, const btVector3& centre = btVector3(0, 0, 0), btScalar halfSize = 50,
                        int cellsPerSide = 32, const btVector3& colour = btVector3(btScalar(0.2), btScalar(0.5), 1)) const;
    /// Internal (btBuoyancyAction): deliver `count` events of `action` to the listeners, in order.
    void dispatchEvents(btBuoyancyAction& action, const btBuoyancyEventType* types, const int* waterBodies, int count,
                        double submergedFraction);
    ///@}

    /// Internal: actions register and unregister themselves. Returns how many actions registered before this one
    /// (its turn among the bodies for the temporal level of detail; deterministic for a given scene).
    std::uint64_t registerAction(btBuoyancyAction* action);
    void unregisterAction(btBuoyancyAction* action);
    /// Internal: flooding actions register and unregister themselves (their batch, evaluateFloodingBatch).
    void registerFloodingAction(btFloodingAction* action);
    void unregisterFloodingAction(btFloodingAction* action);
    /// Internal (btFloodingAction::updateAction): with batching on and `caller` one of them, move the water of every
    /// registered flooding action that is in `from`'s action array (once each) for a substep of dt seconds, across
    /// the threads.
    void evaluateFloodingBatch(const btCollisionWorld* from, double dt, const btFloodingAction* caller);
    /// Internal: time-varying mass actions register and unregister themselves (evaluateTimeVaryingMassBatch).
    void registerTimeVaryingMassAction(btTimeVaryingMassAction* action);
    void unregisterTimeVaryingMassAction(btTimeVaryingMassAction* action);
    /// Internal (btTimeVaryingMassAction::updateAction): with batching on and `caller` one of them, check the map of
    /// every registered time-varying mass action that is in `from`'s action array (once each) at the world's time,
    /// and recompute the changed ones' mass properties across the threads; each applies its own at its turn.
    void evaluateTimeVaryingMassBatch(const btCollisionWorld* from, const btTimeVaryingMassAction* caller);

private:
    friend class btBuoyancyImmediate;  // sets the gravity vector of its private context
    /// Read gravity (m/s², world frame) into m_gravity and m_gravityStatus.
    void followGravity(double gx, double gy, double gz);
    /// Evaluate every registered action that is in `from`'s action array (the batch), across the threads.
    void evaluateBatch(const btCollisionWorld* from, double dt);
    /// Rebuild m_batch when the Bullet world's action array or the registered actions changed since the last batch.
    void refreshBatch(const btActionInterface* const* worldActions, int count);

    btDynamicsWorld* m_dynamicsWorld = nullptr;
    const btWaterSurface* m_water;
    double m_fluidDensity;
    std::vector<btWaterBody> m_waterBodies;   ///< addWaterBody (empty: the unbounded m_water)
    bool m_anyWaterBodyTimeVarying = false;   ///< some water body's surface is time-varying
    double m_gravity;
    Eigen::Vector3d m_gravityVector = Eigen::Vector3d(0, -9.81, 0);
    bool m_gravityKnown = false;  ///< m_gravityVector was read from a world (or given)
    btWaterFrame m_frame;
    bool m_frameFixed = false;    ///< set explicitly, or derived from a non-zero gravity
    std::uint64_t m_frameVersion = 0;
    btBuoyancyStatus m_gravityStatus = btBuoyancyStatus::Ok;
    double m_time = 0;
    std::uint64_t m_substep = 0;
    std::vector<btBuoyancyAction*> m_actions;
    std::vector<btBuoyancyDeviceBody*> m_deviceBodies;  ///< m_actions as btBuoyancyDeviceBody
    std::uint64_t m_registrations = 0;  ///< actions registered so far (never decreases)
    std::unique_ptr<btBuoyancyDeviceBackend> m_device;  ///< batching backend, nullptr = CPU
    /// @name Events (addEventListener)
    ///@{
    std::vector<btBuoyancyEventListener*> m_listeners;  ///< registration order (nullptr: removed during a dispatch)
    btBuoyancyEventSettings m_eventSettings;
    bool m_dispatching = false;  ///< listeners are being called
    bool m_listenersRemoved = false;  ///< some entries of m_listeners were set to nullptr during the dispatch
    /// The water body whose region holds `point` (world, m), else one whose region but its top face does (lowest
    /// index first), or −1.
    int waterBodyAt(const Eigen::Vector3d& point) const;
    ///@}
    /// @name Threads
    ///@{
    int m_threads = 0;                ///< setThreads (0: the hardware's)
    bool m_batching = true;           ///< setBatching
    /// True while a batch runs: creating or destroying an action then is refused with a message.
    std::atomic<bool> m_inBatch{false};
    bool m_batchDirty = true;         ///< the registered actions changed since m_batch was built
    std::vector<const btActionInterface*> m_seenWorldActions; ///< the Bullet world's action array m_batch was built from
    std::vector<btBuoyancyAction*> m_batch; ///< registered actions in the Bullet world, in its order
    std::vector<btFloodingAction*> m_floodingActions;  ///< registered flooding actions
    bool m_floodingBatchDirty = true;  ///< the registered flooding actions changed since m_floodingBatch was built
    /// The Bullet world's action array m_floodingBatch was built from.
    std::vector<const btActionInterface*> m_seenFloodingWorldActions;
    /// Registered flooding actions in the Bullet world (each there once), in its order.
    std::vector<btFloodingAction*> m_floodingBatch;
    std::size_t m_lastFloodingBatchSize = 0;  ///< flooding actions in the last flooding batch
    std::vector<btTimeVaryingMassAction*> m_massActions;  ///< registered time-varying mass actions
    bool m_massBatchDirty = true;  ///< the registered time-varying mass actions changed since m_massBatch was built
    /// The Bullet world's action array m_massBatch was built from.
    std::vector<const btActionInterface*> m_seenMassWorldActions;
    /// Registered time-varying mass actions in the Bullet world (each there once), in its order.
    std::vector<btTimeVaryingMassAction*> m_massBatch;
    std::vector<btTimeVaryingMassAction*> m_massRecomputes;  ///< the members whose map changed in the last batch
    std::size_t m_lastMassBatchSize = 0;  ///< time-varying mass actions in the last mass batch
    std::size_t m_lastBatchSize = 0;  ///< bodies evaluated in the last batch
    bool m_prebuildPatches = false;   ///< see prebuildsPatches
    static bool queriesAheadByDefault();  ///< on with oneTBB's threads (btBuoyancyThreads.cpp)
    bool m_queriesAhead = queriesAheadByDefault();  ///< setQueriesAhead
    std::size_t m_lastQueriedAhead = 0;  ///< see getLastQueriedAhead
    struct PrebuildJob;
    /// The heights being queried ahead on another thread, the surface copies they use, and that thread's arena
    /// (btBuoyancyThreads.cpp).
    std::shared_ptr<PrebuildJob> m_prebuildJob;
    /// Decide whether this batch's actions ask for patch heights ahead, and refresh the surface copies.
    void preparePrebuilds(int batchSize);
    /// Start querying the batch's requested patch heights on another thread (or nothing).
    void startPrebuilds(unsigned csr);
    ///@}
};
