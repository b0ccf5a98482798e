/// @file btWaterBody.cpp
/// The regions of water bodies (btWaterBody.h, design.md 2.9): checking them, point and sphere tests, their convex
/// pieces as half-spaces of the water frame (what regionHydrostatics clips by), and the exact overlap test.

#include <BulletBuoyancy/bullet/btWaterBody.h>

#include <BulletBuoyancy/bullet/btWaterFrame.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace {

/// Cosine above which a mesh face's outward normal is taken as up (the tank's lid) or down (its floor).
constexpr double kFlatFace = 1.0 - 1e-9;

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

/// "[x, y, z]" of a corner, m.
std::string cornerText(const Eigen::Vector3d& v) {
    return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]";
}

std::string pointText(const Eigen::Vector2d& v) { return "[" + num(v.x()) + ", " + num(v.y()) + "]"; }

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Distance from p to the segment a-b (2-D).
double segmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + u * ab)).norm();
}

/// Orientation of c relative to the line a-b (2-D): > 0 left, < 0 right, 0 on it.
double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return cross2(b - a, c - a);
}

bool onSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
    return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
           p.y() <= std::max(a.y(), b.y());
}

/// True when the closed segments a-b and c-d meet (crossing or touching).
bool segmentsMeet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
    const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
    if (o1 == 0 && onSegment(a, b, c)) return true;
    if (o2 == 0 && onSegment(a, b, d)) return true;
    if (o3 == 0 && onSegment(c, d, a)) return true;
    if (o4 == 0 && onSegment(c, d, b)) return true;
    return false;
}

/// Closest point to p on the triangle a, b, c (Ericson, Real-Time Collision Detection 5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

/// A triangle of a region's mesh in water-frame coordinates (the frame in use: a mesh is given in world coordinates).
struct FrameTriangle {
    Eigen::Vector3d corner[3];
    Eigen::Vector3d normal;  ///< (b − a) × (c − a), outward, not normalised
    /// +1 when the outward normal has a part along up (the region's top: its lid, a roof), −1 against up (its floor),
    /// 0 for a wall (no area seen from above).
    int facing = 0;
    Eigen::Vector2d flat(int k) const { return Eigen::Vector2d(corner[k].x(), corner[k].z()); }
    /// Height along up of the triangle's plane above the horizontal point p = (x, z), m.
    double heightAt(const Eigen::Vector2d& p) const {
        return corner[0].y() - (normal.x() * (p.x() - corner[0].x()) + normal.z() * (p.y() - corner[0].z())) / normal.y();
    }
};

/// Below this |n_y| / |n| a face of a column mesh is a wall: its shadow seen from above has no area.
constexpr double kWallFace = 1e-9;

FrameTriangle frameTriangle(const btWaterBody& body, const btWaterFrame& frame, std::size_t t) {
    FrameTriangle f;
    for (int k = 0; k < 3; ++k) f.corner[k] = frame.toWaterPoint(body.meshVertices[std::size_t(body.meshTriangles[t][std::size_t(k)])]);
    f.normal = (f.corner[1] - f.corner[0]).cross(f.corner[2] - f.corner[0]);
    const double n = f.normal.norm();
    f.facing = f.normal.y() > kWallFace * n ? 1 : (f.normal.y() < -kWallFace * n ? -1 : 0);
    return f;
}

/// The triangle's shadow seen from above as a counter-clockwise (x, z) triangle (positive cross2 area).
std::array<Eigen::Vector2d, 3> shadowOf(const FrameTriangle& f) {
    std::array<Eigen::Vector2d, 3> t = {f.flat(0), f.flat(1), f.flat(2)};
    if (cross2(t[1] - t[0], t[2] - t[0]) < 0) std::swap(t[1], t[2]);
    return t;
}

/// Horizontal distance from p to the counter-clockwise triangle t, m (0 inside or on it).
double shadowDistance(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& p) {
    if (orient(t[0], t[1], p) >= 0 && orient(t[1], t[2], p) >= 0 && orient(t[2], t[0], p) >= 0) return 0.0;
    return std::min({segmentDistance(p, t[0], t[1]), segmentDistance(p, t[1], t[2]), segmentDistance(p, t[2], t[0])});
}

/// The part of the convex counter-clockwise polygon `poly` left of the line a → b (Sutherland–Hodgman, one edge).
std::vector<Eigen::Vector2d> keepLeftOf(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& a,
                                        const Eigen::Vector2d& b) {
    std::vector<Eigen::Vector2d> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Eigen::Vector2d& p = poly[i];
        const Eigen::Vector2d& q = poly[(i + 1) % poly.size()];
        const double dp = orient(a, b, p), dq = orient(a, b, q);
        if (dp >= 0) out.push_back(p);
        if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    return out;
}

/// The common part of two counter-clockwise triangles (a convex polygon, counter-clockwise; empty or degenerate when
/// they only touch).
std::vector<Eigen::Vector2d> commonShadow(const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b) {
    std::vector<Eigen::Vector2d> poly(a.begin(), a.end());
    for (int k = 0; k < 3 && poly.size() >= 3; ++k) poly = keepLeftOf(poly, b[std::size_t(k)], b[std::size_t((k + 1) % 3)]);
    return poly;
}

