#include <BulletBuoyancy/bullet/btCollisionShapeMesh.h>

#include <BulletBuoyancy/bullet/btConvexHullMesh.h>

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btMultiSphereShape.h>
#include <BulletCollision/CollisionShapes/btStridingMeshInterface.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Finest tessellation tried for a curved shape (segments around its axis).
constexpr int kMaxSegments = 4096;

/// Signed volume of a closed triangle mesh, m³ (divergence theorem: Σ v0 · (v1 × v2) / 6).
double signedVolume(const buoyancy::TriangleMesh& m) {
    double v = 0;
    for (const auto& t : m.triangles)
        v += m.vertices[std::size_t(t[0])].dot(m.vertices[std::size_t(t[1])].cross(m.vertices[std::size_t(t[2])]));
    return v / 6.0;
}

/// Turn every triangle over when the mesh encloses a negative volume (outward normals wanted).
void makeOutward(buoyancy::TriangleMesh& m) {
    if (signedVolume(m) < 0)
        for (auto& t : m.triangles) std::swap(t[1], t[2]);
}

/// The surface of revolution about +y of a profile (r_i, y_i) going from one end of the axis to the other
/// (r = 0 at an end closes it with a pole; r > 0 at an end closes it with a flat disc), `segments` around.
buoyancy::TriangleMesh revolve(const std::vector<std::pair<double, double>>& profile, int segments) {
    buoyancy::TriangleMesh m;
    std::vector<int> first(profile.size());  // index of the first vertex of each profile point's ring (or pole)
    for (std::size_t i = 0; i < profile.size(); ++i) {
        first[i] = int(m.vertices.size());
        const auto [r, y] = profile[i];
        if (r <= 0) {
            m.vertices.emplace_back(0.0, y, 0.0);
            continue;
        }
        for (int k = 0; k < segments; ++k) {
            const double a = 2.0 * kPi * k / segments;
            m.vertices.emplace_back(r * std::cos(a), y, r * std::sin(a));
        }
    }
    auto ring = [&](std::size_t i, int k) { return profile[i].first <= 0 ? first[i] : first[i] + (k % segments); };
    // Between profile points i and i + 1: a band of quads (two triangles each), or a fan where one end is a pole.
    for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
        const bool pole0 = profile[i].first <= 0, pole1 = profile[i + 1].first <= 0;
        if (pole0 && pole1) throw std::logic_error("revolve: two poles in a row");
        for (int k = 0; k < segments; ++k) {
            const int a = ring(i, k), b = ring(i, k + 1), c = ring(i + 1, k), d = ring(i + 1, k + 1);
            if (pole0) {
                m.triangles.push_back({a, d, c});
            } else if (pole1) {
                m.triangles.push_back({a, b, d});
            } else {
                m.triangles.push_back({a, b, d});
                m.triangles.push_back({a, d, c});
            }
        }
    }
    // Flat ends (r > 0 at the first or the last profile point): a fan around a centre vertex, wound against the
    // band next to it so that every edge is used once each way.
    if (profile.front().first > 0) {
        const int centre = int(m.vertices.size());
        m.vertices.emplace_back(0.0, profile.front().second, 0.0);
        for (int k = 0; k < segments; ++k) m.triangles.push_back({centre, ring(0, k + 1), ring(0, k)});
    }
    if (profile.back().first > 0) {
        const std::size_t end = profile.size() - 1;
        const int centre = int(m.vertices.size());
        m.vertices.emplace_back(0.0, profile.back().second, 0.0);
        for (int k = 0; k < segments; ++k) m.triangles.push_back({centre, ring(end, k), ring(end, k + 1)});
    }
    return m;
}

/// A quarter circle's profile points from angle a0 to a1 (radians, measured from the axis' equator) on a circle of
/// radius r centred at height yc on the axis, `steps` chords.
void arc(std::vector<std::pair<double, double>>& p, double r, double yc, double a0, double a1, int steps) {
    for (int s = 0; s <= steps; ++s) {
        const double a = a0 + (a1 - a0) * s / steps;
        p.emplace_back(r * std::cos(a), yc + r * std::sin(a));
    }
}

