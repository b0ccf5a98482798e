/// @file AtlasGenerator.cpp
/// generateAtlas (declared in UvLayout.h), design.md 1.2: charts grown from neighbouring triangles
/// whose normals stay within a cone around the seed's normal, flattened by orthogonal projection onto the
/// plane normal to that axis (no fold-over: every projected triangle keeps a positive area), verified
/// free of overlap (split with a narrower cone otherwise), scaled to equal texel density (chart UV area
/// proportional to its 3D area), and shelf-packed with a one-texel gap at the largest scale that fits.

#include <BulletBuoyancy/atlas/MeshAdjacency.h>
#include <BulletBuoyancy/atlas/UvLayout.h>
#include <BulletBuoyancy/atlas/UvTriangleOverlap.h>
#include <BulletBuoyancy/geometry/PolygonClip.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Half-angles of the normal cone a chart may span, narrowest first: a narrow cone keeps each texel's
/// pieces nearly coplanar (the volume of a texel holding coplanar pieces is exact, design.md 1.1), a
/// wide one packs denser. The narrowest whose atlas keeps kMinScaleRatio of the widest's scale is used.
constexpr double kConesDeg[] = {45.0, 10.0};  // widest first (its scale bounds the others')
constexpr double kMinScaleRatio = 0.6;   ///< texel size may grow by 1/0.6 to keep charts near-coplanar
constexpr double kChartTurnRad = 0.05;   ///< turn of every chart off its principal axes (anti-aliasing)
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
    // A small turn off the principal axes, so long straight features (a cylinder's generators, a box's
    // edges) do not run along texel rows: a waterline parallel to a texel row puts every straddling sample
    // at the same offset and their all-in/all-out errors add up instead of averaging out (design.md 2.4;
    // measured on a slender cylinder: worst submerged-volume error 0.10 % → 0.065 % at 128²).
    Eigen::Matrix2d turn;
    turn << std::cos(kChartTurnRad), -std::sin(kChartTurnRad), std::sin(kChartTurnRad), std::cos(kChartTurnRad);
    R = turn * R;
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

/// Build the charts of the whole mesh with normal cone `coneDeg`: region growing, then re-growing any chart
/// whose flat form overlaps itself with a halved cone (design.md 1.2).
std::vector<Chart> buildCharts(const TriangleMesh& mesh, const MeshFacts& facts, const TriangleAdjacency& adj,
                               double coneDeg) {
    const std::size_t T = mesh.triangles.size();
    std::vector<Chart> charts;
    std::vector<std::pair<std::vector<std::uint32_t>, double>> todo;
    std::vector<std::uint32_t> all(T);
    std::iota(all.begin(), all.end(), 0u);
    todo.emplace_back(std::move(all), coneDeg);
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
    return charts;
}

/// Recompute a chart's bounding box and move its lower-left corner to the origin.
void rebox(Chart& c) {
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const Eigen::Vector2d& q : c.corners) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    for (Eigen::Vector2d& q : c.corners) q -= lo;
    c.size = hi - lo;
}