double polygonArea(const std::vector<Eigen::Vector2d>& poly) {
    double twice = 0;
    for (std::size_t i = 0; i < poly.size(); ++i) twice += cross2(poly[i], poly[(i + 1) % poly.size()]);
    return 0.5 * twice;
}

bool boxesApart(const std::array<Eigen::Vector2d, 3>& a, const std::array<Eigen::Vector2d, 3>& b) {
    for (int k = 0; k < 2; ++k) {
        const double aLo = std::min({a[0][k], a[1][k], a[2][k]}), aHi = std::max({a[0][k], a[1][k], a[2][k]});
        const double bLo = std::min({b[0][k], b[1][k], b[2][k]}), bHi = std::max({b[0][k], b[1][k], b[2][k]});
        if (aHi <= bLo || bHi <= aLo) return true;
    }
    return false;
}

/// The region's planes: the three vertical sides of the prism over the counter-clockwise (x, z) triangle `t` (water
/// frame).
void setPrismSides(buoyancy::WaterRegion& region, const std::array<Eigen::Vector2d, 3>& t) {
    region.planeCount = 0;
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& a = t[std::size_t(k)];
        const Eigen::Vector2d& b = t[std::size_t((k + 1) % 3)];
        // Positive area: the interior is left of a → b, the outward normal points right.
        const Eigen::Vector3d normal = Eigen::Vector3d(b.y() - a.y(), 0, -(b.x() - a.x())).normalized();
        const int i = region.planeCount++;
        region.normal[i] = normal;
        region.offset[i] = normal.x() * a.x() + normal.z() * a.y();
    }
}

/// A convex piece of a region in water-frame coordinates, for the separating-axis test.
struct ConvexPiece {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<Eigen::Vector3d> normals;  ///< face normals (direction only)
    std::vector<Eigen::Vector3d> edges;    ///< edge directions
};

void addDirection(std::vector<Eigen::Vector3d>& list, const Eigen::Vector3d& d) {
    const double n = d.norm();
    if (!(n > 0)) return;
    const Eigen::Vector3d u = d / n;
    for (const Eigen::Vector3d& e : list)
        if (std::abs(e.dot(u)) > 1.0 - 1e-12) return;
    list.push_back(u);
}

/// The region's convex pieces, closed (with top and bottom), in water-frame coordinates.
std::vector<ConvexPiece> convexPieces(const btWaterBody& body, const btWaterFrame& frame) {
    std::vector<ConvexPiece> pieces;
    switch (body.kind) {
    case btWaterRegionKind::Box: {
        ConvexPiece piece;
        for (int corner = 0; corner < 8; ++corner)
            piece.vertices.push_back(frame.toWaterPoint(Eigen::Vector3d(
                (corner & 1) ? body.regionMax.x() : body.regionMin.x(), (corner & 2) ? body.regionMax.y() : body.regionMin.y(),
                (corner & 4) ? body.regionMax.z() : body.regionMin.z())));
        for (int k = 0; k < 3; ++k) {
            addDirection(piece.normals, frame.toWaterVector(Eigen::Vector3d::Unit(k)));
            addDirection(piece.edges, frame.toWaterVector(Eigen::Vector3d::Unit(k)));
        }
        pieces.push_back(piece);
        break;
    }
    case btWaterRegionKind::Polygon:
        for (const std::array<int, 3>& t : body.footprintTriangles) {
            ConvexPiece piece;
            for (int k = 0; k < 3; ++k) {
                const Eigen::Vector2d& a = body.footprint[std::size_t(t[k])];
                const Eigen::Vector2d& b = body.footprint[std::size_t(t[(k + 1) % 3])];
                piece.vertices.emplace_back(a.x(), body.bottom, a.y());
                piece.vertices.emplace_back(a.x(), body.top, a.y());
                addDirection(piece.normals, Eigen::Vector3d(b.y() - a.y(), 0, -(b.x() - a.x())));
                addDirection(piece.edges, Eigen::Vector3d(b.x() - a.x(), 0, b.y() - a.y()));
            }
            addDirection(piece.normals, Eigen::Vector3d::UnitY());
            addDirection(piece.edges, Eigen::Vector3d::UnitY());
            pieces.push_back(piece);
        }
        break;
    case btWaterRegionKind::Mesh: {
        if (body.meshColumns) {
            // Every vertical line meets the region in one segment, from a floor triangle up to a top triangle: the
            // region is the union of the columns over the common shadows of a top and a floor triangle, each bounded by
            // their two planes (convex: a convex shadow between two planes).
            std::vector<FrameTriangle> tops, floors;
            for (std::size_t t = 0; t < body.meshTriangles.size(); ++t) {
                const FrameTriangle f = frameTriangle(body, frame, t);
                if (f.facing > 0) tops.push_back(f);
                if (f.facing < 0) floors.push_back(f);
            }
            for (const FrameTriangle& top : tops) {
                const std::array<Eigen::Vector2d, 3> topShadow = shadowOf(top);
                for (const FrameTriangle& floor : floors) {
                    const std::array<Eigen::Vector2d, 3> floorShadow = shadowOf(floor);
                    if (boxesApart(topShadow, floorShadow)) continue;
                    const std::vector<Eigen::Vector2d> cell = commonShadow(topShadow, floorShadow);
                    if (cell.size() < 3 || !(polygonArea(cell) > 0)) continue;
                    ConvexPiece piece;
                    for (std::size_t k = 0; k < cell.size(); ++k) {
                        const Eigen::Vector2d& a = cell[k];
                        const Eigen::Vector2d& b = cell[(k + 1) % cell.size()];
                        piece.vertices.emplace_back(a.x(), floor.heightAt(a), a.y());
                        piece.vertices.emplace_back(a.x(), top.heightAt(a), a.y());
                        addDirection(piece.normals, Eigen::Vector3d(b.y() - a.y(), 0, -(b.x() - a.x())));
                        addDirection(piece.edges, Eigen::Vector3d(b.x() - a.x(), floor.heightAt(b) - floor.heightAt(a),
                                                                  b.y() - a.y()));
                        addDirection(piece.edges, Eigen::Vector3d(b.x() - a.x(), top.heightAt(b) - top.heightAt(a),
                                                                  b.y() - a.y()));
                    }
                    addDirection(piece.normals, top.normal);
                    addDirection(piece.normals, floor.normal);
                    addDirection(piece.edges, Eigen::Vector3d::UnitY());
                    pieces.push_back(piece);
                }
            }
            break;
        }
        ConvexPiece piece;
        for (const Eigen::Vector3d& v : body.meshVertices) piece.vertices.push_back(frame.toWaterPoint(v));
        for (const Eigen::Vector3d& n : body.meshNormals) addDirection(piece.normals, frame.toWaterVector(n));
        for (const std::array<int, 3>& t : body.meshTriangles)
            for (int k = 0; k < 3; ++k)
                addDirection(piece.edges, frame.toWaterVector(body.meshVertices[std::size_t(t[(k + 1) % 3])] -
                                                              body.meshVertices[std::size_t(t[k])]));
        pieces.push_back(piece);
        break;
    }
    }
    return pieces;
}

