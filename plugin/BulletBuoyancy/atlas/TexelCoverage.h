#pragma once
/// @file TexelCoverage.h
/// Exact coverage of texel squares by one UV triangle (design.md 1.1): the triangle is clipped to each
/// texel row, then to each texel of the row (Sutherland–Hodgman), and every piece of non-zero area is
/// handed to a callback. Shared by the baker and the UV-layout checks.

#include <BulletBuoyancy/geometry/PolygonClip.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace buoyancy {

/// Inclusive texel range [lo, hi] touched by the interval [a, b] (texel coordinates), clamped to [0, N−1].
inline void texelRange(double a, double b, int N, int& lo, int& hi) {
    lo = std::max(0, std::min(N - 1, static_cast<int>(std::floor(a))));
    hi = std::min(N - 1, static_cast<int>(std::ceil(b)) - 1);
    if (hi < lo) hi = lo;
}

/// Call f(x, y, piece) for every texel (x, y) of an N×N grid whose square [x, x+1]×[y, y+1] overlaps the
/// triangle (s0, s1, s2) with non-zero area. Corners are in texel coordinates (s = N·uv); parts outside
/// [0, N]² are not visited. `piece` keeps the triangle's winding (negative area for mirrored triangles).
template <class F>
void forEachTexelPiece(const Eigen::Vector2d& s0, const Eigen::Vector2d& s1, const Eigen::Vector2d& s2, int N, F&& f) {
    const ClipPolygon tri = ClipPolygon::triangle(s0, s1, s2);
    int y0, y1;
    texelRange(std::min({s0.y(), s1.y(), s2.y()}), std::max({s0.y(), s1.y(), s2.y()}), N, y0, y1);
    ClipPolygon tmp, strip, piece;
    for (int y = y0; y <= y1; ++y) {
        clipAxisAligned(tri, 1, y, true, tmp);
        clipAxisAligned(tmp, 1, y + 1.0, false, strip);
        if (strip.n == 0) continue;
        double umin = strip.v[0].x(), umax = umin;
        for (int k = 1; k < strip.n; ++k) {
            umin = std::min(umin, strip.v[k].x());
            umax = std::max(umax, strip.v[k].x());
        }
        int x0, x1;
        texelRange(umin, umax, N, x0, x1);
        for (int x = x0; x <= x1; ++x) {
            clipAxisAligned(strip, 0, x, true, tmp);
            clipAxisAligned(tmp, 0, x + 1.0, false, piece);
            if (piece.n == 0) continue;
            f(x, y, piece);
        }
    }
}

/// Shared by the texel-centre baker (BakeSamples.cpp) and the deformable re-bake map (DeformableRebake.cpp).
/// Edge function of edge a → b at p, computed from the lexicographically smaller endpoint so that the
/// two triangles sharing an edge get exactly opposite values (a consistent fill rule).
inline double edgeFunction(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
    const bool forward = a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    return forward ? cross2(a, b, p) : -cross2(b, a, p);
}

/// Fill rule for centres exactly on an edge: of the directions d and −d, exactly one qualifies.
inline bool ownsEdge(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = b - a;
    return d.y() < 0 || (d.y() == 0 && d.x() > 0);
}

}  // namespace buoyancy
