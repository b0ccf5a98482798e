/// @file MeshRepair.cpp
/// Weld, clean and check an imported triangle soup ("Import"; design.md 6 item 6: bad or
/// degenerate meshes must not turn into overflow or huge forces).
///
/// The rules, all relative to the bounding-box diagonal D of the referenced vertices:
/// - coordinates must be finite, |x| ≤ kMaxCoordinate = 1e6 m and D ≥ kMinDiagonal = 1e-6 m. Inertia
///   grows like ρ L⁵: with L ≤ 1e6 m and any sane density it stays far inside the double range and,
///   more importantly, inside single-precision Bullet's range (≈3e38) for bodies up to ~1e7 m; a larger
///   value is almost always a unit error or garbage (scale the model instead);
/// - vertices closer than kWeldRelative · D = 1e-6 · D are merged (greedy clustering in a hash grid of
///   cell size equal to the tolerance, 27 neighbour cells, O(n));
/// - a triangle with a repeated vertex after welding, or with area ≤ kDegenerateRelative · D² =
///   1e-12 · D² (zero up to rounding), is removed and counted;
/// - closed: every undirected edge is used by exactly two triangles; consistent orientation: those two
///   triangles traverse it in opposite directions;
/// - per connected component (triangles joined by edges), the signed volume Σ a·(b×c)/6 decides the
///   orientation; nesting is decided by the generalized winding number (solid-angle sum, Van Oosterom &
///   Strackee 1983) of a point of the inner component's surface. An inward component inside nothing is
///   flipped with a warning; inward inside outward is a cavity and kept; components that intersect
///   each other (triangle–triangle test with a bounding-volume hierarchy, ComponentIntersections.h) get a
///   warning.

#include <BulletBuoyancy/mesh/MeshRepair.h>

#include <BulletBuoyancy/mesh/BoxTree.h>
#include <BulletBuoyancy/mesh/CloseHoles.h>
#include <BulletBuoyancy/mesh/ComponentIntersections.h>
#include <BulletBuoyancy/mesh/MeshImport.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace buoyancy {

