#pragma once
/// @file btTimeVaryingMassAction.h
/// A dry mass distribution that changes over time (the paper's Fig. 15 ball; "a small boat with people moving
/// on it"): a density map σ(t, p) over the surface whose mass, centre and inertia are recomputed — only when
/// the map changes — from the same surface samples as the buoyancy (design.md 2.1, shell integrals), and
/// pushed into the body in place (btBuoyantBody::updateMassProperties: the mesh does not jump). With a water
/// graph, the new dry properties go to the btFloodingAction, which composes them with the water.
///
/// The map says when it changes through a version number: version(t) is called every substep and the mass
/// properties are recomputed only when it differs from the last one (e.g. floor(t / interval)).
///
/// Threads: with the world's batching on (btBuoyancyWorld::setBatching), the first time-varying mass action called in a
/// substep checks every one's version (on the calling thread, in the world's action order) and recomputes the changed
/// maps across the world's threads: the density function may then be called from several threads at once, for
/// different bodies (it must not write shared state). Each action applies its own result at its turn.

#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>

#include <BulletDynamics/Dynamics/btActionInterface.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <vector>

class btBuoyancyWorld;
class btFloodingAction;

/// Time-varying density map of one buoyant body, as a Bullet action.
class btTimeVaryingMassAction : public btActionInterface {
public:
    /// Version of the map at water-clock time t, s: recompute when it changes.
    using VersionFn = std::function<std::int64_t(double t)>;
    /// Areal density σ (kg/m², ≥ 0, finite) at body-frame surface point p, for the map of time t, s.
    using DensityFn = std::function<double(double t, const Eigen::Vector3d& p)>;

    /// @param body      the body (not owned)
    /// @param world     the buoyancy context whose clock (getTime) drives the map (not owned)
    /// @param settings  the body's mass settings: `mass` > 0 rescales every map to that total (kg), `ballast`
    ///                  is added; massModel and arealDensity are replaced by the map
    /// @param version   see VersionFn     @param density  see DensityFn
    /// @param flooding  the body's water graph action, or null: receives the dry properties when present
    /// The map of time world->getTime() is applied at once.
    /// @throws std::invalid_argument for a fixed body, a null world or function, or a bad map (body unchanged)
    btTimeVaryingMassAction(btBuoyantBody& body, btBuoyancyWorld* world, btBuoyantBodySettings settings,
                            VersionFn version, DensityFn density, btFloodingAction* flooding = nullptr);
    ~btTimeVaryingMassAction() override;
    btTimeVaryingMassAction(const btTimeVaryingMassAction&) = delete;
    btTimeVaryingMassAction& operator=(const btTimeVaryingMassAction&) = delete;

    /// Called by Bullet once per substep: recompute when the version changed.
    void updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) override;
    /// Nothing to draw.
    void debugDraw(btIDebugDraw*) override {}

    /// How many times the mass properties were recomputed (the first one included).
    long long getRecomputeCount() const { return m_recomputes; }
    /// Version of the map in use.
    std::int64_t getVersion() const { return m_version; }
    /// Recompute and apply the map of time t now. A map that fails (σ negative, NaN, zero everywhere) is
    /// refused and the body keeps its mass properties. @throws std::invalid_argument
    void apply(double t);

    ///@name Save and restore (btBuoyancyState.h, docs/integration.md "Save and restore")
    /// The map's version in use and the recompute count, as a versioned blob of bytes. The body's mass properties are
    /// the btBuoyantBody's (btBuoyantBody::saveState) or, with a water graph, the btFloodingAction's dry ones
    /// (btFloodingAction::saveState). Call between stepSimulation calls.
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote. Read and checked whole before anything changes; the body is not touched.
    /// @param data, size  the blob (size in bytes)
    /// @throws std::invalid_argument naming the problem, the action unchanged: not a state blob, another format
    ///         version or precision, another kind of blob, truncated or corrupted
    void restoreState(const unsigned char* data, std::size_t size);
    /// restoreState of a whole vector. @throws std::invalid_argument (see above)
    void restoreState(const std::vector<unsigned char>& blob) { restoreState(blob.data(), blob.size()); }
    ///@}

    /// Internal (btBuoyancyWorld's batch, calling thread): at the world's time t (s), true when this action's map
    /// changed and its mass properties are to be recomputed by computeForBatch; the result waits for updateAction.
    bool prepareForBatch(double t);
    /// Internal (btBuoyancyWorld's batch, any thread): recompute the mass properties prepareForBatch asked for.
    void computeForBatch();

private:
    /// The mass properties of the map at time t. @throws std::invalid_argument for a bad map
    buoyancy::MassProperties compute(double t) const;
    /// Push `mp` into the body (or the flooding action) as version `version`.
    void commit(const buoyancy::MassProperties& mp, std::int64_t version);
    /// Whether the body takes mass changes now (in a world, not fixed).
    bool active() const;
    btBuoyantBody* m_body;
    btBuoyancyWorld* m_world;
    btBuoyantBodySettings m_settings;
    VersionFn m_versionFn;
    DensityFn m_densityFn;
    btFloodingAction* m_flooding;
    std::int64_t m_version = 0;
    long long m_recomputes = 0;
    /// @name The batch's result for this substep (prepareForBatch, computeForBatch), applied at updateAction
    ///@{
    bool m_batched = false;                 ///< prepared by the batch at m_batchTime
    double m_batchTime = 0;                 ///< the world's time the batch checked the map at, s
    bool m_batchRecompute = false;          ///< the map changed: m_batchResult or m_batchError holds the recompute
    std::int64_t m_batchVersion = 0;        ///< the map's version at m_batchTime
    buoyancy::MassProperties m_batchResult; ///< the recomputed mass properties (valid without m_batchError)
    std::exception_ptr m_batchError;        ///< what the recompute threw, rethrown (or absorbed) at the action's turn
    ///@}
};