/// Split every chart whose longer bounding-box side exceeds `maxSide` (m) into slabs across that side,
/// each slab cut further into its edge-connected pieces (a chart must be connected: the packer keeps a
/// texel of gap only between charts). A piece of a valid flat chart is valid: it is only rescaled.
/// Long charts (e.g. strips along a slender body) otherwise cap the uniform scale at N / their length.
std::vector<Chart> splitLongCharts(std::vector<Chart> charts, const TriangleAdjacency& adj, const MeshFacts& facts,
                                   double maxSide, std::size_t triangleCount) {
    std::vector<Chart> out;
    std::vector<int> pieceKey(triangleCount, -1);   // slab id of a triangle of the chart being split
    std::vector<std::uint32_t> local(triangleCount); // its index inside that chart
    std::vector<char> seen(triangleCount, 0);
    std::vector<std::uint32_t> queue;
    for (Chart& c : charts) {
        const int axis = c.size.x() >= c.size.y() ? 0 : 1;
        const double len = c.size[axis];
        if (!(len > maxSide) || c.tris.size() < 2) {
            out.push_back(std::move(c));
            continue;
        }
        const int slabs = static_cast<int>(std::ceil(len / maxSide));
        for (std::size_t i = 0; i < c.tris.size(); ++i) {
            const double mid = (c.corners[3 * i][axis] + c.corners[3 * i + 1][axis] + c.corners[3 * i + 2][axis]) / 3;
            pieceKey[c.tris[i]] = std::min(slabs - 1, static_cast<int>(mid / len * slabs));
            local[c.tris[i]] = static_cast<std::uint32_t>(i);
        }
        for (std::size_t i = 0; i < c.tris.size(); ++i) {
            const std::uint32_t seed = c.tris[i];
            if (seen[seed]) continue;
            Chart piece;
            queue.assign(1, seed);
            seen[seed] = 1;
            for (std::size_t qi = 0; qi < queue.size(); ++qi) {
                const std::uint32_t t = queue[qi];
                piece.tris.push_back(t);
                for (int k = 0; k < 3; ++k) piece.corners.push_back(c.corners[3 * local[t] + k]);
                for (std::uint32_t j = adj.start[t]; j < adj.start[t + 1]; ++j) {
                    const std::uint32_t n = adj.neighbours[j];
                    if (seen[n] || pieceKey[n] != pieceKey[seed]) continue;
                    seen[n] = 1;
                    queue.push_back(n);
                }
            }
            // Same texel density in every chart: the piece's flat area equals its 3D area again.
            double flatArea = 0, area3 = 0;
            for (std::size_t k = 0; k < piece.tris.size(); ++k) {
                flatArea += 0.5 * cross2(piece.corners[3 * k], piece.corners[3 * k + 1], piece.corners[3 * k + 2]);
                area3 += facts.area[piece.tris[k]];
            }
            const double scale = flatArea > 0 && area3 > 0 ? std::sqrt(area3 / flatArea) : 1.0;
            for (Eigen::Vector2d& q : piece.corners) q *= scale;
            rebox(piece);
            out.push_back(std::move(piece));
        }
        for (std::uint32_t t : c.tris) {
            pieceKey[t] = -1;
            seen[t] = 0;
        }
    }
    return out;
}

/// The texels a chart covers at a given scale and orientation, as one run of rows per column (holes inside
/// a column count as covered: conservative). Texel coordinates of a chart point p (m, chart frame) are
/// at + shift + scale · R·p, with R the identity or the +90° rotation (which keeps the UV winding).
struct Footprint {
    int w = 0, h = 0;               ///< columns and rows spanned
    std::vector<int> bottom, top;   ///< per column: first covered row, one past the last (bottom > top: empty)
    Eigen::Vector2d shift;          ///< texel offset of the chart frame origin relative to the footprint corner
    int rot = 0;                    ///< 0 or 1 (quarter turn)
};

/// Chart point (m) → texel units before the shift, for orientation `rot`.
inline Eigen::Vector2d orient(const Eigen::Vector2d& p, const Eigen::Vector2d& size, int rot, double scale) {
    return rot == 0 ? Eigen::Vector2d(scale * p.x(), scale * p.y())
                    : Eigen::Vector2d(scale * (size.y() - p.y()), scale * p.x());
}