namespace {

constexpr double kMaxCoordinate = 1e6;        ///< m, largest |coordinate| accepted
constexpr double kMinDiagonal = 1e-6;         ///< m, smallest bounding-box diagonal accepted
constexpr double kWeldRelative = 1e-6;        ///< weld tolerance / diagonal
constexpr double kDegenerateRelative = 1e-12; ///< area threshold / diagonal²
constexpr double kFlatRelative = 1e-12;       ///< |component volume| threshold / component diagonal³
constexpr double kPi = 3.14159265358979323846;

/// Hash of an integer cell coordinate (collisions are harmless: positions are compared exactly).
std::uint64_t cellHash(std::int64_t x, std::int64_t y, std::int64_t z) {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h;
}

/// Union–find over triangle indices.
struct DisjointSets {
    std::vector<int> parent;
    explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int i) {
        while (parent[i] != i) { parent[i] = parent[parent[i]]; i = parent[i]; }
        return i;
    }
    void unite(int a, int b) {
        a = find(a); b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

struct Component {
    std::vector<int> tris;
    Eigen::AlignedBox3d box;
    double volume = 0.0;
    int parent = -1;      ///< smallest enclosing component, -1 if none
    int depth = 0;        ///< number of enclosing components
    bool flipped = false;
};

/// Generalized winding number of a closed triangle set about point x (solid angles, Van Oosterom &
/// Strackee 1983): ±1 inside (sign = orientation), 0 outside.
double windingNumber(const TriangleMesh& m, const std::vector<int>& tris, const Eigen::Vector3d& x) {
    double sum = 0.0;
    for (int t : tris) {
        const Eigen::Vector3d a = m.corner(t, 0) - x, b = m.corner(t, 1) - x, c = m.corner(t, 2) - x;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double num = a.dot(b.cross(c));
        const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        sum += 2.0 * std::atan2(num, den);
    }
    return sum / (4.0 * kPi);
}

/// "1 edge" / "3 edges".
std::string count(std::size_t n, const std::string& singular, const std::string& plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

/// Signed volume Σ a·(b×c)/6 about `ref` (for a closed surface, the enclosed volume; for an open one, the volume
/// closed by the cone from `ref`).
double signedVolume(const TriangleMesh& m, const Eigen::Vector3d& ref) {
    double six = 0.0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
        six += (m.corner(t, 0) - ref).dot((m.corner(t, 1) - ref).cross(m.corner(t, 2) - ref));
    return six / 6.0;
}

/// Turn triangle t over (its UVs follow).
void turnOver(TriangleMesh& m, std::size_t t) {
    std::swap(m.triangles[t][1], m.triangles[t][2]);
    if (!m.corner_uvs.empty()) std::swap(m.corner_uvs[3 * t + 1], m.corner_uvs[3 * t + 2]);
}

/// Keep the triangles with keep[t] != 0 (their UVs follow).
void keepTriangles(TriangleMesh& m, const std::vector<char>& keep) {
    std::size_t out = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        if (!keep[t]) continue;
        m.triangles[out] = m.triangles[t];
        if (!m.corner_uvs.empty())
            for (int k = 0; k < 3; ++k) m.corner_uvs[3 * out + k] = m.corner_uvs[3 * t + k];
        ++out;
    }
    m.triangles.resize(out);
    if (!m.corner_uvs.empty()) m.corner_uvs.resize(3 * out);
}

/// Faces given more than once (the same three vertices): one of the majority orientation is kept, none when as
/// many face each way (an inner double wall between two parts, or a two-sided sheet). @return faces removed
std::size_t removeDuplicateFaces(TriangleMesh& m) {
    struct Key { std::array<int, 3> v; bool even; std::size_t tri; };
    std::vector<Key> keys;
    keys.reserve(m.triangles.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        const Eigen::Vector3i& tr = m.triangles[t];
        // Rotate so the smallest index comes first; then the order of the other two gives the orientation.
        int r = 0;
        if (tr[1] < tr[r]) r = 1;
        if (tr[2] < tr[r]) r = 2;
        const int a = tr[r], b = tr[(r + 1) % 3], c = tr[(r + 2) % 3];
        keys.push_back({{a, std::min(b, c), std::max(b, c)}, b < c, t});
    }
    std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) { return x.v != y.v ? x.v < y.v : x.tri < y.tri; });
    std::vector<char> keep(m.triangles.size(), 1);
    std::size_t removed = 0;
    for (std::size_t i = 0; i < keys.size();) {
        std::size_t j = i;
        std::size_t even = 0;
        while (j < keys.size() && keys[j].v == keys[i].v) even += keys[j++].even ? 1 : 0;
        const std::size_t group = j - i, odd = group - even;
        if (group > 1) {
            bool kept = false;  // keep the first face of the majority orientation
            for (std::size_t k = i; k < j; ++k) {
                const bool keepThis = !kept && even != odd && keys[k].even == (even > odd);
                if (keepThis) kept = true;
                else { keep[keys[k].tri] = 0; ++removed; }
            }
        }
        i = j;
    }
    if (removed > 0) keepTriangles(m, keep);
    return removed;
}

/// Turn faces so that every edge shared by exactly two faces is traversed once each way (breadth-first over
/// those edges; per connected part the orientation given to most of its faces is kept).
/// @return faces turned over; @throws MeshError for a part that cannot be oriented (a one-sided surface)
std::size_t orientFaces(TriangleMesh& m) {
    const std::size_t nt = m.triangles.size();
    struct Use { int lo, hi, tri; bool forward; };
    std::vector<Use> uses;
    uses.reserve(3 * nt);
    for (std::size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), int(t), a < b});
        }
    std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
        return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri);
    });
    // Neighbours across two-face edges: (other face, same direction as given?)
    std::vector<std::vector<std::pair<int, bool>>> next(nt);
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
        if (j - i == 2) {
            const bool same = uses[i].forward == uses[i + 1].forward;
            next[std::size_t(uses[i].tri)].push_back({uses[i + 1].tri, same});
            next[std::size_t(uses[i + 1].tri)].push_back({uses[i].tri, same});
        }
        i = j;
    }
    std::vector<signed char> flip(nt, -1);
    std::size_t conflicts = 0, turned = 0;
    std::vector<int> part, queue;
    for (std::size_t seed = 0; seed < nt; ++seed) {
        if (flip[seed] >= 0) continue;
        part.clear();
        queue.assign(1, int(seed));
        flip[seed] = 0;
        while (!queue.empty()) {
            const int f = queue.back();
            queue.pop_back();
            part.push_back(f);
            for (const auto& [g, same] : next[std::size_t(f)]) {
                // f and g must traverse the edge opposite ways: g is turned iff they were given the same way
                // XOR f is turned.
                const auto want = static_cast<signed char>((same ? 1 : 0) ^ flip[std::size_t(f)]);
                if (flip[std::size_t(g)] < 0) { flip[std::size_t(g)] = want; queue.push_back(g); }
                else if (flip[std::size_t(g)] != want) ++conflicts;
            }
        }
        std::size_t flips = 0;
        for (int f : part) flips += std::size_t(flip[std::size_t(f)]);
        const bool invert = 2 * flips > part.size();  // keep the orientation most faces were given
        for (int f : part)
            if ((flip[std::size_t(f)] != 0) != invert) { turnOver(m, std::size_t(f)); ++turned; }
    }
    if (conflicts > 0)
        throw MeshError("cannot be repaired: the surface cannot be oriented consistently (one-sided, like a Moebius "
                        "strip): " + std::to_string(std::max<std::size_t>(1, conflicts / 2)) + " edges disagree whichever way its faces turn");
    return turned;
}

