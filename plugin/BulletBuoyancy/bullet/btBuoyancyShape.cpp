#include <BulletBuoyancy/bullet/btBuoyancyShape.h>

#include <BulletBuoyancy/bullet/btCollisionShapeMesh.h>
#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <BulletBuoyancy/atlas/UvLayout.h>
#include <BulletBuoyancy/bake/BakeSamples.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace {

/// Drag/shell samples for the ExactMesh method: each triangle split into n×n congruent sub-triangles
/// (n from its longest edge / targetEdge, 1..64), one sample per sub-triangle at its centroid with area
/// vector A_tri / n². A box's 12 triangles alone would leave whole rotation axes undamped.
buoyancy::SurfaceSamples faceSamples(const buoyancy::TriangleMesh& mesh, double targetEdge) {
    auto splits = [&](std::size_t t) {
        const Eigen::Vector3d& a = mesh.corner(t, 0);
        const Eigen::Vector3d& b = mesh.corner(t, 1);
        const Eigen::Vector3d& c = mesh.corner(t, 2);
        const double e = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        return static_cast<int>(std::clamp(std::ceil(e / targetEdge), 1.0, 64.0));
    };
    // Keep the count moderate: at most ≈ 16384 samples beyond one per triangle.
    for (int pass = 0; pass < 20; ++pass) {
        std::size_t total = 0;
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) total += std::size_t(splits(t)) * splits(t);
        if (total <= std::max<std::size_t>(16384, mesh.triangleCount())) break;
        targetEdge *= 1.5;
    }
    buoyancy::SurfaceSamples s;
    s.texture_size = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Eigen::Vector3d& a = mesh.corner(t, 0);
        const Eigen::Vector3d& b = mesh.corner(t, 1);
        const Eigen::Vector3d& c = mesh.corner(t, 2);
        const int n = splits(t);
        const Eigen::Vector3d A = 0.5 * (b - a).cross(c - a) / double(n * n);
        const double area = A.norm();
        const Eigen::Vector3d du = (b - a) / double(n), dv = (c - a) / double(n);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; i + j < n; ++j) {
                // Upward sub-triangle (i,j),(i+1,j),(i,j+1): centroid at (i+1/3, j+1/3).
                Eigen::Vector3d p = a + (i + 1.0 / 3.0) * du + (j + 1.0 / 3.0) * dv;
                s.push(p.x(), p.y(), p.z(), A.x(), A.y(), A.z(), area, 0u, static_cast<std::uint32_t>(t));
                if (i + j < n - 1) {
                    // Downward sub-triangle (i+1,j),(i,j+1),(i+1,j+1): centroid at (i+2/3, j+2/3).
                    p = a + (i + 2.0 / 3.0) * du + (j + 2.0 / 3.0) * dv;
                    s.push(p.x(), p.y(), p.z(), A.x(), A.y(), A.z(), area, 0u, static_cast<std::uint32_t>(t));
                }
            }
        }
    }
    return s;
}

bool finite(const buoyancy::MassProperties& m) {
    return std::isfinite(m.mass) && std::isfinite(m.volume) && m.centre.allFinite() && m.inertia.allFinite();
}

}  // namespace

std::shared_ptr<const btBuoyancyShape> btBuoyancyShape::fromCollisionShape(const btCollisionShape& shape,
                                                                           const btBuoyancySettings& settings) {
    settings.validate();
    std::shared_ptr<const btBuoyancyShape> made = create(btCollisionShapeToMesh(shape, settings.curvedShapeTolerance), settings);
    // Not shared with anyone yet: the one place a shape is completed after create().
    if (shape.getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
        std::const_pointer_cast<btBuoyancyShape>(made)->m_sphereRadius =
            double(static_cast<const btSphereShape&>(shape).getRadius());
    } else if (shape.getShapeType() == BOX_SHAPE_PROXYTYPE) {
        // The same extents btCollisionShapeToMesh built the mesh from (Bullet keeps the margin inside them).
        const btVector3 h = static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin();
        std::const_pointer_cast<btBuoyancyShape>(made)->m_boxHalfExtents =
            Eigen::Vector3d(double(h.x()), double(h.y()), double(h.z()));
    } else if (shape.getShapeType() == CAPSULE_SHAPE_PROXYTYPE) {
        // The same dimensions btCollisionShapeToMesh tessellated (local scaling included, as Bullet applies it).
        const auto& capsule = static_cast<const btCapsuleShape&>(shape);
        auto* completed = std::const_pointer_cast<btBuoyancyShape>(made).get();
        completed->m_capsuleRadius = double(capsule.getRadius());
        completed->m_capsuleHalfHeight = double(capsule.getHalfHeight());
        completed->m_capsuleAxis = capsule.getUpAxis();
    }
    return made;
}