/// A curved shape tessellated about +y at increasing resolution until its volume is within `tolerance` of the
/// closed form `exactVolume` (the polyhedra are inscribed: their volume is below the shape's).
template <class Profile>
buoyancy::TriangleMesh tessellate(const char* what, double exactVolume, double tolerance, Profile profile) {
    // The deficit of an inscribed polyhedron falls like 1/n² with n segments around: from each measured deficit
    // the next n is the one that should just meet the tolerance (a multiple of 4, so quarter arcs have whole steps).
    int segments = 16;
    for (;;) {
        buoyancy::TriangleMesh m = revolve(profile(segments), segments);
        makeOutward(m);  // revolve() is consistent; which way it faces depends on the profile's direction
        const double deficit = (exactVolume - signedVolume(m)) / exactVolume;
        if (deficit <= tolerance) return m;
        if (segments >= kMaxSegments)
            throw std::invalid_argument(std::string(what) + ": cannot reach curvedShapeTolerance " +
                                        std::to_string(tolerance) + " with " + std::to_string(kMaxSegments) +
                                        " segments");
        const double wanted = segments * std::sqrt(deficit / tolerance) * 1.02;
        segments = std::min(kMaxSegments, std::max(segments + 4, 4 * int(std::ceil(wanted / 4.0))));
    }
}

/// Rotate a mesh built about +y so that its axis becomes `axis` (0 = x, 1 = y, 2 = z); rotations keep it outward.
void axisFromY(buoyancy::TriangleMesh& m, int axis) {
    if (axis == 1) return;
    for (auto& v : m.vertices) {
        const Eigen::Vector3d p = v;
        if (axis == 0) v = Eigen::Vector3d(p.y(), -p.x(), p.z());  // −90° about z: +y → +x
        else v = Eigen::Vector3d(p.x(), -p.z(), p.y());            // +90° about x: +y → +z
    }
}

void requirePositiveScaling(const btCollisionShape& shape) {
    const btVector3 s = shape.getLocalScaling();
    if (!(s.x() > 0 && s.y() > 0 && s.z() > 0))
        throw std::invalid_argument(std::string(shape.getName()) + ": local scaling (" + std::to_string(double(s.x())) +
                                    ", " + std::to_string(double(s.y())) + ", " + std::to_string(double(s.z())) +
                                    ") must be positive on every axis");
}

buoyancy::TriangleMesh sphereMesh(double r, double tolerance) {
    const double exact = 4.0 / 3.0 * kPi * r * r * r;
    return tessellate("btSphereShape", exact, tolerance, [r](int segments) {
        std::vector<std::pair<double, double>> p;
        arc(p, r, 0.0, -kPi / 2, kPi / 2, std::max(2, segments / 2));
        p.front().first = 0;
        p.back().first = 0;
        return p;
    });
}

buoyancy::TriangleMesh capsuleMesh(double r, double halfHeight, double tolerance) {
    const double exact = kPi * r * r * (2.0 * halfHeight + 4.0 / 3.0 * r);
    return tessellate("btCapsuleShape", exact, tolerance, [r, halfHeight](int segments) {
        std::vector<std::pair<double, double>> p;
        const int quarter = std::max(1, segments / 4);
        arc(p, r, -halfHeight, -kPi / 2, 0.0, quarter);
        arc(p, r, halfHeight, 0.0, kPi / 2, quarter);
        p.front().first = 0;
        p.back().first = 0;
        return p;
    });
}

buoyancy::TriangleMesh cylinderMesh(double r, double halfHeight, double tolerance) {
    const double exact = kPi * r * r * 2.0 * halfHeight;
    return tessellate("btCylinderShape", exact, tolerance, [r, halfHeight](int) {
        return std::vector<std::pair<double, double>>{{r, -halfHeight}, {r, halfHeight}};
    });
}

buoyancy::TriangleMesh coneMesh(double r, double height, double tolerance) {
    // Bullet's cone: its origin at mid-height, the apex at +height/2 along the axis, the base at −height/2.
    const double exact = kPi * r * r * height / 3.0;
    return tessellate("btConeShape", exact, tolerance, [r, height](int) {
        return std::vector<std::pair<double, double>>{{r, -0.5 * height}, {0.0, 0.5 * height}};
    });
}

buoyancy::TriangleMesh hullMesh(const btConvexHullShape& hull) {
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < hull.getNumPoints(); ++i) {
        const btVector3 p = hull.getScaledPoint(i);
        points.emplace_back(double(p.x()), double(p.y()), double(p.z()));
    }
    return btConvexHullMesh(points, "btConvexHullShape");
}