/// Compute the footprint of `c` at `scale` texels per metre (the chart centred in the cells of its box).
void computeFootprint(const Chart& c, double scale, int rot, Footprint& fp) {
    constexpr double eps = 1e-9;  // texels; rounding slack, always widening the footprint
    const Eigen::Vector2d ext = rot == 0 ? Eigen::Vector2d(c.size * scale) : Eigen::Vector2d(c.size.y(), c.size.x()) * scale;
    const Eigen::Vector2d centring(0.5 * (std::ceil(ext.x()) - ext.x()), 0.5 * (std::ceil(ext.y()) - ext.y()));
    const int cols = static_cast<int>(std::ceil(ext.x() + 2 * eps)) + 2;
    fp.rot = rot;
    fp.bottom.assign(cols, std::numeric_limits<int>::max());
    fp.top.assign(cols, std::numeric_limits<int>::min());
    const int colBase = -1;  // column index of fp.bottom[0] (eps may reach one column left of 0)
    for (std::size_t i = 0; i < c.tris.size(); ++i) {
        Eigen::Vector2d v[3];
        for (int k = 0; k < 3; ++k) v[k] = orient(c.corners[3 * i + k], c.size, rot, scale) + centring;
        const double xmin = std::min({v[0].x(), v[1].x(), v[2].x()}), xmax = std::max({v[0].x(), v[1].x(), v[2].x()});
        const int c0 = static_cast<int>(std::floor(xmin - eps)), c1 = static_cast<int>(std::ceil(xmax + eps)) - 1;
        for (int col = c0; col <= c1; ++col) {
            // y-extent of the triangle inside the strip [col, col + 1] (widened by eps): its boundary clipped.
            const double xl = col - eps, xr = col + 1 + eps;
            double ylo = INFINITY, yhi = -INFINITY;
            for (int k = 0; k < 3; ++k) {
                const Eigen::Vector2d &a = v[k], &b = v[(k + 1) % 3];
                const double ex0 = std::min(a.x(), b.x()), ex1 = std::max(a.x(), b.x());
                if (ex1 < xl || ex0 > xr) continue;
                if (ex1 - ex0 <= 0) {
                    ylo = std::min({ylo, a.y(), b.y()});
                    yhi = std::max({yhi, a.y(), b.y()});
                    continue;
                }
                for (double x : {std::max(ex0, xl), std::min(ex1, xr)}) {
                    const double y = a.y() + (b.y() - a.y()) * ((x - a.x()) / (b.x() - a.x()));
                    ylo = std::min(ylo, y);
                    yhi = std::max(yhi, y);
                }
            }
            if (!(ylo <= yhi)) continue;
            const int slot = std::max(0, std::min(cols - 1, col - colBase));
            fp.bottom[slot] = std::min(fp.bottom[slot], static_cast<int>(std::floor(ylo - eps)));
            fp.top[slot] = std::max(fp.top[slot], static_cast<int>(std::ceil(yhi + eps)));
        }
    }
    // Trim empty columns at both ends and move the footprint's corner to (0, 0).
    int first = 0, last = cols - 1;
    while (first < cols && fp.bottom[first] > fp.top[first]) ++first;
    while (last > first && fp.bottom[last] > fp.top[last]) --last;
    int rowMin = std::numeric_limits<int>::max(), rowMax = std::numeric_limits<int>::min();
    for (int k = first; k <= last; ++k)
        if (fp.bottom[k] <= fp.top[k]) {
            rowMin = std::min(rowMin, fp.bottom[k]);
            rowMax = std::max(rowMax, fp.top[k]);
        }
    fp.w = last - first + 1;
    fp.h = rowMax - rowMin;
    fp.bottom.erase(fp.bottom.begin() + last + 1, fp.bottom.end());
    fp.bottom.erase(fp.bottom.begin(), fp.bottom.begin() + first);
    fp.top.erase(fp.top.begin() + last + 1, fp.top.end());
    fp.top.erase(fp.top.begin(), fp.top.begin() + first);
    for (int k = 0; k < fp.w; ++k)
        if (fp.bottom[k] <= fp.top[k]) {
            fp.bottom[k] -= rowMin;
            fp.top[k] -= rowMin;
        }
    fp.shift = centring - Eigen::Vector2d(first + colBase, rowMin);
}

/// Where a chart went: lower-left texel of its footprint and its orientation.
struct Placement {
    int x = 0, y = 0, rot = 0;
    Eigen::Vector2d shift = Eigen::Vector2d::Zero();
};

