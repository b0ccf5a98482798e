#include <BulletBuoyancy/graph/WaterIngress.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace buoyancy {

double PermeableSamples::totalOpenArea() const {
    double s = 0;
    for (double a : openArea) s += a;
    return s;
}

int nearestWaterNode(const WaterGraph& graph, const Eigen::Vector3d& p) {
    int best = -1;
    double bestD = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < graph.nodes.size(); ++i) {
        const double d = (graph.nodes[i].position - p).squaredNorm();
        if (d < bestD) {
            bestD = d;
            best = int(i);
        }
    }
    return best;
}

namespace {

void pushSample(PermeableSamples& out, const SurfaceSamples& s, std::size_t i, double value, int node,
                const WaterGraph& graph) {
    const Eigen::Vector3d p(s.px[i], s.py[i], s.pz[i]);
    const double area = i < s.area.size() ? s.area[i] : Eigen::Vector3d(s.ax[i], s.ay[i], s.az[i]).norm();
    out.px.push_back(p.x());
    out.py.push_back(p.y());
    out.pz.push_back(p.z());
    out.openArea.push_back(value * area);
    out.node.push_back(node >= 0 ? node : nearestWaterNode(graph, p));
}

}  // namespace

PermeableSamples permeableSamplesFromRegions(const SurfaceSamples& samples, const std::vector<PermeabilityRegion>& regions,
                                             const WaterGraph& graph) {
    for (std::size_t r = 0; r < regions.size(); ++r) {
        const std::string key = "regions[" + std::to_string(r) + "]";
        const PermeabilityRegion& g = regions[r];
        if (!g.centre.allFinite()) throw std::invalid_argument(key + ".centre: must be finite");
        if (!std::isfinite(g.radius) || !(g.radius > 0)) throw std::invalid_argument(key + ".radius: must be > 0");
        if (!std::isfinite(g.value) || g.value < 0 || g.value > 1)
            throw std::invalid_argument(key + ".value: must be in [0, 1]");
        if (g.node >= int(graph.nodes.size())) throw std::invalid_argument(key + ".node: no such node");
    }
    PermeableSamples out;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const Eigen::Vector3d p(samples.px[i], samples.py[i], samples.pz[i]);
        double best = 0;
        int node = -1;
        for (const PermeabilityRegion& g : regions) {
            if ((p - g.centre).squaredNorm() <= g.radius * g.radius && g.value > best) {
                best = g.value;
                node = g.node;
            }
        }
        if (best > 0) pushSample(out, samples, i, best, node, graph);
    }
    return out;
}

PermeableSamples permeableSamplesFromValues(const SurfaceSamples& samples, const std::vector<double>& values,
                                            const std::vector<int>& nodes, const WaterGraph& graph) {
    if (values.size() != samples.size())
        throw std::invalid_argument("permeability: " + std::to_string(values.size()) + " values for " +
                                    std::to_string(samples.size()) + " samples");
    if (!nodes.empty() && nodes.size() != samples.size())
        throw std::invalid_argument("permeability: node list size differs from the sample count");
    PermeableSamples out;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const double v = values[i];
        if (!std::isfinite(v) || v < 0 || v > 1)
            throw std::invalid_argument("permeability[" + std::to_string(i) + "]: must be in [0, 1]");
        const int node = nodes.empty() ? -1 : nodes[i];
        if (node >= int(graph.nodes.size()))
            throw std::invalid_argument("permeability node[" + std::to_string(i) + "]: no such node");
        if (v > 0) pushSample(out, samples, i, v, node, graph);
    }
    return out;
}

void IngressScratch::resize(std::size_t n) {
    inflow.assign(n, 0);
    outflow.assign(n, 0);
    inLimit.assign(n, 0);
    outLimit.assign(n, 0);
}

double applyIngress(WaterGraphState& state, const PermeableSamples& samples, const double* wy, const double* f,
                    double dt, double g, IngressScratch& scratch, double fluidDensity) {
    if (!(dt > 0) || !std::isfinite(dt) || samples.size() == 0) return 0.0;
    const std::size_t nn = state.size();
    if (scratch.inflow.size() != nn) scratch.resize(nn);
    const double inf = std::numeric_limits<double>::infinity();
    std::fill(scratch.inflow.begin(), scratch.inflow.end(), 0.0);
    std::fill(scratch.outflow.begin(), scratch.outflow.end(), 0.0);
    std::fill(scratch.inLimit.begin(), scratch.inLimit.end(), -inf);
    std::fill(scratch.outLimit.begin(), scratch.outLimit.end(), inf);
    const WaterGraph& graph = state.graph();
    const bool paper = graph.ingress == WaterIngressModel::Paper;
    const double cd = graph.dischargeCoefficient;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const int node = samples.node[i];
        if (node < 0 || std::size_t(node) >= nn) continue;
        const double y = wy[i], fi = f[i];
        if (!std::isfinite(y) || !std::isfinite(fi)) continue;
        const double outside = std::max(0.0, fi - y);
        const std::size_t k = std::size_t(node);
        if (paper) {
            // Paper section 4.2: permeability × the water in contact (the column over the sample), per step.
            if (outside > 0) {
                scratch.inflow[k] += samples.openArea[i] * outside;
                scratch.inLimit[k] = std::max(scratch.inLimit[k], fi);
            }
            continue;
        }
        const double inside = std::max(0.0, state.levelHeight(node) - y);
        const double dh = outside - inside;  // design.md 4: outside head minus inside head over the hole
        if (dh == 0 || !(g > 0)) continue;
        const double q = cd * samples.openArea[i] * std::sqrt(2.0 * g * std::abs(dh)) * dt;
        if (dh > 0) {
            scratch.inflow[k] += q;
            scratch.inLimit[k] = std::max(scratch.inLimit[k], fi);
        } else {
            scratch.outflow[k] += q;
            scratch.outLimit[k] = std::min(scratch.outLimit[k], std::max(y, fi));
        }
    }
    double net = 0;
    for (std::size_t k = 0; k < nn; ++k) {
        const double v = scratch.inflow[k] - scratch.outflow[k];
        if (v > 0) {
            const double moved = state.exchange(int(k), v, scratch.inLimit[k]);
            net += moved;
            if (v - moved > 0 && state.isFull(int(k)))
                net += state.pushThrough(int(k), v - moved, scratch.inLimit[k], dt, fluidDensity, g);
        }
        else if (v < 0) net += state.exchange(int(k), v, scratch.outLimit[k]);
    }
    return net;
}

}  // namespace buoyancy
