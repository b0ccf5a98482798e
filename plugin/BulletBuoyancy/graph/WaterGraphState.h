#pragma once
/// @file WaterGraphState.h
/// The running state of one body's water graph (paper section 4.2, design.md 4): the water in each
/// node, its level at the body's current pose, the exchange with the outside and the flow inside.
///
/// Conservation is exact to rounding: every move takes from one node what it gives to another, and every
/// exchange with the outside is counted in a compensated ledger, so
/// Σ node water − initial water = entered − drained at all times. No node is ever negative or over its
/// capacity, and no move overshoots the level that would stop it.

#include <BulletBuoyancy/graph/DischargeSearch.h>
#include <BulletBuoyancy/graph/WaterGraph.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace buoyancy {

/// Water of one graph at one pose.
class WaterGraphState {
public:
    /// @throws std::invalid_argument (WaterGraph::validate)
    explicit WaterGraphState(WaterGraph graph);

    /// The graph (node positions, capacities, initial water and parameters).
    const WaterGraph& graph() const { return m_graph; }
    /// Number of nodes.
    std::size_t size() const { return m_water.size(); }
    /// Water in node i, m³.
    double water(int i) const { return m_water[std::size_t(i)]; }
    /// Water of every node, m³.
    const std::vector<double>& waterVolumes() const { return m_water; }
    /// Σ node water, m³.
    double totalWater() const;
    /// Water that came in from outside (exchange > 0), m³, compensated sum.
    double enteredVolume() const { return m_entered; }
    /// Water that went out (exchange < 0), m³, positive, compensated sum.
    double drainedVolume() const { return m_drained; }
    /// Σ initial water (graph's node "water") plus what setWater added or removed, m³.
    double initialVolume() const { return m_initial; }
    /// Set node i's water directly (e.g. a scripted event), m³ in [0, capacity]; counted in initialVolume.
    /// @throws std::invalid_argument for a bad index or volume
    void setWater(int i, double volume);

    /// Place the body: node heights, levels and the up direction in body axes follow `bodyToWorld`
    /// (mesh frame → world). Call before exchange/flow/massProperties whenever the body moved.
    void setPose(const Eigen::Isometry3d& bodyToWorld);
    /// World up (0, 1, 0) in body axes at the current pose.
    const Eigen::Vector3d& upInBody() const { return m_up; }
    /// World y of node i's centre, m.
    double centreHeight(int i) const { return m_centreY[std::size_t(i)]; }
    /// World y of node i's lowest point, m.
    double bottomHeight(int i) const { return m_bottom[std::size_t(i)]; }
    /// World y of node i's water level (its bottom when empty, its top when full), m.
    double levelHeight(int i) const { return m_level[std::size_t(i)]; }
    /// True when node i holds its capacity.
    bool isFull(int i) const { return m_full[std::size_t(i)] != 0; }
    /// Centre of node i's water, body frame, m (free surface: the water lies at the bottom in world down).
    Eigen::Vector3d waterCentroid(int i) const;

    /// Exchange with the outside: add `volume` (> 0) or remove (< 0) from node i, limited so the node
    /// never goes below 0 or above capacity, and its level never rises above `levelLimit` (inflow) or
    /// falls below it (outflow), world y, m. Counted in the ledger.
    /// @return the volume actually exchanged, signed, m³
    double exchange(int i, double volume, double levelLimit);

    /// Outside water pushing through full node i (its hole's outside surface at `outsideLevel`, world y)
    /// into the graph beyond: Algorithm 1 from i with that head, the flow capped by the path's pipes
    /// (eq. 14 and the orifice rate) and by the room under `outsideLevel` in the target. Counted as entered.
    /// @return the volume that came in, m³
    double pushThrough(int i, double volume, double outsideLevel, double dt, double fluidDensity, double gravity);

    /// Move water inside the graph for `dt` seconds (Poiseuille along findDischargeNode paths, or
    /// diffusion between neighbours; see WaterFlowModel).
    /// @param fluidDensity ρ, kg/m³   @param gravity g, m/s²
    void flow(double dt, double fluidDensity, double gravity);

    /// Algorithm 1 from `source` at the current pose (advances the seeded generator).
    DischargePath findDischargeNode(int source);

    /// Everything that carries from one substep to the next, for save and restore (btFloodingAction::saveState):
    /// the water (m³), the ledger, the random generator's state, and the levels and heights of the last pose.
    struct Dynamic {
        std::vector<double> water, centreY, bottom, level, half; ///< #nodes each: m³, then world heights, m
        std::vector<unsigned char> full;                         ///< #nodes: non-zero when full
        Eigen::Vector3d up = Eigen::Vector3d::UnitY();           ///< world up in body axes
        double entered = 0, enteredC = 0, drained = 0, drainedC = 0, initial = 0; ///< ledger, m³ (with compensations)
        std::uint64_t rng = 0;                                   ///< SplitMix64::state
    };
    /// The dynamic state, bit for bit.
    Dynamic dynamicState() const;
    /// Set the dynamic state saved by dynamicState (a state of this graph).
    /// @throws std::invalid_argument when an array's size is not the node count (the state unchanged)
    void setDynamicState(const Dynamic& state);

private:
    void updateLevel(int i);
    void transfer(int from, int to, double volume);
    double equalisingVolume(int from, int to) const;
    void flowPoiseuille(double dt, double rho, double g);
    void flowDiffusion(double dt);

    WaterGraph m_graph;
    DischargeSearch m_search;
    SplitMix64 m_rng;
    std::vector<double> m_water, m_centreY, m_bottom, m_level, m_half;
    std::vector<unsigned char> m_full;
    std::vector<int> m_order, m_edgeOrder;
    Eigen::Vector3d m_up = Eigen::Vector3d::UnitY();
    double m_entered = 0, m_enteredC = 0, m_drained = 0, m_drainedC = 0, m_initial = 0;
};

}  // namespace buoyancy