/// True when the interiors of two convex pieces meet: no axis (face normals of either, cross products of their edge
/// directions) separates their projections by more than −tolerance.
bool piecesOverlap(const ConvexPiece& a, const ConvexPiece& b, double tolerance) {
    const auto separates = [&](const Eigen::Vector3d& axis) {
        const double n = axis.norm();
        if (!(n > 1e-12)) return false;
        const Eigen::Vector3d u = axis / n;
        double minA = std::numeric_limits<double>::infinity(), maxA = -minA, minB = minA, maxB = -minA;
        for (const Eigen::Vector3d& v : a.vertices) {
            minA = std::min(minA, u.dot(v));
            maxA = std::max(maxA, u.dot(v));
        }
        for (const Eigen::Vector3d& v : b.vertices) {
            minB = std::min(minB, u.dot(v));
            maxB = std::max(maxB, u.dot(v));
        }
        return maxA <= minB + tolerance || maxB <= minA + tolerance;
    };
    for (const Eigen::Vector3d& n : a.normals)
        if (separates(n)) return false;
    for (const Eigen::Vector3d& n : b.normals)
        if (separates(n)) return false;
    for (const Eigen::Vector3d& ea : a.edges)
        for (const Eigen::Vector3d& eb : b.edges)
            if (separates(ea.cross(eb))) return false;
    return true;
}

/// Point in polygon (2-D, crossing number; points on the boundary count as inside through the distance test).
bool insidePolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
    bool inside = false;
    const std::size_t n = poly.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const Eigen::Vector2d& a = poly[i];
        const Eigen::Vector2d& b = poly[j];
        if ((a.y() > p.y()) != (b.y() > p.y())) {
            const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
            if (p.x() < x) inside = !inside;
        }
    }
    return inside;
}

double boundaryDistance(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < poly.size(); ++i) d = std::min(d, segmentDistance(p, poly[i], poly[(i + 1) % poly.size()]));
    return d;
}

/// Horizontal distance from p to the footprint, m (0 inside or on it).
double footprintDistance(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
    if (insidePolygon(poly, p)) return 0.0;
    return boundaryDistance(poly, p);
}

bool isLid(const btWaterFrame& frame, const Eigen::Vector3d& worldNormal) {
    return frame.toWaterVector(worldNormal).y() >= kFlatFace;
}
bool isFloor(const btWaterFrame& frame, const Eigen::Vector3d& worldNormal) {
    return frame.toWaterVector(worldNormal).y() <= -kFlatFace;
}

/// The axis of the box face nearest the water frame's up (its top: the water is not cut off there).
int topAxisOf(const Eigen::Vector3d& up) {
    int top = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(up[k]) > std::abs(up[top])) top = k;
    return top;
}

}  // namespace

