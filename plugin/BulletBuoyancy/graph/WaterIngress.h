#pragma once
/// @file WaterIngress.h
/// Where and how water enters a body (paper section 4.2, design.md 4): the permeability of each
/// surface sample (the paper's permeability texture; here from painted spherical regions or per-sample
/// values set from code) and the exchange through the permeable samples each substep.
///
/// Orifice model (default): per sample Q = C_d a sqrt(2 g |Δh|) with a = permeability × sample area and
/// Δh = max(0, f − y) − max(0, ℓ_in − y) (outside head over the hole minus the inside water's head over it),
/// signed: water drains out where the inside is higher. The paper's model (option): each substep adds
/// permeability × area × the water column over the sample (a volume per step, so its result depends on
/// the step size — the reason it is not the default).

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/graph/WaterGraphState.h>

#include <Eigen/Core>
#include <vector>

namespace buoyancy {

/// A painted permeable region: samples within the sphere get `value` (overlaps take the largest value).
struct PermeabilityRegion {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(); ///< body (mesh) frame, m
    double radius = 0.1;                              ///< m, > 0
    double value = 1.0;                               ///< open-area fraction in [0, 1]
    int node = -1;                                    ///< node its samples feed; -1: each sample's nearest node
};

/// The permeable samples of one body (only those with permeability > 0: a sealed body has none).
struct PermeableSamples {
    std::vector<double> px, py, pz;  ///< body-frame positions, m
    std::vector<double> openArea;    ///< permeability × sample area, m²
    std::vector<int> node;           ///< node each sample exchanges with
    /// Number of permeable samples.
    std::size_t size() const { return px.size(); }
    /// Σ open area, m².
    double totalOpenArea() const;
};

/// Node nearest to a body-frame point (ties: the lower index).
int nearestWaterNode(const WaterGraph& graph, const Eigen::Vector3d& p);

/// Permeable samples from painted regions. @throws std::invalid_argument naming a bad region
/// (regions[i].radius, .value, .node)
PermeableSamples permeableSamplesFromRegions(const SurfaceSamples& samples, const std::vector<PermeabilityRegion>& regions,
                                             const WaterGraph& graph);

/// Permeable samples from per-sample values (a texture lookup or values set from code).
/// @param values  #samples permeability in [0, 1]
/// @param nodes   #samples node per sample (-1: nearest), or empty (all nearest)
/// @throws std::invalid_argument for sizes or values out of range
PermeableSamples permeableSamplesFromValues(const SurfaceSamples& samples, const std::vector<double>& values,
                                            const std::vector<int>& nodes, const WaterGraph& graph);

/// Scratch of applyIngress (sized once per graph).
struct IngressScratch {
    std::vector<double> inflow, outflow, inLimit, outLimit;
    /// Size for n nodes.
    void resize(std::size_t n);
};

/// Exchange water through the permeable samples for `dt` seconds at the state's current pose.
/// Per node, the summed flow is applied through WaterGraphState::exchange with the level limit that
/// stops it (inflow: the highest outside surface over its inflowing holes; outflow: the lowest of
/// max(hole, outside surface) over its draining holes), so a node's level never overshoots.
/// @param wy  #samples world y of each permeable sample, m
/// @param f   #samples water surface height over each sample, m
/// Inflow into a full node pushes on through the graph (WaterGraphState::pushThrough): a flooded bow
/// compartment passes the sea on to the next one.
/// @param g   gravity, m/s²   @param fluidDensity ρ, kg/m³ (Poiseuille through the pipes)
/// @return net volume that came in (negative when it drained), m³
double applyIngress(WaterGraphState& state, const PermeableSamples& samples, const double* wy, const double* f,
                    double dt, double g, IngressScratch& scratch, double fluidDensity = 1000.0);

}  // namespace buoyancy
