/// @file CloseHoles.cpp
/// Boundary loops of a triangle mesh and their least-area triangulations (design.md, "Repairing a model").
/// The dynamic programme is the one of polygon triangulation by minimum weight (Klincsek 1980; its use for
/// mesh holes with an area weight: Barequet & Sharir 1995, Liepa 2003): W(i, j) = min over i < m < j of
/// W(i, m) + W(m, j) + area(p_i, p_m, p_j), W(i, i+1) = 0, over the loop's vertices p_0 … p_{n−1}.

#include <BulletBuoyancy/mesh/CloseHoles.h>

#include <BulletBuoyancy/mesh/MeshImport.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>

namespace buoyancy {

namespace {

/// The boundary of the mesh as directed edges a→b (as the triangles traverse them) left unpaired.
std::vector<std::pair<int, int>> boundaryEdges(const TriangleMesh& mesh) {
    // net[(lo, hi)] = (# lo→hi) − (# hi→lo)
    std::map<std::pair<int, int>, int> net;
    for (const Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            net[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
        }
    std::vector<std::pair<int, int>> out;
    for (const auto& [e, n] : net)
        for (int c = 0; c < std::abs(n); ++c) out.push_back(n > 0 ? e : std::make_pair(e.second, e.first));
    return out;
}

/// Boundary loops (vertex sequences in the direction of the mesh's edges), each visiting a vertex once: a walk
/// that comes back to a vertex it passed (two holes touching at a vertex) is split there.
std::vector<std::vector<int>> boundaryLoops(const std::vector<std::pair<int, int>>& edges) {
    std::map<int, std::vector<std::size_t>> outgoing;
    for (std::size_t e = 0; e < edges.size(); ++e) outgoing[edges[e].first].push_back(e);
    std::vector<char> used(edges.size(), 0);
    std::vector<std::vector<int>> loops;
    for (std::size_t e0 = 0; e0 < edges.size(); ++e0) {
        if (used[e0]) continue;
        // Walk until the start vertex comes back. At every vertex as many boundary edges start as end (each
        // triangle is a closed cycle and removing pairs keeps that), so the walk cannot get stuck.
        std::vector<int> walk{edges[e0].first};
        used[e0] = 1;
        int at = edges[e0].second;
        while (at != walk.front()) {
            walk.push_back(at);
            std::size_t next = edges.size();
            for (std::size_t cand : outgoing[at])
                if (!used[cand]) { next = cand; break; }
            if (next == edges.size()) break;  // unreachable for a balanced boundary; stop rather than loop
            used[next] = 1;
            at = edges[next].second;
        }
        // Split at repeated vertices (a stack of the open part; a vertex seen again closes the part above it).
        std::vector<int> stack;
        std::map<int, std::size_t> position;
        for (int v : walk) {
            auto it = position.find(v);
            if (it != position.end()) {
                std::vector<int> loop(stack.begin() + std::ptrdiff_t(it->second), stack.end());
                for (std::size_t k = it->second + 1; k < stack.size(); ++k) position.erase(stack[k]);
                stack.resize(it->second + 1);
                if (loop.size() >= 3) loops.push_back(std::move(loop));
                continue;
            }
            position[v] = stack.size();
            stack.push_back(v);
        }
        if (stack.size() >= 3) loops.push_back(std::move(stack));
    }
    return loops;
}

}  // namespace

HoleClosing closeHoles(TriangleMesh& mesh, std::size_t maxLoopEdges, double minDoubleArea) {
    HoleClosing result;
    const std::vector<std::vector<int>> loops = boundaryLoops(boundaryEdges(mesh));
    if (loops.empty()) return result;
    for (const std::vector<int>& loop : loops)
        if (loop.size() > maxLoopEdges)
            throw MeshError("a hole with " + std::to_string(loop.size()) + " boundary edges is larger than the " +
                            std::to_string(maxLoopEdges) + " that closing supports");
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<double> cost;
    std::vector<std::int32_t> split;
    for (const std::vector<int>& loop : loops) {
        const std::size_t n = loop.size();
        auto p = [&](std::size_t i) -> const Eigen::Vector3d& { return mesh.vertices[std::size_t(loop[i])]; };
        auto doubleArea = [&](std::size_t i, std::size_t m, std::size_t j) {
            return (p(m) - p(i)).cross(p(j) - p(i)).norm();
        };
        cost.assign(n * n, 0.0);
        split.assign(n * n, -1);
        for (std::size_t gap = 2; gap < n; ++gap)
            for (std::size_t i = 0; i + gap < n; ++i) {
                const std::size_t j = i + gap;
                double best = kInf;
                std::int32_t bestM = -1;
                for (std::size_t m = i + 1; m < j; ++m) {
                    const double a2 = doubleArea(i, m, j);
                    if (!(a2 > minDoubleArea)) continue;
                    const double c = cost[i * n + m] + cost[m * n + j] + 0.5 * a2;
                    if (c < best) { best = c; bestM = std::int32_t(m); }
                }
                cost[i * n + j] = best;
                split[i * n + j] = bestM;
            }
        if (!(cost[n - 1] < kInf))
            throw MeshError("a hole with " + std::to_string(n) + " boundary edges encloses no area (its vertices " +
                            "lie on a line: a crack); weld or rebuild it in a modeller");
        // Emit (p_j, p_m, p_i): its edge p_m→p_i pairs with the loop edge p_i→p_m when m = i + 1, its edge
        // p_i→p_j with the parent's p_j→p_i.
        std::vector<std::pair<std::size_t, std::size_t>> todo{{0, n - 1}};
        while (!todo.empty()) {
            const auto [i, j] = todo.back();
            todo.pop_back();
            if (j < i + 2) continue;
            const std::size_t m = std::size_t(split[i * n + j]);
            result.triangles.push_back(mesh.triangles.size());
            result.hole_of_triangle.push_back(result.holes);
            mesh.triangles.emplace_back(loop[j], loop[m], loop[i]);
            result.area_added += 0.5 * doubleArea(i, m, j);
            todo.push_back({i, m});
            todo.push_back({m, j});
        }
        ++result.holes;
        result.boundary_edges += n;
    }
    mesh.corner_uvs.clear();
    return result;
}

}  // namespace buoyancy
