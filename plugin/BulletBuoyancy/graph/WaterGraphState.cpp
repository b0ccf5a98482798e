#include <BulletBuoyancy/graph/WaterGraphState.h>

#include <BulletBuoyancy/graph/MonotoneRoot.h>
#include <BulletBuoyancy/graph/NodeLevel.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Kahan–Babuška (Neumaier) compensated accumulation: sum + c holds the exact running total to rounding.
void neumaier(double& sum, double& c, double x) {
    const double t = sum + x;
    if (std::abs(sum) >= std::abs(x)) c += (sum - t) + x;
    else c += (x - t) + sum;
    sum = t;
}

}  // namespace

WaterGraphState::WaterGraphState(WaterGraph graph) : m_graph(std::move(graph)) {
    m_graph.validate();
    m_search = DischargeSearch(m_graph);
    m_rng = SplitMix64(m_graph.seed);
    const std::size_t n = m_graph.nodes.size();
    m_water.resize(n);
    m_centreY.resize(n);
    m_bottom.resize(n);
    m_level.resize(n);
    m_half.resize(n);
    m_full.resize(n);
    m_order.resize(n);
    m_edgeOrder.resize(m_graph.edges.size());
    for (std::size_t i = 0; i < n; ++i) {
        m_water[i] = m_graph.nodes[i].water;
        m_initial += m_water[i];
    }
    setPose(Eigen::Isometry3d::Identity());
}

double WaterGraphState::totalWater() const {
    double s = 0, c = 0;
    for (double w : m_water) neumaier(s, c, w);
    return s + c;
}

void WaterGraphState::setWater(int i, double volume) {
    if (i < 0 || std::size_t(i) >= m_water.size())
        throw std::invalid_argument("setWater: no node " + std::to_string(i));
    const double cap = m_graph.nodes[std::size_t(i)].capacity;
    if (!std::isfinite(volume) || volume < 0 || volume > cap)
        throw std::invalid_argument("setWater: node \"" + m_graph.nodes[std::size_t(i)].name +
                                    "\": volume must be in [0, capacity]");
    m_initial += volume - m_water[std::size_t(i)];
    m_water[std::size_t(i)] = volume;
    updateLevel(i);
}

void WaterGraphState::setPose(const Eigen::Isometry3d& bodyToWorld) {
    // World up in body axes: Rᵀ (0, 1, 0) = the second row of R.
    const Eigen::Vector3d up = bodyToWorld.linear().row(1).transpose();
    const double norm = up.norm();
    if (std::isfinite(norm) && norm > 0) m_up = up / norm;
    for (std::size_t i = 0; i < m_water.size(); ++i) {
        const WaterNode& node = m_graph.nodes[i];
        m_centreY[i] = (bodyToWorld * node.position).y();
        m_half[i] = nodeHalfHeight(node, m_up);
        m_bottom[i] = m_centreY[i] - m_half[i];
        updateLevel(int(i));
    }
}

void WaterGraphState::updateLevel(int i) {
    const std::size_t k = std::size_t(i);
    const WaterNode& node = m_graph.nodes[k];
    m_full[k] = m_water[k] >= node.capacity ? 1 : 0;
    m_level[k] = m_centreY[k] + nodeLevelForVolume(node, m_up, m_water[k]);
}

Eigen::Vector3d WaterGraphState::waterCentroid(int i) const {
    return nodeWaterCentroid(m_graph.nodes[std::size_t(i)], m_up, m_water[std::size_t(i)]);
}

double WaterGraphState::exchange(int i, double volume, double levelLimit) {
    if (i < 0 || std::size_t(i) >= m_water.size() || !std::isfinite(volume) || volume == 0) return 0.0;
    const std::size_t k = std::size_t(i);
    const WaterNode& node = m_graph.nodes[k];
    const double w = m_water[k];
    double moved = 0;
    if (volume > 0) {
        if (!(levelLimit > m_level[k])) return 0.0;  // already at or above the level that stops inflow
        const double room = std::max(0.0, node.capacity - w);
        const double toLimit = std::max(0.0, nodeVolumeBelow(node, m_up, levelLimit - m_centreY[k]) - w);
        const double x = std::min({volume, room, toLimit});
        if (!(x > 0)) return 0.0;
        const double nw = std::min(w + x, node.capacity);
        moved = nw - w;
        m_water[k] = nw;
        neumaier(m_entered, m_enteredC, moved);
    } else {
        if (!(levelLimit < m_level[k])) return 0.0;
        const double toLimit = std::max(0.0, w - nodeVolumeBelow(node, m_up, levelLimit - m_centreY[k]));
        const double x = std::min({-volume, w, toLimit});
        if (!(x > 0)) return 0.0;
        const double nw = std::max(w - x, 0.0);
        moved = nw - w;  // negative
        m_water[k] = nw;
        neumaier(m_drained, m_drainedC, -moved);
    }
    updateLevel(i);
    return moved;
}