void btWaterBody::setRegion(const btWaterBodyInfo& info, const btWaterFrame& frame, const std::string& who) {
    kind = info.regionKind;
    footprint.clear();
    footprintTriangles.clear();
    meshVertices.clear();
    meshTriangles.clear();
    meshNormals.clear();
    meshOffsets.clear();
    meshNeighbours.clear();
    meshColumns = false;
    switch (kind) {
    case btWaterRegionKind::Box: {
        regionMin = Eigen::Vector3d(double(info.regionMin.x()), double(info.regionMin.y()), double(info.regionMin.z()));
        regionMax = Eigen::Vector3d(double(info.regionMax.x()), double(info.regionMax.y()), double(info.regionMax.z()));
        static const char* const axes[3] = {"x", "y", "z"};
        for (int k = 0; k < 3; ++k) {
            if (!std::isfinite(regionMin[k])) throw std::invalid_argument(who + "regionMin." + axes[k] + ": must be finite");
            if (!std::isfinite(regionMax[k])) throw std::invalid_argument(who + "regionMax." + axes[k] + ": must be finite");
            if (!(regionMin[k] < regionMax[k]))
                throw std::invalid_argument(who + "regionMax." + axes[k] + ": must be greater than regionMin." + axes[k] +
                                            " (" + cornerText(regionMin) + " to " + cornerText(regionMax) + ")");
        }
        return;
    }
    case btWaterRegionKind::Polygon: {
        const std::size_t n = info.footprint.size();
        if (n < 3)
            throw std::invalid_argument(who + "footprint: a polygon needs at least 3 corners (got " + std::to_string(n) +
                                        ")");
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector2d p(info.footprint[i][0], info.footprint[i][1]);
            if (!p.allFinite()) throw std::invalid_argument(who + "footprint[" + std::to_string(i) + "]: must be finite");
            footprint.push_back(p);
        }
        if (!std::isfinite(info.bottom)) throw std::invalid_argument(who + "bottom: must be finite");
        if (!std::isfinite(info.top)) throw std::invalid_argument(who + "top: must be finite");
        if (!(info.bottom < info.top))
            throw std::invalid_argument(who + "top: must be greater than bottom (bottom " + num(info.bottom) + ", top " +
                                        num(info.top) + ")");
        bottom = info.bottom;
        top = info.top;
        const std::string bad = who + "footprint: not a simple polygon: ";
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j)
                if (footprint[i] == footprint[j])
                    throw std::invalid_argument(bad + "corners " + std::to_string(i) + " and " + std::to_string(j) +
                                                " are the same point " + pointText(footprint[i]));
        const auto edgeText = [&](std::size_t i) {
            return "edge " + std::to_string(i) + " (" + pointText(footprint[i]) + " to " +
                   pointText(footprint[(i + 1) % n]) + ")";
        };
        for (std::size_t i = 0; i < n; ++i) {
            // Adjacent edges meet at their shared corner only: folding back along the same line is a crossing.
            const std::size_t j = (i + 1) % n;
            const Eigen::Vector2d e0 = footprint[j] - footprint[i], e1 = footprint[(j + 1) % n] - footprint[j];
            if (cross2(e0, e1) == 0 && e0.dot(e1) < 0)
                throw std::invalid_argument(bad + edgeText(i) + " and " + edgeText(j) + " fold back on each other");
            for (std::size_t k = i + 2; k < n; ++k) {
                if (i == 0 && k == n - 1) continue;  // adjacent through the closing edge
                if (segmentsMeet(footprint[i], footprint[j], footprint[k], footprint[(k + 1) % n]))
                    throw std::invalid_argument(bad + edgeText(i) + " meets " + edgeText(k));
            }
        }
        double area2 = 0;
        for (std::size_t i = 0; i < n; ++i) area2 += cross2(footprint[i], footprint[(i + 1) % n]);
        double extent = 0;
        for (const Eigen::Vector2d& p : footprint) extent = std::max(extent, (p - footprint[0]).norm());
        if (!(std::abs(area2) > 1e-12 * extent * extent))
            throw std::invalid_argument(who + "footprint: the polygon has zero area (its corners are on one line)");
        if (area2 < 0) std::reverse(footprint.begin(), footprint.end());
        // Ear clipping: cut off a convex corner whose triangle holds no other remaining corner, until 3 are left.
        std::vector<int> left(n);
        for (std::size_t i = 0; i < n; ++i) left[i] = int(i);
        while (left.size() > 3) {
            const std::size_t m = left.size();
            bool cut = false;
            for (std::size_t i = 0; i < m && !cut; ++i) {
                const int ia = left[(i + m - 1) % m], ib = left[i], ic = left[(i + 1) % m];
                const Eigen::Vector2d &a = footprint[std::size_t(ia)], &b = footprint[std::size_t(ib)],
                                      &c = footprint[std::size_t(ic)];
                const double turn = orient(a, b, c);
                if (turn < 0) continue;  // a reflex corner
                bool empty = true;
                for (std::size_t k = 0; k < m && empty; ++k) {
                    const int iv = left[k];
                    if (iv == ia || iv == ib || iv == ic) continue;
                    const Eigen::Vector2d& p = footprint[std::size_t(iv)];
                    empty = !(orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0);
                }
                if (!empty) continue;
                if (turn > 0) footprintTriangles.push_back({ia, ib, ic});  // a straight corner leaves no triangle
                left.erase(left.begin() + std::ptrdiff_t(i));
                cut = true;
            }
            if (!cut)
                throw std::invalid_argument(who + "footprint: the polygon could not be cut into triangles (nearly "
                                                  "degenerate corners)");
        }
        if (orient(footprint[std::size_t(left[0])], footprint[std::size_t(left[1])], footprint[std::size_t(left[2])]) > 0)
            footprintTriangles.push_back({left[0], left[1], left[2]});
        for (std::size_t i = 0; i < 2 * n; ++i) {
            const Eigen::Vector2d& p = footprint[i / 2];
            const Eigen::Vector3d w = frame.toWorldPoint(Eigen::Vector3d(p.x(), (i & 1) ? top : bottom, p.y()));
            regionMin = i == 0 ? w : Eigen::Vector3d(regionMin.cwiseMin(w));
            regionMax = i == 0 ? w : Eigen::Vector3d(regionMax.cwiseMax(w));
        }
        return;
    }
    case btWaterRegionKind::Mesh: {
        const std::size_t nv = info.meshVertices.size();
        if (nv < 4)
            throw std::invalid_argument(who + "meshVertices: a closed mesh needs at least 4 vertices (got " +
                                        std::to_string(nv) + ")");
        for (std::size_t i = 0; i < nv; ++i) {
            const btVector3& v = info.meshVertices[i];
            const Eigen::Vector3d p(double(v.x()), double(v.y()), double(v.z()));
            if (!p.allFinite()) throw std::invalid_argument(who + "meshVertices[" + std::to_string(i) + "]: must be finite");
            meshVertices.push_back(p);
            regionMin = i == 0 ? p : Eigen::Vector3d(regionMin.cwiseMin(p));
            regionMax = i == 0 ? p : Eigen::Vector3d(regionMax.cwiseMax(p));
        }
        if (info.meshTriangles.size() % 3 != 0 || info.meshTriangles.size() < 12)
            throw std::invalid_argument(who + "meshTriangles: needs 3 indices per triangle and at least 4 triangles (got " +
                                        std::to_string(info.meshTriangles.size()) + " indices)");
        // Vertices may come rounded to float (btVector3): flatness and convexity within 1e-6 of the mesh's size.
        const double size = (regionMax - regionMin).norm();
        const double tolerance = 1e-6 * (1.0 + size);
        std::map<std::pair<int, int>, int> edges;
        double volume6 = 0;
        for (std::size_t t = 0; t * 3 < info.meshTriangles.size(); ++t) {
            std::array<int, 3> tri{};
            for (int k = 0; k < 3; ++k) {
                tri[std::size_t(k)] = info.meshTriangles[3 * t + std::size_t(k)];
                if (tri[std::size_t(k)] < 0 || std::size_t(tri[std::size_t(k)]) >= nv)
                    throw std::invalid_argument(who + "meshTriangles: triangle " + std::to_string(t) + " has vertex index " +
                                                std::to_string(tri[std::size_t(k)]) + " out of range (" +
                                                std::to_string(nv) + " vertices)");
            }
            const Eigen::Vector3d &a = meshVertices[std::size_t(tri[0])], &b = meshVertices[std::size_t(tri[1])],
                                  &c = meshVertices[std::size_t(tri[2])];
            const Eigen::Vector3d normal = (b - a).cross(c - a);
            if (!(normal.norm() > 1e-12 * (1.0 + size * size)))
                throw std::invalid_argument(who + "meshTriangles: triangle " + std::to_string(t) + " has zero area");
            volume6 += a.dot(b.cross(c));
            for (int k = 0; k < 3; ++k) ++edges[{tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)]}];
            meshTriangles.push_back(tri);
        }
        for (const auto& e : edges) {
            const auto back = edges.find({e.first.second, e.first.first});
            if (e.second != 1 || back == edges.end() || back->second != 1)
                throw std::invalid_argument(who + "meshTriangles: the mesh is not closed and consistently oriented: "
                                                  "edge " + std::to_string(e.first.first) + "-" +
                                            std::to_string(e.first.second) + " is used " + std::to_string(e.second) +
                                            " times, its reverse " +
                                            std::to_string(back == edges.end() ? 0 : back->second) +
                                            " times (each edge once in each direction)");
        }
        if (!(volume6 > 0))
            throw std::invalid_argument(who + "meshTriangles: the triangles face inward (the mesh's volume is negative): "
                                              "give them counter-clockwise seen from outside");
        // Convex with few enough face planes: one piece clipped by its walls. Otherwise the mesh is taken as columns
        // along up (a stepped pool, an L-shaped lock, a lake bed): it must then meet every vertical line once at most.
        meshColumns = false;
        for (std::size_t t = 0; t < meshTriangles.size() && !meshColumns; ++t) {
            const Eigen::Vector3d &a = meshVertices[std::size_t(meshTriangles[t][0])],
                                  &b = meshVertices[std::size_t(meshTriangles[t][1])],
                                  &c = meshVertices[std::size_t(meshTriangles[t][2])];
            const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
            const double offset = normal.dot(a);
            for (std::size_t i = 0; i < nv && !meshColumns; ++i) meshColumns = normal.dot(meshVertices[i]) - offset > tolerance;
            bool known = false;
            for (std::size_t k = 0; k < meshNormals.size() && !known; ++k)
                known = meshNormals[k].dot(normal) > 1.0 - 1e-9 && std::abs(meshOffsets[k] - offset) <= tolerance;
            if (!known) {
                meshNormals.push_back(normal);
                meshOffsets.push_back(offset);
            }
        }
        if (meshNormals.size() > std::size_t(buoyancy::WaterRegion::kMaxPlanes)) meshColumns = true;
        if (!meshColumns) return;
        meshNormals.clear();
        meshOffsets.clear();
        // Each edge's other triangle (the edge map holds each directed edge once).
        std::map<std::pair<int, int>, int> owner;
        for (std::size_t t = 0; t < meshTriangles.size(); ++t)
            for (int k = 0; k < 3; ++k) owner[{meshTriangles[t][std::size_t(k)], meshTriangles[t][std::size_t((k + 1) % 3)]}] = int(t);
        meshNeighbours.assign(meshTriangles.size(), {-1, -1, -1});
        for (std::size_t t = 0; t < meshTriangles.size(); ++t)
            for (int k = 0; k < 3; ++k)
                meshNeighbours[t][std::size_t(k)] =
                    owner.at({meshTriangles[t][std::size_t((k + 1) % 3)], meshTriangles[t][std::size_t(k)]});
        // No overhang: the shadows of two top triangles seen from above do not overlap (a vertical line then meets
        // one top and, the mesh being closed, one floor).
        std::vector<std::pair<std::size_t, std::array<Eigen::Vector2d, 3>>> tops;
        for (std::size_t t = 0; t < meshTriangles.size(); ++t) {
            const FrameTriangle f = frameTriangle(*this, frame, t);
            if (f.facing > 0) tops.emplace_back(t, shadowOf(f));
        }
        const double areaTolerance = 1e-9 * (1.0 + size * size);
        for (std::size_t i = 0; i < tops.size(); ++i)
            for (std::size_t j = i + 1; j < tops.size(); ++j) {
                if (boxesApart(tops[i].second, tops[j].second)) continue;
                const double common = polygonArea(commonShadow(tops[i].second, tops[j].second));
                if (common > areaTolerance)
                    throw std::invalid_argument(
                        who + "meshTriangles: the region mesh of water body '" + name + "' overhangs: triangles " +
                        std::to_string(tops[i].first) + " and " + std::to_string(tops[j].first) +
                        " both face up and lie one above the other (" + num(common) +
                        " m^2 in common seen from above); a mesh that is not convex must meet every vertical line in "
                        "one segment at most (split it into water bodies that do)");
            }
        return;
    }
    }
    throw std::invalid_argument(who + "regionKind: not a btWaterRegionKind");
}