/// Bounding box of the mesh's referenced vertices.
Eigen::AlignedBox3d bboxOf(const TriangleMesh& m) {
    Eigen::AlignedBox3d b;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) b.extend(m.corner(t, k));
    return b;
}

/// The warning that says what the repair did.
std::string repairSummary(const std::string& sourceName, const MeshRepairReport& r) {
    std::string done;
    auto add = [&](const std::string& what) { done += (done.empty() ? "" : ", ") + what; };
    if (r.duplicate_faces_removed > 0) add("removed " + count(r.duplicate_faces_removed, "face", "faces") + " given twice");
    if (r.faces_reoriented > 0) add("turned " + count(r.faces_reoriented, "face", "faces") + " to agree with their neighbours");
    if (r.holes_closed > 0)
        add("closed " + count(r.holes_closed, "hole", "holes") + " (" + count(r.hole_edges, "boundary edge", "boundary edges") +
            ", " + fmt(r.area_added) + " m^2 added)");
    if (r.flat_parts_removed > 0)
        add("removed " + count(r.flat_parts_removed, "flat part", "flat parts") + " enclosing no volume");
    return sourceName + ": repaired: " + done + "; volume " + fmt(r.volume_before) + " m^3 before (" +
           (r.holes_closed > 0 ? "open surface closed through its bounding-box centre" : "as given") + "), " +
           fmt(r.volume_after) + " m^3 after";
}

}  // namespace

