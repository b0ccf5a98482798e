#include <BulletBuoyancy/graph/DischargeSearch.h>

#include <algorithm>
#include <limits>

namespace buoyancy {

DischargeSearch::DischargeSearch(const WaterGraph& graph) : m_edges(graph.edges) {
    const int n = int(graph.nodes.size());
    m_offset.assign(std::size_t(n) + 1, 0);
    for (const WaterEdge& e : graph.edges) {
        ++m_offset[std::size_t(e.from) + 1];
        ++m_offset[std::size_t(e.to) + 1];
    }
    for (int i = 0; i < n; ++i) m_offset[std::size_t(i) + 1] += m_offset[std::size_t(i)];
    m_adj.assign(std::size_t(m_offset[std::size_t(n)]), -1);
    m_other.assign(m_adj.size(), -1);
    std::vector<int> fill(m_offset.begin(), m_offset.end() - 1);
    for (std::size_t k = 0; k < graph.edges.size(); ++k) {
        const WaterEdge& e = graph.edges[k];
        m_adj[std::size_t(fill[std::size_t(e.from)])] = int(k);
        m_other[std::size_t(fill[std::size_t(e.from)]++)] = e.to;
        m_adj[std::size_t(fill[std::size_t(e.to)])] = int(k);
        m_other[std::size_t(fill[std::size_t(e.to)]++)] = e.from;
    }
    m_order.resize(m_adj.size());
    m_visited.assign(std::size_t(n), 0);
}

DischargePath DischargeSearch::find(int source, const double* bottom, const double* level, const unsigned char* full,
                                    SplitMix64& rng) {
    if (source < 0 || std::size_t(source) >= m_visited.size()) return DischargePath();
    return find(source, level[source], bottom, level, full, rng);
}

DischargePath DischargeSearch::find(int source, double sourceLevel, const double* bottom, const double* level,
                                    const unsigned char* full, SplitMix64& rng) {
    DischargePath out;
    if (source < 0 || std::size_t(source) >= m_visited.size()) return out;
    m_sourceLevel = sourceLevel;
    std::fill(m_visited.begin(), m_visited.end(), 0);
    m_source = source;
    visit(source, bottom, level, full, rng, std::numeric_limits<double>::infinity(), 0.0, 1.0, out);
    return out;
}

bool DischargeSearch::visit(int current, const double* bottom, const double* level, const unsigned char* full,
                            SplitMix64& rng, double radius, double length, double perm, DischargePath& out) {
    // Algorithm 1: visited → null; energy barrier → null; a suitable node → it; else recurse.
    if (m_visited[std::size_t(current)]) return false;
    m_visited[std::size_t(current)] = 1;
    if (current != m_source && bottom[current] > m_sourceLevel) return false;  // energy barrier
    if (current != m_source && !full[current] && level[current] < m_sourceLevel) {
        out.node = current;
        out.radius = radius;
        out.length = length;
        out.permeability = perm;
        return true;
    }
    const int b = m_offset[std::size_t(current)], e = m_offset[std::size_t(current) + 1];
    for (int k = b; k < e; ++k) m_order[std::size_t(k)] = k;
    rng.shuffle(m_order.data() + b, std::size_t(e - b));
    for (int k = b; k < e; ++k) {
        const int slot = m_order[std::size_t(k)];
        const WaterEdge& edge = m_edges[std::size_t(m_adj[std::size_t(slot)])];
        if (!(edge.permeability > 0)) continue;  // a closed pipe
        const int next = m_other[std::size_t(slot)];
        if (visit(next, bottom, level, full, rng, std::min(radius, edge.radius), length + edge.length,
                  std::min(perm, edge.permeability), out))
            return true;
    }
    return false;
}

}  // namespace buoyancy