double btWaterBody::distanceTo(const btWaterFrame& frame, const Eigen::Vector3d& point) const {
    switch (kind) {
    case btWaterRegionKind::Box: break;
    case btWaterRegionKind::Polygon: {
        const Eigen::Vector3d q = frame.toWaterPoint(point);
        const double horizontal = footprintDistance(footprint, Eigen::Vector2d(q.x(), q.z()));
        const double vertical = std::max({0.0, bottom - q.y(), q.y() - top});
        return std::sqrt(horizontal * horizontal + vertical * vertical);
    }
    case btWaterRegionKind::Mesh: {
        bool inside = true;
        if (meshColumns) {
            // Inside: under a top triangle and over a floor triangle of the vertical line through the point.
            const Eigen::Vector3d q = frame.toWaterPoint(point);
            const Eigen::Vector2d p(q.x(), q.z());
            bool under = false, over = false;
            for (std::size_t t = 0; t < meshTriangles.size() && !(under && over); ++t) {
                const FrameTriangle f = frameTriangle(*this, frame, t);
                if (f.facing == 0 || shadowDistance(shadowOf(f), p) > 0) continue;
                if (f.facing > 0) under = under || q.y() <= f.heightAt(p);
                else over = over || q.y() >= f.heightAt(p);
            }
            inside = under && over;
        } else {
            for (std::size_t k = 0; k < meshNormals.size() && inside; ++k) inside = meshNormals[k].dot(point) <= meshOffsets[k];
        }
        if (inside) return 0.0;
        double d = std::numeric_limits<double>::infinity();
        for (const std::array<int, 3>& t : meshTriangles)
            d = std::min(d, (point - closestOnTriangle(point, meshVertices[std::size_t(t[0])],
                                                       meshVertices[std::size_t(t[1])],
                                                       meshVertices[std::size_t(t[2])])).norm());
        return d;
    }
    }
    const Eigen::Vector3d outside = (regionMin - point).cwiseMax(point - regionMax).cwiseMax(0.0);
    return outside.norm();
}

