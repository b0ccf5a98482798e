/// @file AtlasGenerator.cpp
/// generateAtlas (declared in UvLayout.h), DESIGN-NOTES 1.2: charts grown from neighbouring triangles
/// whose normals stay within a cone around the seed's normal, flattened by orthogonal projection onto the
/// plane normal to that axis (no fold-over: every projected triangle keeps a positive area), verified
/// free of overlap (split with a narrower cone otherwise), scaled to equal texel density (chart UV area
/// proportional to its 3D area), and shelf-packed with a one-texel gap at the largest scale that fits.

#include "atlas/MeshAdjacency.h"
#include "atlas/UvLayout.h"
#include "atlas/UvTriangleOverlap.h"
#include "bake/PolygonClip.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInitialConeDeg = 45.0; ///< half-angle of the normal cone a chart may span
constexpr double kSmallestConeDeg = 1.0; ///< below this a chart that still overlaps becomes single triangles

/// One flattened chart: its triangles and their corner coordinates in metres (3 per triangle), with the
/// bounding box starting at the origin.
struct Chart {
    std::vector<std::uint32_t> tris;
    std::vector<Eigen::Vector2d> corners;
    Eigen::Vector2d size = Eigen::Vector2d::Zero(); ///< bounding-box width, height, m
};

struct MeshFacts {
    std::vector<Eigen::Vector3d> normal; ///< unit normals (zero for degenerate triangles)
    std::vector<double> area;            ///< m²
    std::vector<char> degenerate;
};