/// btMultiSphereShape: the convex hull of its spheres, as Bullet collides it. Bullet scales each sphere's centre and
/// radius by the local scaling per axis (a sphere becomes an ellipsoid under non-uniform scaling): the tessellated
/// sphere points are scaled the same way before the hull is taken. Each sphere is tessellated to the tolerance, so
/// the hull of the inscribed polyhedra falls short of the hull of the spheres by about as much.
buoyancy::TriangleMesh multiSphereMesh(const btMultiSphereShape& shape, double tolerance) {
    const btVector3 scale = shape.getLocalScaling();
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < shape.getSphereCount(); ++i) {
        const double r = double(shape.getSphereRadius(i));
        if (!(r > 0)) throw std::invalid_argument("btMultiSphereShape: sphere " + std::to_string(i) + " has radius " +
                                                  std::to_string(r) + " (must be positive)");
        const btVector3& c = shape.getSpherePosition(i);
        for (const Eigen::Vector3d& v : sphereMesh(r, tolerance).vertices)
            points.emplace_back(double(scale.x()) * (double(c.x()) + v.x()), double(scale.y()) * (double(c.y()) + v.y()),
                                double(scale.z()) * (double(c.z()) + v.z()));
    }
    return btConvexHullMesh(points, "btMultiSphereShape");
}

/// The triangles of a striding mesh (btConvexTriangleMeshShape, btGImpactMeshShape), scaled as Bullet scales them
/// (the mesh interface holds the shape's local scaling). Corners are welded and the mesh checked later
/// (btBuoyancyShape::create): an open mesh is refused there.
buoyancy::TriangleMesh stridingMesh(const btStridingMeshInterface& mesh) {
    struct Collect : btInternalTriangleIndexCallback {
        buoyancy::TriangleMesh m;
        void internalProcessTriangleIndex(btVector3* triangle, int, int) override {
            const int base = int(m.vertices.size());
            for (int k = 0; k < 3; ++k)
                m.vertices.emplace_back(double(triangle[k].x()), double(triangle[k].y()), double(triangle[k].z()));
            m.triangles.emplace_back(base, base + 1, base + 2);
        }
    } collect;
    const btScalar big = btScalar(BT_LARGE_FLOAT);
    mesh.InternalProcessAllTriangles(&collect, btVector3(-big, -big, -big), btVector3(big, big, big));
    return collect.m;
}

/// A triangle mesh shape's triangles must enclose a volume: welded and checked here so that the message names the
/// shape ("btGImpactMeshShape: open surface: 4 boundary edges").
buoyancy::TriangleMesh closedTriangleMesh(buoyancy::TriangleMesh m, const char* what) {
    if (m.triangles.empty()) throw std::invalid_argument(std::string(what) + ": no triangles");
    try {
        buoyancy::prepareMesh(m, what);
    } catch (const buoyancy::MeshError& e) {
        throw std::invalid_argument(std::string(e.what()) + " (a triangle mesh shape must be closed to float)");
    }
    return m;
}

void append(buoyancy::TriangleMesh& into, const buoyancy::TriangleMesh& part, const btTransform& t) {
    const int offset = int(into.vertices.size());
    for (const auto& v : part.vertices) {
        const btVector3 w = t * btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
        into.vertices.emplace_back(double(w.x()), double(w.y()), double(w.z()));
    }
    for (const auto& tr : part.triangles) into.triangles.push_back({tr[0] + offset, tr[1] + offset, tr[2] + offset});
}