void WaterGraphState::transfer(int from, int to, double volume) {
    const std::size_t s = std::size_t(from), d = std::size_t(to);
    const double cap = m_graph.nodes[d].capacity;
    double x = std::min({volume, m_water[s], cap - m_water[d]});
    if (!(x > 0)) return;
    // Give first (clamped to capacity), then take exactly what was given: nothing created or lost
    // beyond the rounding of one addition.
    const double nd = std::min(m_water[d] + x, cap);
    x = nd - m_water[d];
    m_water[d] = nd;
    m_water[s] = std::max(m_water[s] - x, 0.0);
    updateLevel(from);
    updateLevel(to);
}

double WaterGraphState::equalisingVolume(int from, int to) const {
    // Common level L with V_s(L) + V_d(L) = W_s + W_d (bisection; volumes are monotone in L); the source
    // gives W_s − V_s(L). Moving more would overshoot the level (design.md 4).
    const std::size_t s = std::size_t(from), d = std::size_t(to);
    const WaterNode& ns = m_graph.nodes[s];
    const WaterNode& nd = m_graph.nodes[d];
    const double total = m_water[s] + m_water[d];
    double lo = std::min(m_bottom[s], m_bottom[d]);
    double hi = std::max(m_centreY[s] + m_half[s], m_centreY[d] + m_half[d]);
    auto excess = [&](double L) {
        return nodeVolumeBelow(ns, m_up, L - m_centreY[s]) + nodeVolumeBelow(nd, m_up, L - m_centreY[d]) - total;
    };
    const double L = monotoneRoot(excess, lo, hi, excess(lo), excess(hi), 1e-13 * (hi - lo));
    return std::clamp(m_water[s] - nodeVolumeBelow(ns, m_up, L - m_centreY[s]), 0.0, m_water[s]);
}

double WaterGraphState::pushThrough(int i, double volume, double outsideLevel, double dt, double fluidDensity,
                                    double gravity) {
    if (i < 0 || std::size_t(i) >= m_water.size() || !(volume > 0) || !(dt > 0) || !isFull(i) || !(gravity > 0) ||
        !(fluidDensity > 0) || !std::isfinite(outsideLevel))
        return 0.0;
    const DischargePath p = m_search.find(i, outsideLevel, m_bottom.data(), m_level.data(), m_full.data(), m_rng);
    if (p.node < 0 || !(p.permeability > 0)) return 0.0;
    const double dh = outsideLevel - m_level[std::size_t(p.node)];
    if (!(dh > 0)) return 0.0;
    const double r2 = p.radius * p.radius;
    const double poiseuille = kPi * fluidDensity * gravity * dh * r2 * r2 / (8.0 * m_graph.viscosity * p.length);
    const double orifice = m_graph.dischargeCoefficient * kPi * r2 * std::sqrt(2.0 * gravity * dh);
    const double q = p.permeability * std::min(poiseuille, orifice);
    return exchange(p.node, std::min(volume, q * dt), outsideLevel);
}

DischargePath WaterGraphState::findDischargeNode(int source) {
    return m_search.find(source, m_bottom.data(), m_level.data(), m_full.data(), m_rng);
}

void WaterGraphState::flow(double dt, double fluidDensity, double gravity) {
    if (!(dt > 0) || !std::isfinite(dt) || m_graph.edges.empty()) return;
    if (m_graph.flow == WaterFlowModel::Diffusion) flowDiffusion(dt);
    else flowPoiseuille(dt, fluidDensity, gravity);
}