/// Flatten `tris` along `axis`: orthogonal projection, rotation to the principal axes of the corners
/// (long side along u), uniform scale so the flat area equals the 3D area.
Chart flattenChart(const TriangleMesh& mesh, const MeshFacts& facts, std::vector<std::uint32_t> tris,
                   const Eigen::Vector3d& axis) {
    Chart c;
    c.tris = std::move(tris);
    const Eigen::Vector3d helper = std::abs(axis.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d u = axis.cross(helper).normalized();
    const Eigen::Vector3d v = axis.cross(u);  // (u, v, axis) right-handed: CCW triangles stay CCW
    c.corners.resize(3 * c.tris.size());
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < c.tris.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d& p = mesh.corner(c.tris[i], k);
            c.corners[3 * i + k] = Eigen::Vector2d(p.dot(u), p.dot(v));
            mean += c.corners[3 * i + k];
        }
    mean /= static_cast<double>(c.corners.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (Eigen::Vector2d& q : c.corners) {
        q -= mean;
        cov += q * q.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    Eigen::Vector2d major = eig.eigenvectors().col(1);
    if (!major.allFinite() || major.norm() == 0) major = Eigen::Vector2d::UnitX();
    major.normalize();
    Eigen::Matrix2d R;  // rotation taking `major` to +u (det +1 keeps the winding)
    R << major.x(), major.y(), -major.y(), major.x();
    double flatArea = 0, area3 = 0;
    for (std::size_t i = 0; i < c.tris.size(); ++i) {
        for (int k = 0; k < 3; ++k) c.corners[3 * i + k] = R * c.corners[3 * i + k];
        flatArea += 0.5 * cross2(c.corners[3 * i], c.corners[3 * i + 1], c.corners[3 * i + 2]);
        area3 += facts.area[c.tris[i]];
    }
    const double scale = flatArea > 0 && area3 > 0 ? std::sqrt(area3 / flatArea) : 1.0;
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (Eigen::Vector2d& q : c.corners) {
        q *= scale;
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    for (Eigen::Vector2d& q : c.corners) q -= lo;
    c.size = hi - lo;
    return c;
}

/// True when no two triangles of the flat chart overlap and none is flipped.
bool chartIsValid(const Chart& c, const MeshFacts& facts) {
    std::vector<char> active(c.tris.size());
    for (std::size_t i = 0; i < c.tris.size(); ++i) {
        active[i] = !facts.degenerate[c.tris[i]];
        if (active[i] && !(cross2(c.corners[3 * i], c.corners[3 * i + 1], c.corners[3 * i + 2]) > 0)) return false;
    }
    if (c.tris.size() < 3) return true;  // two non-flipped triangles sharing an edge cannot overlap
    const std::vector<char> overlap = findOverlappingUvTriangles(c.corners, active);
    return std::find(overlap.begin(), overlap.end(), 1) == overlap.end();
}

/// Grow charts over `subset` by breadth-first region growing: a neighbour joins when its normal is within
/// the cone (cosLimit) around the seed's normal; degenerate triangles join any neighbouring chart.
void growCharts(const TriangleMesh& mesh, const MeshFacts& facts, const TriangleAdjacency& adj,
                const std::vector<std::uint32_t>& subset, double coneDeg, std::vector<int>& workOf, int workId,
                std::vector<char>& taken, std::vector<Chart>& done,
                std::vector<std::pair<std::vector<std::uint32_t>, double>>& todo) {
    const double cosLimit = std::cos(coneDeg * kPi / 180.0);
    std::vector<std::uint32_t> queue;
    for (int pass = 0; pass < 2; ++pass) {  // non-degenerate seeds first, then leftover degenerate ones
        for (std::uint32_t seed : subset) {
            if (taken[seed] || (pass == 0 && facts.degenerate[seed])) continue;
            const Eigen::Vector3d axis = facts.degenerate[seed] ? Eigen::Vector3d::UnitZ() : facts.normal[seed];
            std::vector<std::uint32_t> tris;
            queue.assign(1, seed);
            taken[seed] = 1;
            for (std::size_t qi = 0; qi < queue.size(); ++qi) {
                const std::uint32_t t = queue[qi];
                tris.push_back(t);
                for (std::uint32_t i = adj.start[t]; i < adj.start[t + 1]; ++i) {
                    const std::uint32_t n = adj.neighbours[i];
                    if (taken[n] || workOf[n] != workId) continue;
                    if (!facts.degenerate[n] && facts.normal[n].dot(axis) < cosLimit) continue;
                    taken[n] = 1;
                    queue.push_back(n);
                }
            }
            Chart c = flattenChart(mesh, facts, tris, axis);
            if (tris.size() == 1 || chartIsValid(c, facts)) {
                done.push_back(std::move(c));
            } else if (coneDeg * 0.5 < kSmallestConeDeg) {
                for (std::uint32_t t : tris) {
                    const Eigen::Vector3d a = facts.degenerate[t] ? Eigen::Vector3d::UnitZ() : facts.normal[t];
                    done.push_back(flattenChart(mesh, facts, {t}, a));
                }
            } else {
                todo.emplace_back(std::move(tris), coneDeg * 0.5);
            }
        }
    }
}

/// Texel cells a chart occupies at `scale` texels per metre: its bounding box rounded up (at least 1).
inline int cellsFor(double metres, double scale) {
    return std::max(1, static_cast<int>(std::ceil(metres * scale * (1 + 1e-12) + 1e-9)));
}

/// Shelf packing (charts sorted by decreasing height) with one empty texel between charts. Writes the
/// lower-left cell of each chart into `at` when it fits.
bool shelfPack(const std::vector<Chart>& charts, const std::vector<std::uint32_t>& order, double scale, int N,
               std::vector<Eigen::Vector2i>* at) {
    long x = 0, y = 0, shelf = 0;
    for (std::uint32_t c : order) {
        const int w = cellsFor(charts[c].size.x(), scale), h = cellsFor(charts[c].size.y(), scale);
        if (w > N || h > N) return false;
        if (x + w > N) {
            y += shelf + 1;
            x = 0;
            shelf = 0;
        }
        if (y + h > N) return false;
        if (at) (*at)[c] = Eigen::Vector2i(static_cast<int>(x), static_cast<int>(y));
        x += w + 1;
        shelf = std::max<long>(shelf, h);
    }
    return true;
}

}  // namespace

std::vector<Eigen::Vector2d> generateAtlas(const TriangleMesh& mesh, int textureSize) {
    const int N = textureSize;
    if (N < 1 || N > 16384)
        throw std::invalid_argument("generateAtlas: texture size " + std::to_string(N) + " is outside 1..16384");
    const std::size_t T = mesh.triangles.size();
    std::vector<Eigen::Vector2d> uvs(3 * T, Eigen::Vector2d::Zero());
    if (T == 0) return uvs;

    MeshFacts facts;
    facts.normal.resize(T);
    facts.area.resize(T);
    facts.degenerate.resize(T);
    double maxArea = 0;
    for (std::size_t t = 0; t < T; ++t) {
        for (int k = 0; k < 3; ++k) {
            const int vi = mesh.triangles[t][k];
            if (vi < 0 || static_cast<std::size_t>(vi) >= mesh.vertices.size())
                throw std::invalid_argument("generateAtlas: triangle " + std::to_string(t) + " has a vertex index out of range");
            if (!mesh.vertices[vi].allFinite())
                throw std::invalid_argument("generateAtlas: vertex " + std::to_string(vi) + " is not finite");
        }
        const Eigen::Vector3d n = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
        facts.area[t] = 0.5 * n.norm();
        facts.normal[t] = facts.area[t] > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
        maxArea = std::max(maxArea, facts.area[t]);
    }
    double totalArea = 0;
    for (std::size_t t = 0; t < T; ++t) {
        facts.degenerate[t] = !(facts.area[t] > 1e-14 * maxArea) || !facts.normal[t].allFinite();
        totalArea += facts.area[t];
    }

    // Charts: region growing, then splitting of any chart whose flat form overlaps itself.
    const TriangleAdjacency adj = buildTriangleAdjacency(mesh, {});
    std::vector<Chart> charts;
    std::vector<std::pair<std::vector<std::uint32_t>, double>> todo;
    std::vector<std::uint32_t> all(T);
    std::iota(all.begin(), all.end(), 0u);
    todo.emplace_back(std::move(all), kInitialConeDeg);
    std::vector<int> workOf(T, 0);
    std::vector<char> taken(T, 0);
    for (std::size_t w = 0; w < todo.size(); ++w) {
        const std::vector<std::uint32_t> subset = todo[w].first;  // copy: todo may grow
        for (std::uint32_t t : subset) {
            workOf[t] = static_cast<int>(w);
            taken[t] = 0;
        }
        growCharts(mesh, facts, adj, subset, todo[w].second, workOf, static_cast<int>(w), taken, charts, todo);
    }

    // Largest uniform scale (texels per metre) at which the shelf packing fits: bisection in log scale.
    std::vector<std::uint32_t> order(charts.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        if (charts[a].size.y() != charts[b].size.y()) return charts[a].size.y() > charts[b].size.y();
        return charts[a].size.x() > charts[b].size.x();
    });
    const double upper = totalArea > 0 ? N / std::sqrt(totalArea) : 1.0;  // area bound: s²·ΣA ≤ N²
    double lo = upper * 1e-9, hi = upper;
    if (!shelfPack(charts, order, lo, N, nullptr)) {
        // At a vanishing scale each chart takes one texel plus the gap: floor((N+1)/2)² charts fit.
        const long need = 2 * static_cast<long>(std::ceil(std::sqrt(static_cast<double>(charts.size())))) - 1;
        throw std::runtime_error("generateAtlas: " + std::to_string(charts.size()) + " charts (from " +
                                 std::to_string(T) + " triangles) cannot fit in a " + std::to_string(N) + "x" +
                                 std::to_string(N) + " texture with a one-texel gap; the smallest texture that fits is " +
                                 std::to_string(need) + "x" + std::to_string(need) + " (use a larger texture size)");
    }
    if (shelfPack(charts, order, hi, N, nullptr)) {
        lo = hi;
    } else {
        for (int it = 0; it < 60 && hi / lo > 1 + 1e-6; ++it) {
            const double mid = std::sqrt(lo * hi);
            (shelfPack(charts, order, mid, N, nullptr) ? lo : hi) = mid;
        }
    }
    const double scale = lo;
    std::vector<Eigen::Vector2i> at(charts.size());
    shelfPack(charts, order, scale, N, &at);

    // Place each chart centred in its cells, in texel units, then to [0,1].
    for (std::size_t ci = 0; ci < charts.size(); ++ci) {
        const Chart& c = charts[ci];
        const int w = cellsFor(c.size.x(), scale), h = cellsFor(c.size.y(), scale);
        const Eigen::Vector2d offset(at[ci].x() + 0.5 * (w - c.size.x() * scale),
                                     at[ci].y() + 0.5 * (h - c.size.y() * scale));
        for (std::size_t i = 0; i < c.tris.size(); ++i)
            for (int k = 0; k < 3; ++k) {
                Eigen::Vector2d s = (offset + scale * c.corners[3 * i + k]) / static_cast<double>(N);
                uvs[3 * c.tris[i] + k] = s.cwiseMax(0.0).cwiseMin(1.0);
            }
    }
    return uvs;
}

}  // namespace buoyancy
