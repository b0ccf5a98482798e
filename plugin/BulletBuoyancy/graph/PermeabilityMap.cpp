#include <BulletBuoyancy/graph/PermeabilityMap.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

bool validValue(double v) { return std::isfinite(v) && v >= 0 && v <= 1; }

}  // namespace

PermeabilityMap::PermeabilityMap(const SurfaceSamples& samples, const WaterGraph& graph)
    : m_samples(samples), m_graph(graph) {
    m_graph.validate();
    m_value.assign(m_samples.size(), 0.0);
    m_node.resize(m_samples.size());
    for (std::size_t i = 0; i < m_samples.size(); ++i)
        m_node[i] = nearestWaterNode(m_graph, Eigen::Vector3d(m_samples.px[i], m_samples.py[i], m_samples.pz[i]));
}

void PermeabilityMap::setValue(std::size_t i, double value) {
    if (i >= m_value.size())
        throw std::invalid_argument("permeability: sample " + std::to_string(i) + " out of range (" +
                                    std::to_string(m_value.size()) + " samples)");
    if (!validValue(value))
        throw std::invalid_argument("permeability: sample " + std::to_string(i) + ": value must be in [0, 1]");
    m_value[i] = value;
}

void PermeabilityMap::setValues(const std::vector<double>& values) {
    if (values.size() != m_value.size())
        throw std::invalid_argument("permeability: " + std::to_string(values.size()) + " values for " +
                                    std::to_string(m_value.size()) + " samples");
    for (std::size_t i = 0; i < values.size(); ++i)
        if (!validValue(values[i]))
            throw std::invalid_argument("permeability: value " + std::to_string(i) + " must be in [0, 1]");
    m_value = values;
}

std::size_t PermeabilityMap::paintSphere(const Eigen::Vector3d& centre, double radius, double value,
                                         PermeabilityPaint mode, int node) {
    if (!centre.allFinite()) throw std::invalid_argument("permeability sphere: centre must be finite");
    if (!std::isfinite(radius) || !(radius > 0)) throw std::invalid_argument("permeability sphere: radius must be > 0");
    if (!validValue(value)) throw std::invalid_argument("permeability sphere: value must be in [0, 1]");
    if (node < -1 || node >= int(m_graph.nodes.size()))
        throw std::invalid_argument("permeability sphere: node " + std::to_string(node) + " does not exist");
    std::size_t count = 0;
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < m_value.size(); ++i) {
        const Eigen::Vector3d p(m_samples.px[i], m_samples.py[i], m_samples.pz[i]);
        if ((p - centre).squaredNorm() > r2) continue;
        ++count;
        m_value[i] = mode == PermeabilityPaint::Max ? std::max(m_value[i], value) : value;
        if (node >= 0) m_node[i] = node;
    }
    return count;
}

void PermeabilityMap::paintImage(const PermeabilityImage& image, const std::vector<Eigen::Vector2d>& sampleUvs,
                                 PermeabilityPaint mode, TextureFilter filter) {
    if (sampleUvs.size() != m_value.size())
        throw std::invalid_argument("permeability image: " + std::to_string(sampleUvs.size()) + " UVs for " +
                                    std::to_string(m_value.size()) + " samples");
    if (image.width <= 0 || image.height <= 0 || image.value.size() != std::size_t(image.width) * std::size_t(image.height))
        throw std::invalid_argument("permeability image: empty or inconsistent image");
    const std::vector<double> v = permeabilityFromImage(sampleUvs, image, filter);
    for (std::size_t i = 0; i < v.size(); ++i)
        m_value[i] = mode == PermeabilityPaint::Max ? std::max(m_value[i], v[i]) : v[i];
}

PermeableSamples PermeabilityMap::permeableSamples() const {
    return permeableSamplesFromValues(m_samples, m_value, m_node, m_graph);
}

}  // namespace buoyancy