void WaterGraphState::flowPoiseuille(double dt, double rho, double g) {
    if (!(g > 0) || !(rho > 0)) return;
    // Every node in a seeded random order looks for its discharge node (Algorithm 1) and sends water there.
    for (std::size_t i = 0; i < m_order.size(); ++i) m_order[i] = int(i);
    m_rng.shuffle(m_order.data(), m_order.size());
    const double mu = m_graph.viscosity, cd = m_graph.dischargeCoefficient;
    for (int s : m_order) {
        if (!(m_water[std::size_t(s)] > 0)) continue;
        const DischargePath p = findDischargeNode(s);
        if (p.node < 0 || !(p.permeability > 0)) continue;
        const double dh = m_level[std::size_t(s)] - m_level[std::size_t(p.node)];
        if (!(dh > 0)) continue;
        // Paper eq. 14: Φ = π Δp r⁴ / (8 μ L), Δp = ρ g Δh; laminar only, so capped by the orifice rate
        // C_d π r² sqrt(2 g Δh) of the pipe's cross-section (design.md 4). Both scaled by perm_min.
        const double r2 = p.radius * p.radius;
        const double poiseuille = kPi * rho * g * dh * r2 * r2 / (8.0 * mu * p.length);
        const double orifice = cd * kPi * r2 * std::sqrt(2.0 * g * dh);
        const double q = p.permeability * std::min(poiseuille, orifice);
        const double amount = std::min(q * dt, equalisingVolume(s, p.node));
        transfer(s, p.node, amount);
    }
}

void WaterGraphState::flowDiffusion(double dt) {
    // Fick's law on the fill fraction c = W/C between neighbours: Φ = perm D π r² Δc / L (the paper: "Δp
    // replaced by the difference in concentration"), capped by the volume that equalises the fractions,
    // x = (W_a C_b − W_b C_a)/(C_a + C_b).
    const std::size_t ne = m_edgeOrder.size();
    for (std::size_t i = 0; i < ne; ++i) m_edgeOrder[i] = int(i);
    m_rng.shuffle(m_edgeOrder.data(), ne);
    for (int k : m_edgeOrder) {
        const WaterEdge& e = m_graph.edges[std::size_t(k)];
        if (!(e.permeability > 0)) continue;
        int a = e.from, b = e.to;
        const double ca = m_water[std::size_t(a)] / m_graph.nodes[std::size_t(a)].capacity;
        const double cb = m_water[std::size_t(b)] / m_graph.nodes[std::size_t(b)].capacity;
        if (ca == cb) continue;
        if (ca < cb) std::swap(a, b);
        const double Ca = m_graph.nodes[std::size_t(a)].capacity, Cb = m_graph.nodes[std::size_t(b)].capacity;
        const double Wa = m_water[std::size_t(a)], Wb = m_water[std::size_t(b)];
        const double dc = std::abs(ca - cb);
        const double q = e.permeability * m_graph.diffusivity * kPi * e.radius * e.radius * dc / e.length;
        const double eq = std::max(0.0, (Wa * Cb - Wb * Ca) / (Ca + Cb));
        transfer(a, b, std::min(q * dt, eq));
    }
}

}  // namespace buoyancy

namespace buoyancy {

WaterGraphState::Dynamic WaterGraphState::dynamicState() const {
    Dynamic d;
    d.water = m_water;
    d.centreY = m_centreY;
    d.bottom = m_bottom;
    d.level = m_level;
    d.half = m_half;
    d.full = m_full;
    d.up = m_up;
    d.entered = m_entered;
    d.enteredC = m_enteredC;
    d.drained = m_drained;
    d.drainedC = m_drainedC;
    d.initial = m_initial;
    d.rng = m_rng.state();
    return d;
}

void WaterGraphState::setDynamicState(const Dynamic& d) {
    const std::size_t n = m_water.size();
    for (const std::vector<double>* v : {&d.water, &d.centreY, &d.bottom, &d.level, &d.half})
        if (v->size() != n)
            throw std::invalid_argument("WaterGraphState: a saved array has " + std::to_string(v->size()) +
                                        " entries, the graph has " + std::to_string(n) + " nodes");
    if (d.full.size() != n)
        throw std::invalid_argument("WaterGraphState: the saved full flags have " + std::to_string(d.full.size()) +
                                    " entries, the graph has " + std::to_string(n) + " nodes");
    m_water = d.water;
    m_centreY = d.centreY;
    m_bottom = d.bottom;
    m_level = d.level;
    m_half = d.half;
    m_full = d.full;
    m_up = d.up;
    m_entered = d.entered;
    m_enteredC = d.enteredC;
    m_drained = d.drained;
    m_drainedC = d.drainedC;
    m_initial = d.initial;
    m_rng = SplitMix64(d.rng);
}

}  // namespace buoyancy
