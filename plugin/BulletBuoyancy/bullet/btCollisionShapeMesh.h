#pragma once
/// @file btCollisionShapeMesh.h
/// The closed triangle mesh of a Bullet collision shape, in the shape's own frame (for a rigid body: its
/// centre-of-mass frame), so a body made with the user's own btBoxShape, btSphereShape, btConvexHullShape, …
/// floats with the geometry it collides with (design.md 8.3).
///
/// The geometric shape is used, not Bullet's margin-inflated one: boxes and cylinders keep their margin inside
/// their extents, spheres and capsules are their radius, and hulls and cones are their points (Bullet would
/// add its 0.04 m margin around them: +24 % volume on a 1 m cube hull). Local scaling is the one Bullet applies
/// (each shape's own getters). Flat-faced shapes are exact; curved ones (sphere, capsule, cylinder, cone) are
/// inscribed polyhedra whose volume is within `curvedShapeTolerance` of the shape's (checked against the closed
/// form while tessellating).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <string>

class btCollisionShape;

/// Mesh of `shape` in its own frame, m. Supported: btBoxShape, btSphereShape, btCapsuleShape (X, Y, Z),
/// btCylinderShape (X, Y, Z), btConeShape (X, Y, Z), btConvexHullShape, btMultiSphereShape (the convex hull of its
/// spheres, as Bullet collides it), btConvexTriangleMeshShape and btGImpactMeshShape when their triangles are closed
/// (the mesh itself, not its hull), and btCompoundShape of those (children with their transforms, nested; children
/// must not overlap). btBvhTriangleMeshShape is refused: Bullet moves it only as a static body.
/// @param curvedShapeTolerance  the largest relative volume error of a curved shape's tessellation, in (0, 0.1]
/// @throws std::invalid_argument naming the shape type for a shape that is not supported (a static plane, a height
///         field, a triangle mesh, …) or a negative or zero local scaling
buoyancy::TriangleMesh btCollisionShapeToMesh(const btCollisionShape& shape, double curvedShapeTolerance);
