/// @file ComponentIntersections.cpp
/// Component–component intersection test of prepareMesh (MeshRepair.cpp header: "components that intersect
/// each other get a warning"). The triangle–triangle predicate is the classic edge-crosses-triangle test
/// with orient3d signs (Möller 1997 reduces to the same sign tests); the broad phase is a bounding-volume
/// hierarchy over triangle boxes (BoxTree.h).

#include <BulletBuoyancy/mesh/ComponentIntersections.h>

#include <BulletBuoyancy/mesh/BoxTree.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace buoyancy {

namespace {

/// orient3d: sign of six times the signed volume of tetrahedron (a, b, c, d), with a relative "zero" band.
int orientSign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
               const Eigen::Vector3d& d) {
    const Eigen::Vector3d u = b - a, v = c - a, w = d - a;
    const double det = u.cross(v).dot(w);
    const double scale = u.norm() * v.norm() * w.norm();
    if (std::abs(det) <= 1e-12 * scale) return 0;
    return det > 0 ? 1 : -1;
}

/// True when segment pq crosses the interior of triangle abc (touching does not count).
bool segmentCrossesTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const int sp = orientSign(a, b, c, p), sq = orientSign(a, b, c, q);
    if (sp == 0 || sq == 0 || sp == sq) return false;
    // The line pq meets the closed triangle (edges included: symmetric overlaps often cross exactly on a
    // diagonal); the strict plane test above already excludes mere touching by an endpoint.
    const int s1 = orientSign(p, q, a, b), s2 = orientSign(p, q, b, c), s3 = orientSign(p, q, c, a);
    const bool allNonNeg = s1 >= 0 && s2 >= 0 && s3 >= 0, allNonPos = s1 <= 0 && s2 <= 0 && s3 <= 0;
    return (allNonNeg || allNonPos) && (s1 != 0 || s2 != 0 || s3 != 0);
}

/// Proper (non-touching, non-coplanar) intersection of two triangles: an edge of one crosses the other.
bool trianglesIntersect(const Eigen::Vector3d* A, const Eigen::Vector3d* B) {
    for (int e = 0; e < 3; ++e) {
        if (segmentCrossesTriangle(A[e], A[(e + 1) % 3], B[0], B[1], B[2])) return true;
        if (segmentCrossesTriangle(B[e], B[(e + 1) % 3], A[0], A[1], A[2])) return true;
    }
    return false;
}

}  // namespace

std::vector<std::pair<int, int>> intersectingComponentPairs(const TriangleMesh& mesh,
                                                            const std::vector<int>& triangleComponent) {
    const std::size_t nt = mesh.triangles.size();
    std::vector<Eigen::AlignedBox3d> boxes(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        boxes[t] = Eigen::AlignedBox3d(mesh.corner(t, 0));
        boxes[t].extend(mesh.corner(t, 1));
        boxes[t].extend(mesh.corner(t, 2));
    }
    const BoxTree tree(std::move(boxes));
    std::unordered_set<std::uint64_t> found;
    auto key = [](int a, int b) {
        return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
    };
    std::vector<int> stack;
    for (std::size_t t = 0; t < nt; ++t) {
        const int ct = triangleComponent[t];
        const Eigen::Vector3d A[3] = {mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)};
        tree.query(tree.box(int(t)), stack, [&](int u) {
            if (std::size_t(u) <= t) return;  // each unordered pair once
            const int cu = triangleComponent[std::size_t(u)];
            if (cu == ct) return;  // neighbours in one closed surface touch by construction
            const std::uint64_t k = key(ct, cu);
            if (found.count(k)) return;
            const Eigen::Vector3d B[3] = {mesh.corner(std::size_t(u), 0), mesh.corner(std::size_t(u), 1),
                                          mesh.corner(std::size_t(u), 2)};
            if (trianglesIntersect(A, B)) found.insert(k);
        });
    }
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(found.size());
    for (std::uint64_t k : found) pairs.emplace_back(int(k >> 32), int(k & 0xffffffffu));
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace buoyancy