bool btWaterBody::inColumn(const btWaterFrame& frame, const Eigen::Vector3d& point, double slack) const {
    switch (kind) {
    case btWaterRegionKind::Box: {
        const Eigen::Vector3d up = frame.up();
        const int topAxis = topAxisOf(up);
        for (int k = 0; k < 3; ++k) {
            const bool skipMax = k == topAxis && up[topAxis] > 0, skipMin = k == topAxis && up[topAxis] < 0;
            if (!skipMin && !(point[k] >= regionMin[k] - slack)) return false;
            if (!skipMax && !(point[k] <= regionMax[k] + slack)) return false;
        }
        return true;
    }
    case btWaterRegionKind::Polygon: {
        const Eigen::Vector3d q = frame.toWaterPoint(point);
        return q.y() >= bottom - slack && footprintDistance(footprint, Eigen::Vector2d(q.x(), q.z())) <= slack;
    }
    case btWaterRegionKind::Mesh:
        if (meshColumns) {
            // Over a floor triangle whose shadow holds the point (within slack).
            const Eigen::Vector3d q = frame.toWaterPoint(point);
            const Eigen::Vector2d p(q.x(), q.z());
            for (std::size_t t = 0; t < meshTriangles.size(); ++t) {
                const FrameTriangle f = frameTriangle(*this, frame, t);
                if (f.facing < 0 && shadowDistance(shadowOf(f), p) <= slack && q.y() >= f.heightAt(p) - slack) return true;
            }
            return false;
        }
        for (std::size_t k = 0; k < meshNormals.size(); ++k)
            if (!isLid(frame, meshNormals[k]) && !(meshNormals[k].dot(point) <= meshOffsets[k] + slack)) return false;
        return true;
    }
    return false;
}