/// Skyline packing with chart profiles ("Tetris" packing): the atlas keeps, per column, the first row above
/// everything placed; each chart, in both orientations, drops at every column to where its per-column
/// bottom rests one empty texel above the skyline of its own and its neighbouring columns (so texels of
/// different charts are never 8-neighbours), and the placement with the lowest resulting top is kept.
bool skylinePack(const std::vector<Chart>& charts, const std::vector<std::uint32_t>& order, double scale, int N,
                 bool allowRotation, std::vector<Placement>* at) {
    constexpr int kEmpty = std::numeric_limits<int>::max() / 4;
    std::vector<int> sky(N, 0), dilated;
    Footprint fp[2];
    for (std::uint32_t ci : order) {
        int bestScore = std::numeric_limits<int>::max(), bestX = -1, bestY = 0, bestRot = 0;
        for (int rot = 0; rot < (allowRotation ? 2 : 1); ++rot) {
            Footprint& f = fp[rot];
            computeFootprint(charts[ci], scale, rot, f);
            if (f.w > N || f.h > N) continue;
            // Lowest row allowed for the footprint corner from column j of the dilated footprint (j = 0 is
            // the column left of the chart): one free row below the chart's texels in columns j−1..j+1.
            dilated.assign(f.w + 2, kEmpty);
            for (int k = 0; k < f.w; ++k) {
                if (f.bottom[k] > f.top[k]) continue;
                for (int j = k; j <= k + 2; ++j) dilated[j] = std::min(dilated[j], f.bottom[k] - 1);
            }
            for (int x = 0; x + f.w <= N; ++x) {
                int y = 0;
                for (int j = 0; j < f.w + 2; ++j) {
                    const int col = x - 1 + j;
                    if (col < 0 || col >= N || dilated[j] == kEmpty) continue;
                    y = std::max(y, sky[col] - dilated[j]);
                    if (y + f.h >= bestScore) break;
                }
                if (y + f.h < bestScore && y + f.h <= N) {
                    bestScore = y + f.h;
                    bestX = x;
                    bestY = y;
                    bestRot = rot;
                }
            }
        }
        if (bestX < 0) return false;
        const Footprint& f = fp[bestRot];
        for (int k = 0; k < f.w; ++k)
            if (f.bottom[k] <= f.top[k]) sky[bestX + k] = std::max(sky[bestX + k], bestY + f.top[k]);
        if (at) (*at)[ci] = Placement{bestX, bestY, bestRot, f.shift};
    }
    return true;
}

/// A packed atlas candidate: its charts, their order and places, and the scale (texels per metre).
struct Packing {
    std::vector<Chart> charts;
    std::vector<Placement> at;
    double scale = 0;
};

