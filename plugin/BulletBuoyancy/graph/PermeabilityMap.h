#pragma once
/// @file PermeabilityMap.h
/// The permeability of every surface sample of one body, editable at run time ("set from code at
/// run time, e.g. a hit opens a hole"). It holds one open-area fraction per sample (0 sealed … 1 open) and the
/// node each sample feeds; permeableSamples() gives the compact list btFloodingAction uses
/// (btFloodingAction::setPermeability). Every edit validates all its input first and changes nothing when
/// any of it is bad (no half-applied hole).

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/graph/PermeabilityTexture.h>
#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/graph/WaterIngress.h>

#include <Eigen/Core>
#include <vector>

namespace buoyancy {

/// How a painted sphere combines with what is there.
enum class PermeabilityPaint {
    Max, ///< value = max(old, new): overlapping holes take the largest value (the scene rule)
    Set, ///< value = new inside the sphere (e.g. 0 closes a hole again)
};

/// Per-sample permeability of one body.
class PermeabilityMap {
public:
    /// All samples sealed (0), each feeding its nearest node.
    /// @param samples  the body's surface samples (btBuoyancyShape::getDragSamples()), body frame; copied
    /// @param graph    the body's water graph (node positions, body frame)
    /// @throws std::invalid_argument for an invalid graph
    PermeabilityMap(const SurfaceSamples& samples, const WaterGraph& graph);

    /// Number of samples.
    std::size_t size() const { return m_value.size(); }
    /// Open-area fraction of sample i, in [0, 1].
    double value(std::size_t i) const { return m_value[i]; }
    /// Every sample's value.
    const std::vector<double>& values() const { return m_value; }
    /// Node sample i feeds.
    int node(std::size_t i) const { return m_node[i]; }

    /// Set one sample. @throws std::invalid_argument for an index out of range or a value outside [0, 1] / NaN
    void setValue(std::size_t i, double value);
    /// Set every sample at once (#samples values in [0, 1]). @throws std::invalid_argument (map unchanged)
    void setValues(const std::vector<double>& values);
    /// Paint the samples within a sphere (body frame). `node` ≥ 0 sends their water to that node (−1: keep
    /// each sample's node). @return number of samples inside the sphere
    /// @throws std::invalid_argument for a non-finite centre, radius ≤ 0 / non-finite, value outside [0, 1],
    ///         or a node out of range (map unchanged)
    std::size_t paintSphere(const Eigen::Vector3d& centre, double radius, double value,
                            PermeabilityPaint mode = PermeabilityPaint::Max, int node = -1);
    /// Paint from an image looked up at each sample's UV (#samples UVs, surfaceSampleUvs).
    /// @throws std::invalid_argument for a size mismatch or an empty image (map unchanged)
    void paintImage(const PermeabilityImage& image, const std::vector<Eigen::Vector2d>& sampleUvs,
                    PermeabilityPaint mode = PermeabilityPaint::Set, TextureFilter filter = TextureFilter::Bilinear);

    /// The permeable samples (value > 0 only; open area = value × sample area).
    PermeableSamples permeableSamples() const;

private:
    SurfaceSamples m_samples;
    WaterGraph m_graph;
    std::vector<double> m_value;
    std::vector<int> m_node;
};

}  // namespace buoyancy