bool btWaterBody::withinSides(const btWaterFrame& frame, const Eigen::Vector3d& point, double slack) const {
    switch (kind) {
    case btWaterRegionKind::Box: {
        const int topAxis = topAxisOf(frame.up());
        for (int k = 0; k < 3; ++k)
            if (k != topAxis && !(point[k] >= regionMin[k] - slack && point[k] <= regionMax[k] + slack)) return false;
        return true;
    }
    case btWaterRegionKind::Polygon: {
        const Eigen::Vector3d q = frame.toWaterPoint(point);
        return footprintDistance(footprint, Eigen::Vector2d(q.x(), q.z())) <= slack;
    }
    case btWaterRegionKind::Mesh:
        if (meshColumns) {
            // Within the shadow of a top triangle (the footprint seen from above).
            const Eigen::Vector3d q = frame.toWaterPoint(point);
            for (std::size_t t = 0; t < meshTriangles.size(); ++t) {
                const FrameTriangle f = frameTriangle(*this, frame, t);
                if (f.facing > 0 && shadowDistance(shadowOf(f), Eigen::Vector2d(q.x(), q.z())) <= slack) return true;
            }
            return false;
        }
        for (std::size_t k = 0; k < meshNormals.size(); ++k)
            if (!isLid(frame, meshNormals[k]) && !isFloor(frame, meshNormals[k]) &&
                !(meshNormals[k].dot(point) <= meshOffsets[k] + slack))
                return false;
        return true;
    }
    return false;
}

bool btWaterBody::sphereWithinSides(const btWaterFrame& frame, const Eigen::Vector3d& centre, double radius) const {
    switch (kind) {
    case btWaterRegionKind::Box: {
        const int topAxis = topAxisOf(frame.up());
        for (int k = 0; k < 3; ++k) {
            if (k == topAxis) continue;
            if (!(centre[k] - radius >= regionMin[k])) return false;
            if (!(centre[k] + radius <= regionMax[k])) return false;
        }
        return true;
    }
    case btWaterRegionKind::Polygon: {
        const Eigen::Vector3d q = frame.toWaterPoint(centre);
        const Eigen::Vector2d p(q.x(), q.z());
        return insidePolygon(footprint, p) && boundaryDistance(footprint, p) >= radius;
    }
    case btWaterRegionKind::Mesh:
        if (meshColumns) {
            // The centre in the footprint, and the footprint's outline (the top triangles' edges whose other triangle
            // is not a top) at least a radius away.
            const Eigen::Vector3d q = frame.toWaterPoint(centre);
            const Eigen::Vector2d p(q.x(), q.z());
            bool inFootprint = false;
            for (std::size_t t = 0; t < meshTriangles.size(); ++t) {
                const FrameTriangle f = frameTriangle(*this, frame, t);
                if (f.facing <= 0) continue;
                inFootprint = inFootprint || shadowDistance(shadowOf(f), p) == 0.0;
                for (int k = 0; k < 3; ++k) {
                    const std::size_t other = std::size_t(meshNeighbours[t][std::size_t(k)]);
                    if (frameTriangle(*this, frame, other).facing > 0) continue;
                    if (!(segmentDistance(p, f.flat(k), f.flat((k + 1) % 3)) >= radius)) return false;
                }
            }
            return inFootprint;
        }
        for (std::size_t k = 0; k < meshNormals.size(); ++k)
            if (!isLid(frame, meshNormals[k]) && !isFloor(frame, meshNormals[k]) &&
                !(meshNormals[k].dot(centre) + radius <= meshOffsets[k]))
                return false;
        return true;
    }
    return false;
}

