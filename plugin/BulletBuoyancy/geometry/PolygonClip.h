#pragma once
/// @file PolygonClip.h
/// Small convex-polygon geometry in the UV plane, used by the baker (clipping triangles against texel
/// squares, design.md 1.1) and by the UV checks (area of the overlap of two UV triangles, 1.2).
/// Sutherland–Hodgman clipping (Sutherland & Hodgman 1974); fixed-size storage, no allocation.

#include <Eigen/Core>

namespace buoyancy {

/// A convex polygon of at most kMaxVertices vertices in the plane (either winding).
struct ClipPolygon {
    static constexpr int kMaxVertices = 16; ///< a triangle clipped by ≤ 6 half-planes has ≤ 9 vertices
    int n = 0;                              ///< number of vertices
    Eigen::Vector2d v[kMaxVertices];        ///< vertices in order

    /// The polygon of a triangle (a, b, c), in that order.
    static ClipPolygon triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);
};

/// Keep the part of `in` with coordinate `axis` (0 = u, 1 = v) ≥ bound (keepAbove) or ≤ bound (!keepAbove).
/// Points created on the clip line get exactly `bound` as that coordinate. Keeps the input's winding.
void clipAxisAligned(const ClipPolygon& in, int axis, double bound, bool keepAbove, ClipPolygon& out);

/// Keep the part of `in` on the left of the directed line a → b (cross(b − a, p − a) ≥ 0).
void clipHalfPlane(const ClipPolygon& in, const Eigen::Vector2d& a, const Eigen::Vector2d& b, ClipPolygon& out);

/// Signed area by the shoelace formula (positive for counter-clockwise), in squared input units.
double signedArea(const ClipPolygon& poly);

/// Signed area and centroid of the polygon (centroid undefined, set to the first vertex, when area is 0).
/// Computed relative to the first vertex to limit cancellation.
void areaAndCentroid(const ClipPolygon& poly, double& area, Eigen::Vector2d& centroid);

/// Area of the intersection of two triangles (any winding, non-degenerate), ≥ 0: the first triangle
/// clipped by the three edge half-planes of the second.
double triangleIntersectionArea(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& a2,
                                const Eigen::Vector2d& b0, const Eigen::Vector2d& b1, const Eigen::Vector2d& b2);

/// Twice the signed area of triangle (a, b, c): cross(b − a, c − a).
inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

}  // namespace buoyancy
