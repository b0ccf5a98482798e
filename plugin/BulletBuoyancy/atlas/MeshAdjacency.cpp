#include <BulletBuoyancy/atlas/MeshAdjacency.h>

#include <algorithm>
#include <numeric>

namespace buoyancy {

TriangleAdjacency buildTriangleAdjacency(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs,
                                         double uvTolerance) {
    const std::size_t T = mesh.triangles.size();
    struct EdgeRef {
        std::uint64_t key;
        std::uint32_t tri;
        std::uint8_t corner;  // edge from corner k to corner k+1
    };
    std::vector<EdgeRef> edges;
    edges.reserve(3 * T);
    for (std::size_t t = 0; t < T; ++t) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
            if (a == b) continue;
            const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
            edges.push_back({key, static_cast<std::uint32_t>(t), static_cast<std::uint8_t>(k)});
        }
    }
    std::sort(edges.begin(), edges.end(), [](const EdgeRef& x, const EdgeRef& y) {
        return x.key != y.key ? x.key < y.key : x.tri < y.tri;
    });
    const bool withUv = cornerUvs.size() == 3 * T;
    // UV of vertex v inside triangle t.
    auto uvAt = [&](std::uint32_t t, int v) -> const Eigen::Vector2d& {
        for (int k = 0; k < 3; ++k)
            if (mesh.triangles[t][k] == v) return cornerUvs[3 * t + k];
        return cornerUvs[3 * t];
    };
    struct Link {
        std::uint32_t a, b;
        char uv;
    };
    std::vector<Link> links;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j].key == edges[i].key) ++j;
        for (std::size_t p = i; p < j; ++p) {
            for (std::size_t q = p + 1; q < j; ++q) {
                const std::uint32_t ta = edges[p].tri, tb = edges[q].tri;
                if (ta == tb) continue;
                char uv = 0;
                if (withUv) {
                    const int v0 = static_cast<int>(edges[p].key >> 32), v1 = static_cast<int>(edges[p].key & 0xffffffffu);
                    uv = (uvAt(ta, v0) - uvAt(tb, v0)).lpNorm<Eigen::Infinity>() <= uvTolerance &&
                         (uvAt(ta, v1) - uvAt(tb, v1)).lpNorm<Eigen::Infinity>() <= uvTolerance;
                }
                links.push_back({ta, tb, uv});
            }
        }
        i = j;
    }
    TriangleAdjacency adj;
    adj.start.assign(T + 1, 0);
    for (const Link& l : links) {
        ++adj.start[l.a + 1];
        ++adj.start[l.b + 1];
    }
    for (std::size_t t = 0; t < T; ++t) adj.start[t + 1] += adj.start[t];
    adj.neighbours.resize(adj.start[T]);
    adj.uvContinuous.resize(adj.start[T]);
    std::vector<std::uint32_t> fill(adj.start.begin(), adj.start.end() - 1);
    for (const Link& l : links) {
        adj.neighbours[fill[l.a]] = l.b;
        adj.uvContinuous[fill[l.a]++] = l.uv;
        adj.neighbours[fill[l.b]] = l.a;
        adj.uvContinuous[fill[l.b]++] = l.uv;
    }
    return adj;
}

std::vector<int> labelUvCharts(const TriangleAdjacency& adjacency, const std::vector<char>& active, int& chartCount) {
    const std::size_t T = active.size();
    std::vector<int> chart(T, -1);
    std::vector<std::uint32_t> stack;
    chartCount = 0;
    for (std::size_t seed = 0; seed < T; ++seed) {
        if (!active[seed] || chart[seed] >= 0) continue;
        chart[seed] = chartCount;
        stack.assign(1, static_cast<std::uint32_t>(seed));
        while (!stack.empty()) {
            const std::uint32_t t = stack.back();
            stack.pop_back();
            for (std::uint32_t i = adjacency.start[t]; i < adjacency.start[t + 1]; ++i) {
                const std::uint32_t n = adjacency.neighbours[i];
                if (adjacency.uvContinuous[i] && active[n] && chart[n] < 0) {
                    chart[n] = chartCount;
                    stack.push_back(n);
                }
            }
        }
        ++chartCount;
    }
    return chart;
}

}  // namespace buoyancy
