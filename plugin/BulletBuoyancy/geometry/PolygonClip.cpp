#include <BulletBuoyancy/geometry/PolygonClip.h>

#include <cmath>

namespace buoyancy {

ClipPolygon ClipPolygon::triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    ClipPolygon p;
    p.n = 3;
    p.v[0] = a;
    p.v[1] = b;
    p.v[2] = c;
    return p;
}

// Sutherland–Hodgman against one axis-aligned line: walk the edges (prev → cur), emit the crossing point
// when the edge crosses the line and the current vertex when it is inside.
void clipAxisAligned(const ClipPolygon& in, int axis, double bound, bool keepAbove, ClipPolygon& out) {
    out.n = 0;
    if (in.n == 0) return;
    auto inside = [&](const Eigen::Vector2d& p) { return keepAbove ? p[axis] >= bound : p[axis] <= bound; };
    const int other = 1 - axis;
    Eigen::Vector2d prev = in.v[in.n - 1];
    bool prevIn = inside(prev);
    for (int i = 0; i < in.n; ++i) {
        const Eigen::Vector2d& cur = in.v[i];
        const bool curIn = inside(cur);
        if (curIn != prevIn && out.n < ClipPolygon::kMaxVertices) {
            const double t = (bound - prev[axis]) / (cur[axis] - prev[axis]);
            Eigen::Vector2d x;
            x[axis] = bound;
            x[other] = prev[other] + t * (cur[other] - prev[other]);
            out.v[out.n++] = x;
        }
        if (curIn && out.n < ClipPolygon::kMaxVertices) out.v[out.n++] = cur;
        prev = cur;
        prevIn = curIn;
    }
    if (out.n < 3) out.n = 0;
}

void clipHalfPlane(const ClipPolygon& in, const Eigen::Vector2d& a, const Eigen::Vector2d& b, ClipPolygon& out) {
    out.n = 0;
    if (in.n == 0) return;
    Eigen::Vector2d prev = in.v[in.n - 1];
    double dPrev = cross2(a, b, prev);
    for (int i = 0; i < in.n; ++i) {
        const Eigen::Vector2d& cur = in.v[i];
        const double dCur = cross2(a, b, cur);
        if (((dCur >= 0) != (dPrev >= 0)) && out.n < ClipPolygon::kMaxVertices) {
            const double t = dPrev / (dPrev - dCur);
            out.v[out.n++] = prev + t * (cur - prev);
        }
        if (dCur >= 0 && out.n < ClipPolygon::kMaxVertices) out.v[out.n++] = cur;
        prev = cur;
        dPrev = dCur;
    }
    if (out.n < 3) out.n = 0;
}

double signedArea(const ClipPolygon& poly) {
    double twice = 0;
    for (int i = 1; i + 1 < poly.n; ++i) twice += cross2(poly.v[0], poly.v[i], poly.v[i + 1]);
    return 0.5 * twice;
}

// Fan triangulation from vertex 0: area-weighted sum of the fan triangles' centroids (exact for any
// simple polygon, both windings, since the signed weights cancel consistently).
void areaAndCentroid(const ClipPolygon& poly, double& area, Eigen::Vector2d& centroid) {
    area = 0;
    centroid = poly.n > 0 ? poly.v[0] : Eigen::Vector2d::Zero();
    if (poly.n < 3) return;
    const Eigen::Vector2d o = poly.v[0];
    double twice = 0;
    Eigen::Vector2d acc = Eigen::Vector2d::Zero();
    for (int i = 1; i + 1 < poly.n; ++i) {
        const Eigen::Vector2d e1 = poly.v[i] - o, e2 = poly.v[i + 1] - o;
        const double w = e1.x() * e2.y() - e1.y() * e2.x();
        twice += w;
        acc += w * (e1 + e2);  // centroid of fan triangle relative to o: (e1 + e2) / 3
    }
    area = 0.5 * twice;
    if (twice != 0) centroid = o + acc / (3.0 * twice);
}

double triangleIntersectionArea(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& a2,
                                const Eigen::Vector2d& b0, const Eigen::Vector2d& b1, const Eigen::Vector2d& b2) {
    ClipPolygon p = ClipPolygon::triangle(a0, a1, a2), q;
    // Orient the clipping triangle counter-clockwise so "left of each edge" is its inside.
    const bool ccw = cross2(b0, b1, b2) >= 0;
    const Eigen::Vector2d c0 = b0, c1 = ccw ? b1 : b2, c2 = ccw ? b2 : b1;
    clipHalfPlane(p, c0, c1, q);
    clipHalfPlane(q, c1, c2, p);
    clipHalfPlane(p, c2, c0, q);
    return std::abs(signedArea(q));
}

}  // namespace buoyancy