std::shared_ptr<const btBuoyancyShape> btBuoyancyShape::create(buoyancy::TriangleMesh mesh,
                                                               const btBuoyancySettings& settings) {
    settings.validate();
    if (mesh.triangleCount() == 0) throw std::invalid_argument("mesh: no triangles");
    // A mesh that did not go through prepareMesh must not crash us: indices and coordinates.
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k)
            if (mesh.triangles[t][k] < 0 || std::size_t(mesh.triangles[t][k]) >= mesh.vertices.size())
                throw std::invalid_argument("mesh: triangle " + std::to_string(t) + " has vertex index " +
                                            std::to_string(mesh.triangles[t][k]) + " out of range (" +
                                            std::to_string(mesh.vertices.size()) + " vertices)");
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (!mesh.vertices[v].allFinite())
            throw std::invalid_argument("mesh: vertex " + std::to_string(v) + " is not finite");
    // The command line's checks, on every mesh: closed, oriented, outward, a positive volume.
    buoyancy::MeshReport report;
    try {
        buoyancy::PrepareMeshOptions options;
        options.acceptTouchingParts = true;  // what a repair accepted (MeshRepair.h)
        report = buoyancy::prepareMesh(mesh, "mesh", options);
    } catch (const buoyancy::MeshError& e) {
        throw std::invalid_argument(e.what());
    }
    std::shared_ptr<btBuoyancyShape> shape(new btBuoyancyShape());
    shape->m_meshWarnings = std::move(report.warnings);
    shape->m_method = btBuoyancyResolveMethod(settings, mesh.triangleCount());
    shape->m_mesh = std::move(mesh);
    const buoyancy::TriangleMesh& m = shape->m_mesh;

    Eigen::Vector3d lo = m.vertices.front(), hi = m.vertices.front();
    for (const Eigen::Vector3d& v : m.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    shape->m_boundsCentre = 0.5 * (lo + hi);
    for (const Eigen::Vector3d& v : m.vertices)
        shape->m_boundsRadius = std::max(shape->m_boundsRadius, (v - shape->m_boundsCentre).norm());

    shape->m_faceSamples = faceSamples(m, std::max(2.0 * shape->m_boundsRadius / 16.0, 1e-9));
    if (shape->m_method == btBuoyancyMethod::ExactMesh) {
        shape->m_unitSolid = buoyancy::polyhedronMassProperties(m, 1.0);
        shape->m_tree = buoyancy::buildMeshMomentTree(m);  // closed-form wet nodes (design.md 2.5)
        // Shell from point masses on the sub-triangles (their own small inertia neglected).
        shape->m_unitShell = buoyancy::shellMassProperties(shape->m_faceSamples, 1.0, 1.0);
    } else {
        const buoyancy::BakeMethod bake = shape->m_method == btBuoyancyMethod::TexelCentre
                                              ? buoyancy::BakeMethod::TexelCentre
                                              : buoyancy::BakeMethod::ExactCoverage;
        const int n = btBuoyancyResolveTextureSize(settings, shape->m_method);
        const buoyancy::UvLayout layout = buoyancy::chooseUvLayout(m, n, settings.preferModelUvs);
        shape->m_uvGenerated = layout.generated;
        shape->m_uvProblems = layout.reasons;
        shape->m_samples = buoyancy::bakeSurfaceSamples(m, layout.corner_uvs, n, bake);
        if (shape->m_samples.size() == 0) throw std::invalid_argument("mesh: baking produced no samples");
        // Mass properties from the same samples as the buoyancy (design.md 2.1), so ρ_body = ρ_w is neutral.
        shape->m_unitSolid = buoyancy::solidMassProperties(shape->m_samples, 1.0);
        shape->m_unitShell = buoyancy::shellMassProperties(shape->m_samples, 1.0, 1.0);
    }
    if (!finite(shape->m_unitSolid) || !(shape->m_unitSolid.volume > 0.0))
        throw std::invalid_argument("mesh: encloses no positive volume (" + std::to_string(shape->m_unitSolid.volume) +
                                    " m^3); is it closed and outward?");
    return shape;
}
