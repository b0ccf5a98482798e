#pragma once
/// @file btBuoyancyShape.h
/// The immutable, shareable buoyancy data of one mesh: the mesh, its surface samples (sampled methods),
/// the per-face drag samples, and its unit-density dry mass properties. Bodies that use the same mesh at
/// the same settings share one instance through std::shared_ptr.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/integrals/IntegrationMethod.h>
#include <BulletBuoyancy/integrals/MassProperties.h>
#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

class btCollisionShape;

/// Shared per-mesh buoyancy data (immutable once created).
class btBuoyancyShape {
public:
    /// Build the shape: resolve the method (btBuoyancyResolveMethod) and let it prepare the mesh once
    /// (buoyancy::IntegrationMethod::prepare: the UV layout and baked samples of a sampled method, the moment tree
    /// and face samples of exact-mesh), with unit-density mass properties from the same data the buoyancy integrals
    /// use (so a body of the fluid's density is exactly neutral).
    /// The mesh goes through the checks of the command line first (prepareMesh: finite, closed, consistently
    /// oriented, enclosing a positive volume; duplicate vertices welded, degenerate triangles dropped, an inside-out
    /// component turned outward, each with a warning in getMeshWarnings()), so no shape can be built from an open
    /// mesh; a mesh that already passed prepareMesh is kept as it is.
    /// @param mesh      closed, outward mesh in its own frame, m
    /// @param settings  validated here
    /// @throws std::invalid_argument for bad settings, or with prepareMesh's message for a mesh that fails the
    ///         checks (e.g. "mesh: open surface: 2 boundary edges ...")
    static std::shared_ptr<const btBuoyancyShape> create(buoyancy::TriangleMesh mesh,
                                                         const btBuoyancySettings& settings = btBuoyancySettings());
    /// The shape of a Bullet collision shape, in its own frame (a rigid body's centre-of-mass frame): its geometric
    /// shape, not Bullet's margin-inflated one; curved shapes tessellated to settings.curvedShapeTolerance
    /// (btCollisionShapeToMesh has the supported types).
    /// @throws std::invalid_argument naming the shape type when it is not supported, or as create()
    static std::shared_ptr<const btBuoyancyShape> fromCollisionShape(const btCollisionShape& shape,
                                                                     const btBuoyancySettings& settings = btBuoyancySettings());

    /// The concrete method (never Auto).
    btBuoyancyMethod getMethod() const { return m_integration->method; }
    /// The method's registry entry: what it prepared and how a pose is evaluated (integrals/IntegrationMethod.h).
    const buoyancy::IntegrationMethod& getIntegrationMethod() const { return *m_integration; }
    /// The shape data the method's evaluation reads, with `samples` as the samples in use (getSamples(), or a
    /// deformable body's re-baked ones).
    buoyancy::MethodGeometry getGeometry(const buoyancy::SurfaceSamples& samples) const {
        return {m_mesh, m_prepared.tree, samples};
    }
    /// The mesh, body (mesh) frame, m.
    const buoyancy::TriangleMesh& getMesh() const { return m_mesh; }
    /// Moment tree of the mesh for the exact-mesh method (design.md 2.5; empty for sampled methods).
    const buoyancy::MeshMomentTree& getMomentTree() const { return m_prepared.tree; }
    /// Hydrostatic samples (empty for ExactMesh).
    const buoyancy::SurfaceSamples& getSamples() const { return m_prepared.samples; }
    /// Samples used for drag: the hydrostatic samples of a sampled method, else triangle pieces (centroid, area
    /// vector; ExactMesh).
    const buoyancy::SurfaceSamples& getDragSamples() const {
        return m_integration->sampled ? m_prepared.samples : m_prepared.faceSamples;
    }
    /// Solid mass properties at density 1 kg/m³ (mass = volume), mesh frame.
    const buoyancy::MassProperties& getUnitSolid() const { return m_prepared.unitSolid; }
    /// Shell mass properties at density 1 kg/m³ and thickness 1 m (mass = area), mesh frame.
    const buoyancy::MassProperties& getUnitShell() const { return m_prepared.unitShell; }
    /// Enclosed volume as the buoyancy integrals see it, m³.
    double getVolume() const { return m_prepared.unitSolid.volume; }
    /// Centre of the mesh's bounding box, mesh frame, m.
    const Eigen::Vector3d& getBoundsCentre() const { return m_boundsCentre; }
    /// Radius of the bounding sphere about getBoundsCentre(), m.
    double getBoundsRadius() const { return m_boundsRadius; }
    /// > 0 for the shape of a btSphereShape: its radius, m (the sphere is centred at the mesh origin). In flat water
    /// its hydrostatics are then the sphere's cap in closed form (exact, constant time) instead of its tessellation;
    /// 0 for every other shape.
    double getSphereRadius() const { return m_sphereRadius; }
    /// For the shape of a btBoxShape: its half extents along the mesh frame's axes, m (the box is centred at the mesh
    /// origin); in flat water its hydrostatics are then the box's exact clip (buoyancy::boxHydrostatics) in constant
    /// time instead of the mesh path. Zero for every other shape.
    const Eigen::Vector3d& getBoxHalfExtents() const { return m_boxHalfExtents; }
    /// True for the shape of a btBoxShape (getBoxHalfExtents() is then positive).
    bool isBox() const { return m_boxHalfExtents.x() > 0; }
    /// > 0 for the shape of a btCapsuleShape: its radius, m (the capsule is centred at the mesh origin, its axis
    /// along getCapsuleAxis()); in flat water its hydrostatics are then buoyancy::capsuleHydrostatics (exact to
    /// rounding, no tessellation) instead of the mesh path. 0 for every other shape.
    double getCapsuleRadius() const { return m_capsuleRadius; }
    /// For the shape of a btCapsuleShape: half the length of its cylinder (Bullet's getHalfHeight()), m.
    double getCapsuleHalfHeight() const { return m_capsuleHalfHeight; }
    /// For the shape of a btCapsuleShape: the mesh-frame axis it lies along (0 x, 1 y, 2 z; Bullet's getUpAxis()).
    int getCapsuleAxis() const { return m_capsuleAxis; }
    /// True when the samples were baked through an atlas the library generated (the model's UVs were missing or
    /// unusable); false for the model's own UVs and for ExactMesh (no texture).
    bool usesGeneratedUvs() const { return m_prepared.uvGenerated; }
    /// Why the model's UVs were not used (empty unless usesGeneratedUvs()), e.g. "overlapping UVs (120 triangles)".
    const std::vector<std::string>& getUvProblems() const { return m_prepared.uvProblems; }
    /// What the mesh checks changed or noticed (flipped components, intersecting parts); empty for a clean mesh.
    const std::vector<buoyancy::MeshWarning>& getMeshWarnings() const { return m_meshWarnings; }
    /// Texture size the samples were baked at (0 for ExactMesh).
    int getTextureSize() const { return m_prepared.samples.texture_size; }

private:
    btBuoyancyShape() = default;

    const buoyancy::IntegrationMethod* m_integration = nullptr;  ///< set by create()
    buoyancy::TriangleMesh m_mesh;
    buoyancy::PreparedShape m_prepared;
    Eigen::Vector3d m_boundsCentre = Eigen::Vector3d::Zero();
    double m_boundsRadius = 0;
    double m_sphereRadius = 0;
    Eigen::Vector3d m_boxHalfExtents = Eigen::Vector3d::Zero();
    double m_capsuleRadius = 0;
    double m_capsuleHalfHeight = 0;
    int m_capsuleAxis = 1;
    std::vector<buoyancy::MeshWarning> m_meshWarnings;
};