MeshReport prepareMesh(TriangleMesh& mesh, const std::string& sourceName, const PrepareMeshOptions& options) {
    auto fail = [&](const std::string& problem) { return MeshError(sourceName + ": " + problem); };
    MeshReport report;
    report.input_triangles = mesh.triangles.size();
    if (mesh.triangles.empty()) throw fail("no triangles");
    const bool uvs = !mesh.corner_uvs.empty();
    if (uvs && mesh.corner_uvs.size() != 3 * mesh.triangles.size())
        throw fail("corner UV count " + std::to_string(mesh.corner_uvs.size()) + " is not 3 x " +
                   std::to_string(mesh.triangles.size()) + " triangles");

    // --- indices, finiteness, magnitude (of referenced vertices only) ---
    const int nv = static_cast<int>(mesh.vertices.size());
    std::vector<char> used(mesh.vertices.size(), 0);
    std::size_t badIndex = 0;
    for (const Eigen::Vector3i& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            if (t[k] < 0 || t[k] >= nv) ++badIndex;
            else used[t[k]] = 1;
        }
    if (badIndex > 0) throw fail("vertex index out of range: " + count(badIndex, "corner", "corners"));
    // Count triangles (not vertices) with a non-finite corner: the same number for a soup and a welded mesh.
    std::size_t nonFinite = 0;
    for (const Eigen::Vector3i& t : mesh.triangles)
        if (!(mesh.vertices[t[0]].allFinite() && mesh.vertices[t[1]].allFinite() && mesh.vertices[t[2]].allFinite()))
            ++nonFinite;
    if (nonFinite > 0)
        throw fail("non-finite coordinates: " + count(nonFinite, "triangle has", "triangles have") + " a NaN or Inf corner");
    double maxAbs = 0.0;
    Eigen::AlignedBox3d box;
    for (int v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        const Eigen::Vector3d& p = mesh.vertices[v];
        maxAbs = std::max(maxAbs, p.cwiseAbs().maxCoeff());
        box.extend(p);
    }
    if (maxAbs > kMaxCoordinate)
        throw fail("coordinates too large: |x| up to " + fmt(maxAbs) + " m exceeds the limit of " +
                   fmt(kMaxCoordinate) + " m (wrong units? use a scale)");
    const double diag = box.diagonal().norm();
    if (!(diag >= kMinDiagonal))
        throw fail("model too small: bounding-box diagonal " + fmt(diag) + " m is below " + fmt(kMinDiagonal) + " m");
    if (uvs)
        for (const Eigen::Vector2d& t : mesh.corner_uvs)
            if (!t.allFinite()) throw fail("non-finite texture coordinates");

    // --- weld: greedy clustering in a hash grid with cell = tolerance ---
    const double tol = kWeldRelative * diag;
    const Eigen::Vector3d origin = box.min();
    std::unordered_map<std::uint64_t, int> head;  // cell -> first representative in its chain
    std::vector<int> chainNext;                   // representative (new index) -> next in same hash bucket
    std::vector<Eigen::Vector3d> reps;
    std::vector<int> remap(mesh.vertices.size(), -1);
    head.reserve(mesh.vertices.size());
    std::size_t referenced = 0;
    for (int v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        ++referenced;
        const Eigen::Vector3d& p = mesh.vertices[v];
        const Eigen::Vector3d q = (p - origin) / tol;
        const std::int64_t cx = static_cast<std::int64_t>(std::floor(q.x()));
        const std::int64_t cy = static_cast<std::int64_t>(std::floor(q.y()));
        const std::int64_t cz = static_cast<std::int64_t>(std::floor(q.z()));
        int found = -1;
        for (int dx = -1; dx <= 1 && found < 0; ++dx)
            for (int dy = -1; dy <= 1 && found < 0; ++dy)
                for (int dz = -1; dz <= 1 && found < 0; ++dz) {
                    auto it = head.find(cellHash(cx + dx, cy + dy, cz + dz));
                    for (int r = it == head.end() ? -1 : it->second; r >= 0; r = chainNext[r])
                        if ((reps[r] - p).squaredNorm() <= tol * tol) { found = r; break; }
                }
        if (found < 0) {
            found = static_cast<int>(reps.size());
            reps.push_back(p);
            auto [it, inserted] = head.emplace(cellHash(cx, cy, cz), found);
            chainNext.push_back(inserted ? -1 : it->second);
            if (!inserted) it->second = found;
        }
        remap[v] = found;
    }
    report.welded_vertices = referenced - reps.size();

    // --- remap triangles, drop degenerate ones (UVs follow their triangles) ---
    std::vector<Eigen::Vector3i> tris;
    std::vector<Eigen::Vector2d> cuvs;
    tris.reserve(mesh.triangles.size());
    if (uvs) cuvs.reserve(mesh.corner_uvs.size());
    const double minDoubleArea = 2.0 * kDegenerateRelative * diag * diag;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& s = mesh.triangles[t];
        const Eigen::Vector3i w(remap[s[0]], remap[s[1]], remap[s[2]]);
        const bool repeated = w[0] == w[1] || w[1] == w[2] || w[0] == w[2];
        if (repeated || (reps[w[1]] - reps[w[0]]).cross(reps[w[2]] - reps[w[0]]).norm() <= minDoubleArea) {
            ++report.degenerate_removed;
            continue;
        }
        tris.push_back(w);
        if (uvs) for (int k = 0; k < 3; ++k) cuvs.push_back(mesh.corner_uvs[3 * t + k]);
    }
    if (tris.empty())
        throw fail("no triangles left after removing " +
                   count(report.degenerate_removed, "degenerate (zero-area) triangle", "degenerate (zero-area) triangles"));
    if (report.degenerate_removed > 0)
        report.warnings.push_back({sourceName + ": removed " +
                                   count(report.degenerate_removed, "degenerate (zero-area) triangle",
                                         "degenerate (zero-area) triangles")});

    // Compact: keep only vertices still referenced, in their input order (a clean mesh keeps its indices).
    std::vector<int> compact(reps.size(), -1);
    for (const Eigen::Vector3i& t : tris)
        for (int k = 0; k < 3; ++k) compact[t[k]] = 0;
    std::vector<Eigen::Vector3d> verts;
    verts.reserve(reps.size());
    for (std::size_t r = 0; r < reps.size(); ++r)
        if (compact[r] == 0) { compact[r] = static_cast<int>(verts.size()); verts.push_back(reps[r]); }
    for (Eigen::Vector3i& t : tris)
        for (int k = 0; k < 3; ++k) t[k] = compact[t[k]];
    mesh.vertices = std::move(verts);
    mesh.triangles = std::move(tris);
    mesh.corner_uvs = std::move(cuvs);

    // --- repair (opt-in): duplicate faces, orientation, holes ---
    MeshRepairReport& repair = report.repair;
    double volumeBeforeRepair = std::numeric_limits<double>::quiet_NaN();
    if (options.repair) {
        const Eigen::Vector3d centre = box.center();
        const double before = signedVolume(mesh, centre);
        try {
            repair.duplicate_faces_removed = removeDuplicateFaces(mesh);
            if (mesh.triangles.empty()) throw MeshError("no triangles left after removing faces given twice");
            repair.faces_reoriented = orientFaces(mesh);
            const HoleClosing closing = closeHoles(mesh, options.maxHoleEdges, minDoubleArea);
            repair.holes_closed = closing.holes;
            repair.hole_edges = closing.boundary_edges;
            repair.area_added = closing.area_added;
            repair.hole_triangles = closing.triangles;
            repair.hole_of_triangle = closing.hole_of_triangle;
        } catch (const MeshError& e) {
            throw fail(e.what());
        }
        volumeBeforeRepair = std::abs(before);
        if (repair.changed()) repair.volume_before = volumeBeforeRepair;
    }
    const std::size_t nt = mesh.triangles.size();

    // --- edges: closed, manifold, consistently oriented ---
    struct Edge { int lo, hi, tri; bool forward; };
    std::vector<Edge> edges;
    edges.reserve(3 * nt);
    for (std::size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), static_cast<int>(t), a < b});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri);
    });
    std::size_t boundary = 0, nonManifold = 0, inconsistent = 0;
    DisjointSets sets(nt);
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
        const std::size_t uses = j - i;
        if (uses == 1) ++boundary;
        else if (uses > 2) {
            // Repairing: 2k faces, k each way, are a closed surface touching itself along the edge (two parts
            // sharing an edge): pair each face one way with one the other way; the integrals need only that.
            std::vector<int> fwd, back;
            for (std::size_t k = i; k < j; ++k) (edges[k].forward ? fwd : back).push_back(edges[k].tri);
            if ((options.repair || options.acceptTouchingParts) && fwd.size() == back.size()) {
                for (std::size_t k = 0; k < fwd.size(); ++k) sets.unite(fwd[k], back[k]);
                ++repair.paired_nonmanifold_edges;
            } else {
                ++nonManifold;
            }
        } else {
            if (edges[i].forward == edges[i + 1].forward) ++inconsistent;
            sets.unite(edges[i].tri, edges[i + 1].tri);
        }
        i = j;
    }
    {
        std::vector<std::string> problems;
        if (boundary > 0) problems.push_back("open surface: " + count(boundary, "boundary edge", "boundary edges"));
        if (nonManifold > 0)
            problems.push_back("non-manifold: " + count(nonManifold, "edge", "edges") + " shared by more than two faces");
        if (inconsistent > 0)
            problems.push_back("inconsistent orientation: " + count(inconsistent, "edge", "edges") +
                               " used twice in the same direction (flipped triangles)");
        if (!problems.empty()) {
            std::string msg = options.repair ? "cannot be repaired: " : "";
            for (const std::string& p : problems) msg += (msg.empty() || msg.back() == ' ' ? "" : "; ") + p;
            throw fail(msg);
        }
    }

    // --- components ---
    std::vector<Component> comps;
    std::vector<std::size_t> flat;  // repairing: parts enclosing no volume
    {
        std::unordered_map<int, int> rootToComp;
        for (std::size_t t = 0; t < nt; ++t) {
            const int r = sets.find(static_cast<int>(t));
            auto [it, inserted] = rootToComp.emplace(r, static_cast<int>(comps.size()));
            if (inserted) comps.emplace_back();
            comps[it->second].tris.push_back(static_cast<int>(t));
        }
    }
    for (std::size_t c = 0; c < comps.size(); ++c) {
        Component& comp = comps[c];
        for (int t : comp.tris)
            for (int k = 0; k < 3; ++k) comp.box.extend(mesh.corner(t, k));
        const Eigen::Vector3d ref = comp.box.center();  // reference point near the part: less cancellation
        double six = 0.0;
        for (int t : comp.tris)
            six += (mesh.corner(t, 0) - ref).dot((mesh.corner(t, 1) - ref).cross(mesh.corner(t, 2) - ref));
        comp.volume = six / 6.0;
        const double d = comp.box.diagonal().norm();
        if (std::abs(comp.volume) <= kFlatRelative * d * d * d) {
            if (options.repair) { flat.push_back(c); continue; }  // a sheet (e.g. a fin closed by its own cap)
            throw fail("flat component: component " + std::to_string(c + 1) + " of " + std::to_string(comps.size()) +
                       " is a closed surface enclosing no volume");
        }
    }
    if (!flat.empty()) {
        // Repairing: parts enclosing no volume displace no water; drop them and check the rest (closed now, so the
        // second pass repairs nothing and keeps the triangle order: the hole triangles' indices stay valid after
        // the shift; it accepts the paired edges again).
        std::vector<char> keep(nt, 1);
        for (std::size_t c : flat)
            for (int t : comps[c].tris) keep[std::size_t(t)] = 0;
        std::vector<std::size_t> shifted(nt, 0);
        std::size_t kept = 0;
        for (std::size_t t = 0; t < nt; ++t) shifted[t] = kept, kept += keep[t] ? 1 : 0;
        if (kept == 0) throw fail("cannot be repaired: every part is flat (encloses no volume)");
        std::vector<std::size_t> holeTris, holeOf;
        for (std::size_t k = 0; k < repair.hole_triangles.size(); ++k)
            if (keep[repair.hole_triangles[k]]) {
                holeTris.push_back(shifted[repair.hole_triangles[k]]);
                holeOf.push_back(repair.hole_of_triangle[k]);
            }
        keepTriangles(mesh, keep);
        PrepareMeshOptions check;  // no repair: only the pairing the first pass accepted
        check.acceptTouchingParts = true;
        MeshReport inner = prepareMesh(mesh, sourceName, check);
        MeshReport out = report;
        out.repair.hole_triangles = std::move(holeTris);
        out.repair.hole_of_triangle = std::move(holeOf);
        out.repair.flat_parts_removed = flat.size();
        out.repair.paired_nonmanifold_edges = inner.repair.paired_nonmanifold_edges;
        out.repair.volume_before = volumeBeforeRepair;
        out.components = inner.components;
        out.flipped_components = inner.flipped_components;
        out.cavities = inner.cavities;
        for (const MeshWarning& w : inner.warnings) out.warnings.push_back(w);
        out.repair.volume_after = signedVolume(mesh, bboxOf(mesh).center());
        out.warnings.push_back({repairSummary(sourceName, out.repair)});
        return out;
    }
    report.components = comps.size();

    // --- nesting: which components enclose which (winding number of a point on the inner surface) ---
    const std::size_t nc = comps.size();
    // Candidates from a tree of component boxes: near-linear in the component count.
    std::vector<std::vector<int>> enclosedBy(nc);
    std::vector<std::pair<int, int>> mutual;
    if (nc > 1) {
        std::vector<Eigen::AlignedBox3d> compBoxes(nc);
        for (std::size_t c = 0; c < nc; ++c) compBoxes[c] = comps[c].box;
        const BoxTree tree(std::move(compBoxes));
        std::vector<int> stack;
        for (std::size_t j = 0; j < nc; ++j) {
            const int t0 = comps[j].tris.front();
            const Eigen::Vector3d probe = (mesh.corner(t0, 0) + mesh.corner(t0, 1) + mesh.corner(t0, 2)) / 3.0;
            tree.query(Eigen::AlignedBox3d(probe, probe), stack, [&](int i) {
                if (std::size_t(i) != j && std::abs(windingNumber(mesh, comps[std::size_t(i)].tris, probe)) > 0.5)
                    enclosedBy[j].push_back(i);
            });
            std::sort(enclosedBy[j].begin(), enclosedBy[j].end());  // the order of the old loop over i
        }
        // Surfaces that cross each other can each hold the other's probe point: such a pair is not nested
        // (found by fuzzing: the parent walk below looped forever on A in B in A). Drop both links;
        // the intersection warning reports the pair.
        for (std::size_t j = 0; j < nc; ++j)
            for (int i : enclosedBy[j])
                if (std::binary_search(enclosedBy[std::size_t(i)].begin(), enclosedBy[std::size_t(i)].end(), int(j)))
                    mutual.push_back({int(j), i});
        for (const auto& [a, b] : mutual) {
            auto& v = enclosedBy[std::size_t(a)];
            v.erase(std::remove(v.begin(), v.end(), b), v.end());
        }
        for (std::size_t j = 0; j < nc; ++j) comps[j].depth = static_cast<int>(enclosedBy[j].size());
    }
    for (std::size_t j = 0; j < nc; ++j) {
        int best = -1;
        for (int i : enclosedBy[j])
            if (best < 0 || comps[i].depth > comps[best].depth) best = i;
        comps[j].parent = best;
    }
    std::vector<int> order(nc);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return comps[a].depth < comps[b].depth; });
    auto label = [&](int c) { return "component " + std::to_string(c + 1) + " of " + std::to_string(nc); };
    std::vector<char> rootFlipped(nc, 0);
    for (int c : order) {
        Component& comp = comps[c];
        // Longer cycles (A in B in C in A) can still come from crossing surfaces: stop after nc steps.
        int root = c;
        for (std::size_t steps = 0; comps[root].parent >= 0 && steps < nc; ++steps) root = comps[root].parent;
        if (comps[root].parent >= 0) root = c;
        if (comp.parent < 0) {
            if (comp.volume < 0) {
                comp.flipped = true;
                rootFlipped[c] = 1;
                report.warnings.push_back({sourceName + ": " + (nc > 1 ? label(c) : std::string("mesh")) +
                                           " was inside-out (volume " + fmt(comp.volume) + " m^3): flipped outward"});
            }
        } else {
            const double parentSign = (comps[comp.parent].volume < 0) != comps[comp.parent].flipped ? -1.0 : 1.0;
            const double sign = comp.volume < 0 ? -1.0 : 1.0;
            if (sign == parentSign) {
                if (rootFlipped[root]) {
                    comp.flipped = true;  // part of an object exported inside-out as a whole
                    report.warnings.push_back({sourceName + ": " + label(c) + " (inside " + label(comp.parent) +
                                               ") was inside-out: flipped"});
                } else {
                    report.warnings.push_back(
                        {sourceName + ": " + label(c) + " lies inside " + label(comp.parent) +
                         " with the same orientation: the volume they share is counted twice"});
                }
            }
        }
        if (comp.flipped) {
            ++report.flipped_components;
            for (int t : comp.tris) {
                std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
                if (uvs) std::swap(mesh.corner_uvs[3 * t + 1], mesh.corner_uvs[3 * t + 2]);
            }
        }
        const bool negative = (comp.volume < 0) != comp.flipped;
        if (negative) ++report.cavities;
    }

    // --- the whole must enclose a positive volume (found by fuzzing: a cavity larger than its
    // body, or a surface crossing itself, passed the checks above and failed later as an internal error) ---
    {
        double total = 0.0;
        for (const Component& c : comps) total += c.flipped ? -c.volume : c.volume;
        if (!(total > kFlatRelative * diag * diag * diag))
            throw fail("encloses no positive volume: the components add up to " + fmt(total) +
                       " m^3 (a cavity larger than its body, or a surface crossing itself)");
        if (repair.changed()) {
            repair.volume_after = total;
            report.warnings.push_back({repairSummary(sourceName, repair)});
        }
    }

    // --- components that intersect each other (one BVH pass over all triangles) ---
    std::size_t intersecting = 0;
    std::string pairs;
    if (nc > 1) {
        std::vector<int> triangleComponent(nt);
        for (std::size_t c = 0; c < nc; ++c)
            for (int t : comps[c].tris) triangleComponent[std::size_t(t)] = static_cast<int>(c);
        for (const auto& [i, j] : intersectingComponentPairs(mesh, triangleComponent))
            if (++intersecting <= 5) pairs += (pairs.empty() ? "" : ", ") + std::to_string(i + 1) + "&" + std::to_string(j + 1);
    }
    if (intersecting > 0)
        report.warnings.push_back({sourceName + ": " + std::to_string(intersecting) +
                                   (intersecting == 1 ? " pair" : " pairs") +
                                   " of components intersect each other (" + pairs + (intersecting > 5 ? ", ..." : "") +
                                   "): the volume they share is counted twice"});
    return report;
}

}  // namespace buoyancy