buoyancy::TriangleMesh meshOf(const btCollisionShape& shape, double tolerance) {
    requirePositiveScaling(shape);
    switch (shape.getShapeType()) {
    case BOX_SHAPE_PROXYTYPE: {
        const btVector3 h = static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin();
        return buoyancy::makeBoxMesh(2.0 * double(h.x()), 2.0 * double(h.y()), 2.0 * double(h.z()));
    }
    case SPHERE_SHAPE_PROXYTYPE:
        return sphereMesh(double(static_cast<const btSphereShape&>(shape).getRadius()), tolerance);
    case CAPSULE_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btCapsuleShape&>(shape);
        buoyancy::TriangleMesh m = capsuleMesh(double(c.getRadius()), double(c.getHalfHeight()), tolerance);
        axisFromY(m, c.getUpAxis());
        return m;
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btCylinderShape&>(shape);
        const int axis = c.getUpAxis();
        buoyancy::TriangleMesh m =
            cylinderMesh(double(c.getRadius()), double(c.getHalfExtentsWithMargin()[axis]), tolerance);
        axisFromY(m, axis);
        return m;
    }
    case CONE_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btConeShape&>(shape);
        buoyancy::TriangleMesh m = coneMesh(double(c.getRadius()), double(c.getHeight()), tolerance);
        axisFromY(m, c.getConeUpIndex());
        return m;
    }
    case CONVEX_HULL_SHAPE_PROXYTYPE:
        return hullMesh(static_cast<const btConvexHullShape&>(shape));
    case MULTI_SPHERE_SHAPE_PROXYTYPE:
        return multiSphereMesh(static_cast<const btMultiSphereShape&>(shape), tolerance);
    case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE: {
        const btStridingMeshInterface* mesh = static_cast<const btConvexTriangleMeshShape&>(shape).getMeshInterface();
        if (!mesh) throw std::invalid_argument("btConvexTriangleMeshShape: no mesh");
        return closedTriangleMesh(stridingMesh(*mesh), "btConvexTriangleMeshShape");
    }
    case GIMPACT_SHAPE_PROXYTYPE: {
        const auto& g = static_cast<const btGImpactShapeInterface&>(shape);
        if (g.getGImpactShapeType() != CONST_GIMPACT_TRIMESH_SHAPE)
            throw std::invalid_argument(std::string(shape.getName()) +
                                        ": only btGImpactMeshShape is supported among the GImpact shapes");
        const btStridingMeshInterface* mesh = static_cast<const btGImpactMeshShape&>(shape).getMeshInterface();
        if (!mesh) throw std::invalid_argument("btGImpactMeshShape: no mesh");
        return closedTriangleMesh(stridingMesh(*mesh), "btGImpactMeshShape");
    }
    case TRIANGLE_MESH_SHAPE_PROXYTYPE:
        throw std::invalid_argument("btBvhTriangleMeshShape: Bullet uses it for static bodies only; for a dynamic "
                                    "body give the same mesh as a btGImpactMeshShape or a btConvexHullShape");
    case COMPOUND_SHAPE_PROXYTYPE: {
        const auto& c = static_cast<const btCompoundShape&>(shape);
        if (c.getNumChildShapes() == 0) throw std::invalid_argument("btCompoundShape: no children");
        buoyancy::TriangleMesh m;
        for (int i = 0; i < c.getNumChildShapes(); ++i) {
            const btCollisionShape* child = c.getChildShape(i);
            if (!child) throw std::invalid_argument("btCompoundShape: child " + std::to_string(i) + " is null");
            append(m, meshOf(*child, tolerance), c.getChildTransform(i));
        }
        // Overlapping children would count the volume they share twice: refuse them (prepareMesh finds them).
        buoyancy::TriangleMesh check = m;
        const buoyancy::MeshReport report = buoyancy::prepareMesh(check, "btCompoundShape");
        for (const auto& w : report.warnings)
            if (w.message.find("intersect") != std::string::npos)
                throw std::invalid_argument(w.message + "; give the compound children that do not overlap");
        if (report.cavities > 0)
            throw std::invalid_argument("btCompoundShape: a child lies inside another: its volume would not count; "
                                        "give the compound children that do not overlap");
        return m;
    }
    default:
        throw std::invalid_argument(std::string(shape.getName()) +
                                    ": not supported for buoyancy (supported: btBoxShape, btSphereShape, btCapsuleShape, "
                                    "btCylinderShape, btConeShape, btConvexHullShape, btMultiSphereShape, closed "
                                    "btConvexTriangleMeshShape and btGImpactMeshShape, and btCompoundShape of those; "
                                    "give a closed mesh through btBuoyancyShape::create instead)");
    }
}

}  // namespace

buoyancy::TriangleMesh btCollisionShapeToMesh(const btCollisionShape& shape, double curvedShapeTolerance) {
    if (!(curvedShapeTolerance > 0 && curvedShapeTolerance <= 0.1))
        throw std::invalid_argument("curvedShapeTolerance: must be in (0, 0.1] (got " + std::to_string(curvedShapeTolerance) + ")");
    return meshOf(shape, curvedShapeTolerance);
}
