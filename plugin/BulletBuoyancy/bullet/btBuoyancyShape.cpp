#include <BulletBuoyancy/bullet/btBuoyancyShape.h>

#include <BulletBuoyancy/bullet/btCollisionShapeMesh.h>
#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace {

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
    shape->m_integration = &buoyancy::integrationMethod(btBuoyancyResolveMethod(settings, mesh.triangleCount()));
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

    buoyancy::PrepareOptions options;
    options.textureSize = shape->m_integration->sampled ? btBuoyancyResolveTextureSize(settings, shape->getMethod()) : 0;
    options.preferModelUvs = settings.preferModelUvs;
    options.boundsRadius = shape->m_boundsRadius;
    shape->m_integration->prepare(m, options, shape->m_prepared);
    if (!finite(shape->m_prepared.unitSolid) || !(shape->m_prepared.unitSolid.volume > 0.0))
        throw std::invalid_argument("mesh: encloses no positive volume (" + std::to_string(shape->m_prepared.unitSolid.volume) +
                                    " m^3); is it closed and outward?");
    return shape;
}
