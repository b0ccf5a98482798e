#pragma once
/// @file btFloodingAction.h
/// Water inside a body, coupled to Bullet (paper section 4, design.md 3–4): a companion action to the
/// body's btBuoyancyAction. Each substep it places the water graph at the body's pose, lets water in or
/// out through the permeable samples, moves it inside (Algorithm 1 + eq. 14), and pushes the composed
/// mass, centre of mass and inertia (dry body + water, eqs. 15–17 with the free surface) into the body
/// through btBuoyantBody::updateMassProperties (the mesh does not jump; the velocity field is kept).
///
/// A sealed body simply has no flooding action: it pays nothing.
///
/// Usage:  btBuoyancyAction buoyancy(body, &water);    world->addAction(&buoyancy);
///         btFloodingAction flooding(body, &water, graph, holes);  world->addAction(&flooding);  // after it
/// Gravity: Bullet applies gravity once per stepSimulation call with the mass current at that call, so a
/// mass change takes effect on gravity from the next call (a lag of at most one frame, design.md 3).
/// Threads: with the world's batching on (btBuoyancyWorld::setBatching), the first flooding action called in a
/// substep moves the water of every flooding action of its world that is in the Bullet world, in parallel
/// (btBuoyancyWorld::setThreads); each action then writes its body's mass properties at its own turn. The flow reads
/// only the body's pose and the water, which no action changes within a substep, so the results are bit-identical to
/// each action flowing at its own turn, for any thread count.

#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/graph/WaterGraphState.h>
#include <BulletBuoyancy/graph/PermeabilityMap.h>
#include <BulletBuoyancy/graph/WaterIngress.h>
#include <BulletBuoyancy/integrals/MassProperties.h>

#include <BulletDynamics/Dynamics/btActionInterface.h>

#include <cstddef>
#include <vector>

class btBuoyantBody;
class btBuoyancyWorld;

/// The water graph of one buoyant body, as a Bullet action.
class btFloodingAction : public btActionInterface {
public:
    /// @param body   the body (not owned; remove this action before destroying it). Its current mass
    ///               properties are taken as the dry body's.
    /// @param world  the buoyancy context (water surface, ρ_w, g, clock; not owned; must outlive this action, which
    ///               registers with it for its batch)
    /// @param graph  the water graph, body (mesh) frame (validated here)
    /// @param holes  the permeable samples (permeableSamplesFromRegions / FromValues); empty: stays dry
    ///               unless water is set from code
    /// @throws std::invalid_argument for a bad graph, a fixed body or a null world (nothing is changed)
    btFloodingAction(btBuoyantBody& body, btBuoyancyWorld* world, buoyancy::WaterGraph graph,
                     buoyancy::PermeableSamples holes = buoyancy::PermeableSamples());
    ~btFloodingAction() override;
    btFloodingAction(const btFloodingAction&) = delete;
    btFloodingAction& operator=(const btFloodingAction&) = delete;

    /// Called by Bullet once per substep (after the buoyancy action when added after it).
    void updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) override;
    /// Draws each node with water as a cross at its water centre.
    void debugDraw(btIDebugDraw* debugDrawer) override;

    /// The water state (volumes, levels, ledger). Changing water through it takes effect next substep.
    buoyancy::WaterGraphState& getState() { return m_state; }
    /// The water state.
    const buoyancy::WaterGraphState& getState() const { return m_state; }
    /// Σ water in the body, m³.
    double getWaterVolume() const { return m_state.totalWater(); }
    /// Replace the permeable samples at run time (e.g. a hit opens a hole). Nodes out of range are refused.
    /// @throws std::invalid_argument
    void setPermeableSamples(buoyancy::PermeableSamples holes);
    /// Replace the permeable samples by those of a per-sample map (e.g. after PermeabilityMap::paintSphere for
    /// a hit). The map must belong to this body's graph (same node count). All-or-nothing.
    /// @throws std::invalid_argument
    void setPermeability(const buoyancy::PermeabilityMap& map) { setPermeableSamples(map.permeableSamples()); }
    /// The permeable samples in use.
    const buoyancy::PermeableSamples& getPermeableSamples() const { return m_holes; }
    /// The dry body's mass properties, mesh frame (mass kg, centre m, inertia about the centre kg·m²).
    const buoyancy::MassProperties& getDryMassProperties() const { return m_dry; }
    /// Change the dry body (time-varying density, the paper's Fig. 15): recomposed at the next substep.
    /// @throws std::invalid_argument for a non-positive mass or non-finite values
    void setDryMassProperties(const buoyancy::MassProperties& dry);
    /// Push the composed mass properties into the body now (also done every substep).
    void updateBodyMassProperties();

    ///@name Save and restore (btBuoyancyState.h, docs/integration.md "Save and restore")
    /// The water graph's state as a versioned blob of bytes: each node's water (m³), levels and heights at the last
    /// pose, the exchange ledger, the random generator of the discharge search, the permeable samples in use and the
    /// dry body's mass properties. The body's composed mass properties are the btBuoyantBody's: save them with
    /// btBuoyantBody::saveState. Call between stepSimulation calls.
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote into an action of the same water graph (this one or one built the same way).
    /// Read and checked whole before anything changes; the body is not touched (restore it with
    /// btBuoyantBody::restoreState).
    /// @param data, size  the blob (size in bytes)
    /// @throws std::invalid_argument naming the problem, the action unchanged: not a state blob, another format
    ///         version or precision, another kind of blob, truncated or corrupted, or a blob of a graph with another
    ///         node count, or permeable samples naming a node the graph does not have
    void restoreState(const unsigned char* data, std::size_t size);
    /// restoreState of a whole vector. @throws std::invalid_argument (see above)
    void restoreState(const std::vector<unsigned char>& blob) { restoreState(blob.data(), blob.size()); }
    ///@}

    /// Internal (btBuoyancyWorld's batch): place the graph at the body's pose, let water in and out and move it for
    /// a substep of dt seconds, without writing to the body; updateAction then writes the mass properties. Called
    /// on a worker thread, for this action only.
    void flowForBatch(double dt);

private:
    /// The flow of one substep (flowForBatch's work): sets m_flowed, and m_massPending / m_wake for updateAction.
    void flow(double dt);

    btBuoyantBody* m_body;
    btBuoyancyWorld* m_world;
    buoyancy::WaterGraphState m_state;
    buoyancy::PermeableSamples m_holes;
    buoyancy::MassProperties m_dry;
    buoyancy::IngressScratch m_scratch;
    std::vector<double> m_wx, m_wy, m_wz, m_f;  // world positions and water heights of the holes
    bool m_dirty = true;
    bool m_flowed = false;       ///< this substep's flow is done (by the batch), its mass update not yet
    bool m_massPending = false;  ///< the flow ran with gravity along the water's down: update the mass properties
    bool m_wake = false;         ///< the water inside changed: wake the body
};