void btWaterBody::appendWaterRegions(const btWaterFrame& frame, std::vector<buoyancy::WaterRegion>& out) const {
    buoyancy::WaterRegion region;
    region.water = surface;
    region.fluidDensity = fluidDensity;
    const auto addWorldPlane = [&](const Eigen::Vector3d& normal, const Eigen::Vector3d& onPlane) {
        const int i = region.planeCount++;
        region.normal[i] = frame.toWaterVector(normal);
        region.offset[i] = region.normal[i].dot(frame.toWaterPoint(onPlane));
    };
    switch (kind) {
    case btWaterRegionKind::Box: {
        // The box's sides: n · p ≤ n · (a point of the face), the world's normal and point mapped into the frame.
        const int topAxis = topAxisOf(frame.up());
        for (int k = 0; k < 3; ++k)
            for (const double side : {-1.0, 1.0}) {
                if (k == topAxis) continue;  // the top and the bottom
                addWorldPlane(side * Eigen::Vector3d::Unit(k), side > 0 ? regionMax : regionMin);
            }
        out.push_back(region);
        return;
    }
    case btWaterRegionKind::Polygon:
        // One vertical prism per footprint triangle: its three sides, already in the water frame.
        for (const std::array<int, 3>& t : footprintTriangles) {
            setPrismSides(region, {footprint[std::size_t(t[0])], footprint[std::size_t(t[1])], footprint[std::size_t(t[2])]});
            out.push_back(region);
        }
        return;
    case btWaterRegionKind::Mesh:
        if (meshColumns) {
            // One vertical prism per top triangle's shadow (they tile the footprint): its three sides.
            for (std::size_t t = 0; t < meshTriangles.size(); ++t) {
                const FrameTriangle f = frameTriangle(*this, frame, t);
                if (f.facing <= 0) continue;
                setPrismSides(region, shadowOf(f));
                out.push_back(region);
            }
            return;
        }
        // The tank's walls: every face plane but its flat lid and floor.
        for (std::size_t k = 0; k < meshNormals.size(); ++k)
            if (!isLid(frame, meshNormals[k]) && !isFloor(frame, meshNormals[k]))
                addWorldPlane(meshNormals[k], meshOffsets[k] * meshNormals[k]);
        out.push_back(region);
        return;
    }
}

bool btWaterBody::overlaps(const btWaterBody& other, const btWaterFrame& frame) const {
    if (kind == btWaterRegionKind::Box && other.kind == btWaterRegionKind::Box)
        // Boxes overlap when their open interiors meet on every axis (touching faces are accepted).
        return (regionMin.array() < other.regionMax.array()).all() && (other.regionMin.array() < regionMax.array()).all();
    // The pieces in the frame in use (a footprint is in water coordinates: its world bounding box may be older).
    const std::vector<ConvexPiece> mine = convexPieces(*this, frame), theirs = convexPieces(other, frame);
    const auto bounds = [](const ConvexPiece& piece, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
        lo = hi = piece.vertices.front();
        for (const Eigen::Vector3d& v : piece.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
    };
    std::vector<Eigen::Vector3d> lo(theirs.size()), hi(theirs.size());
    double size = 0;
    for (std::size_t j = 0; j < theirs.size(); ++j) {
        bounds(theirs[j], lo[j], hi[j]);
        size = std::max(size, (hi[j] - lo[j]).norm());
    }
    for (const ConvexPiece& a : mine) {
        Eigen::Vector3d alo, ahi;
        bounds(a, alo, ahi);
        size = std::max(size, (ahi - alo).norm());
    }
    const double tolerance = 1e-9 * (1.0 + size);
    for (const ConvexPiece& a : mine) {
        Eigen::Vector3d alo, ahi;
        bounds(a, alo, ahi);
        for (std::size_t j = 0; j < theirs.size(); ++j) {
            // Pieces whose bounding boxes are apart or only touch are apart.
            if (!((alo.array() < hi[j].array() - tolerance).all() && (lo[j].array() < ahi.array() - tolerance).all()))
                continue;
            if (piecesOverlap(a, theirs[j], tolerance)) return true;
        }
    }
    return false;
}

void btWaterBody::footprintBounds(const btWaterFrame& frame, double& x0, double& x1, double& z0, double& z1) const {
    bool first = true;
    const auto add = [&](const Eigen::Vector3d& q) {
        x0 = first ? q.x() : std::min(x0, q.x());
        x1 = first ? q.x() : std::max(x1, q.x());
        z0 = first ? q.z() : std::min(z0, q.z());
        z1 = first ? q.z() : std::max(z1, q.z());
        first = false;
    };
    switch (kind) {
    case btWaterRegionKind::Box:
        for (int corner = 0; corner < 8; ++corner)
            add(frame.toWaterPoint(Eigen::Vector3d((corner & 1) ? regionMax.x() : regionMin.x(),
                                                   (corner & 2) ? regionMax.y() : regionMin.y(),
                                                   (corner & 4) ? regionMax.z() : regionMin.z())));
        break;
    case btWaterRegionKind::Polygon:
        for (const Eigen::Vector2d& p : footprint) add(Eigen::Vector3d(p.x(), 0, p.y()));
        break;
    case btWaterRegionKind::Mesh:
        for (const Eigen::Vector3d& v : meshVertices) add(frame.toWaterPoint(v));
        break;
    }
    if (first) x0 = x1 = z0 = z1 = 0;
}

std::string btWaterBody::regionText() const {
    switch (kind) {
    case btWaterRegionKind::Box: break;
    case btWaterRegionKind::Polygon:
        return "polygon of " + std::to_string(footprint.size()) + " corners, bottom " + num(bottom) + ", top " + num(top);
    case btWaterRegionKind::Mesh: return "mesh of " + std::to_string(meshTriangles.size()) + " triangles";
    }
    return cornerText(regionMin) + " to " + cornerText(regionMax);
}