/// Largest uniform scale (texels per metre) at which the skyline packing of `charts` fits, by bisection in
/// log scale between a vanishing scale and the area bound s²·ΣA ≤ N². Returns false when even one texel per
/// chart does not fit.
bool packAtLargestScale(Packing& p, int N, double totalArea, bool allowRotation, double floorScale = 0) {
    const std::vector<Chart>& charts = p.charts;
    std::vector<std::uint32_t> order(charts.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        const double ha = std::max(charts[a].size.x(), charts[a].size.y());
        const double hb = std::max(charts[b].size.x(), charts[b].size.y());
        if (ha != hb) return ha > hb;
        return a < b;
    });
    const double upper = totalArea > 0 ? N / std::sqrt(totalArea) : 1.0;
    double lo = floorScale > 0 ? floorScale : upper * 1e-9, hi = upper;
    if (!skylinePack(charts, order, lo, N, allowRotation, nullptr)) return false;
    if (skylinePack(charts, order, hi, N, allowRotation, nullptr)) {
        lo = hi;
    } else {
        // Most atlases land between 30 % and 100 % of the area bound: probe there first.
        const double guess = std::max(upper * 0.5, std::sqrt(lo * hi));
        if (guess < hi) (skylinePack(charts, order, guess, N, allowRotation, nullptr) ? lo : hi) = guess;
        for (int it = 0; it < 60 && hi / lo > 1 + 1e-2; ++it) {
            const double mid = std::sqrt(lo * hi);
            (skylinePack(charts, order, mid, N, allowRotation, nullptr) ? lo : hi) = mid;
        }
    }
    p.scale = lo;
    p.at.assign(charts.size(), Placement{});
    skylinePack(charts, order, lo, N, allowRotation, &p.at);
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

    const TriangleAdjacency adj = buildTriangleAdjacency(mesh, {});
    // One packing per cone (long charts split when they cap the scale); keep the narrowest cone whose
    // scale is at least kMinScaleRatio of the best one.
    std::vector<Packing> candidates;
    std::size_t fewestCharts = 0;
    for (double cone : kConesDeg) {
        Packing p;
        // Charts much longer than the atlas is wide in metres cap the scale: split them up front.
        p.charts = splitLongCharts(buildCharts(mesh, facts, adj, cone), adj, facts, 0.5 * std::sqrt(totalArea), T);
        if (fewestCharts == 0 || p.charts.size() < fewestCharts) fewestCharts = p.charts.size();
        // A narrower cone only matters when it reaches kMinScaleRatio of the widest cone's scale.
        const double floorScale = candidates.empty() ? 0.0 : kMinScaleRatio * candidates.front().scale;
        if (!packAtLargestScale(p, N, totalArea, true, floorScale)) continue;
        // Charts whose length caps the scale (slender bodies): split them across their length and keep the
        // split when the atlas gets denser.
        double longest = 0;
        for (const Chart& c : p.charts) longest = std::max(longest, c.size.maxCoeff());
        if (longest * p.scale >= 0.3 * N) {
            for (double part : {0.5, 0.25, 0.125}) {
                Packing trial;
                trial.charts = splitLongCharts(p.charts, adj, facts, part * longest, T);
                if (packAtLargestScale(trial, N, totalArea, true) && trial.scale > p.scale) p = std::move(trial);
            }
        }
        candidates.push_back(std::move(p));
    }
    if (candidates.empty()) {
        // At a vanishing scale each chart takes one texel plus the gap: floor((N+1)/2)² charts fit.
        const long need = 2 * static_cast<long>(std::ceil(std::sqrt(static_cast<double>(fewestCharts)))) - 1;
        throw std::runtime_error("generateAtlas: " + std::to_string(fewestCharts) + " charts (from " +
                                 std::to_string(T) + " triangles) cannot fit in a " + std::to_string(N) + "x" +
                                 std::to_string(N) + " texture with a one-texel gap; the smallest texture that fits is " +
                                 std::to_string(need) + "x" + std::to_string(need) + " (use a larger texture size)");
    }
    double bestScale = 0;
    for (const Packing& p : candidates) bestScale = std::max(bestScale, p.scale);
    std::size_t pick = candidates.size() - 1;  // narrowest cone that packed
    while (candidates[pick].scale < kMinScaleRatio * bestScale) --pick;
    const Packing& best = candidates[pick];

    // Texel coordinates → [0,1].
    const double scale = best.scale;
    for (std::size_t ci = 0; ci < best.charts.size(); ++ci) {
        const Chart& c = best.charts[ci];
        const Placement& p = best.at[ci];
        const Eigen::Vector2d origin = Eigen::Vector2d(p.x, p.y) + p.shift;
        for (std::size_t i = 0; i < c.tris.size(); ++i)
            for (int k = 0; k < 3; ++k) {
                const Eigen::Vector2d s = (origin + orient(c.corners[3 * i + k], c.size, p.rot, scale)) / static_cast<double>(N);
                uvs[3 * c.tris[i] + k] = s.cwiseMax(0.0).cwiseMin(1.0);
            }
    }
    return uvs;
}

}  // namespace buoyancy
