#pragma once
/// @file btBuoyancyDeformable.h
/// A deformable buoyant body's surface samples (paper Fig. 17, the balloon): the user animates
/// the mesh's vertices, the samples are re-baked through the fixed texel → (triangle, barycentric) map
/// (bake/DeformableRebake.h) in one pass, on the CPU here and on the OpenCL device when the world uses it.
///
/// Usage:  auto shape = btBuoyancyShape::create(mesh, settings);            // a sampled method
///         auto skin  = btBuoyancyDeformable::create(*shape, settings);
///         btBuoyancyAction action(body, shape, &world, settings);  action.setDeformable(skin);
///         every frame: skin->setVertices(newPositions);   // mesh frame, same vertex order
/// The shape's mass properties and drag clusters stay those of the rest mesh (set the body's mass
/// yourself if it changes); the hydrostatic samples (volume, buoyancy, wetted area) follow the vertices.

#include <BulletBuoyancy/bake/DeformableRebake.h>
#include <BulletBuoyancy/bake/SurfaceSamples.h>

#include <LinearMath/btVector3.h>

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

class btBuoyancyShape;
struct btBuoyancySettings;

/// Re-bakeable surface samples of one deformable body.
class btBuoyancyDeformable {
public:
    /// Build the piece map of `shape`'s mesh through the same UV layout and texture size its samples were
    /// baked with (chooseUvLayout with settings.preferModelUvs); the samples start at the rest pose.
    /// @param shape     a shape with a sampled method (texel-centre or exact-coverage)
    /// @param settings  the settings the shape was created with (only preferModelUvs is read)
    /// @throws std::invalid_argument when the shape uses exact-mesh (no texture to re-bake), or when the
    ///         rebuilt layout does not reproduce the shape's samples (different settings)
    static std::shared_ptr<btBuoyancyDeformable> create(const btBuoyancyShape& shape, const btBuoyancySettings& settings);

    /// New vertex positions, mesh frame, m (#V, the mesh's vertex order; welded mesh of the shape).
    /// Bumps getVersion(); the CPU samples are re-baked when next asked for (getSamples, getVolume), so that a
    /// world evaluating its bodies in parallel re-bakes them on its threads. @throws std::invalid_argument for a wrong
    /// count or a non-finite position (nothing changed)
    void setVertices(const std::vector<Eigen::Vector3d>& vertices);
    /// Same, from Bullet vectors.
    void setVertices(const std::vector<btVector3>& vertices);

    /// Current vertex positions, mesh frame, m.
    const std::vector<Eigen::Vector3d>& getVertices() const { return m_vertices; }
    /// Current samples of the current vertices, mesh frame (re-baked here, once, after a setVertices; concurrent calls
    /// wait for that one re-bake). Do not call setVertices while another thread reads them.
    const buoyancy::SurfaceSamples& getSamples() const;
    /// The fixed piece map.
    const buoyancy::RebakeMap& getMap() const { return m_map; }
    /// Incremented by every setVertices (a device backend re-bakes its copy when it changes).
    std::uint64_t getVersion() const { return m_version; }
    /// Centre of the current vertices' bounding box, mesh frame, m.
    const Eigen::Vector3d& getBoundsCentre() const { return m_boundsCentre; }
    /// Radius of the bounding sphere about getBoundsCentre() of the current vertices, m.
    double getBoundsRadius() const { return m_boundsRadius; }
    /// Enclosed volume of the current samples, Σ A^y y (divergence theorem, design.md 2.1), m³.
    double getVolume() const;

private:
    btBuoyancyDeformable() = default;
    buoyancy::RebakeMap m_map;
    std::vector<Eigen::Vector3d> m_vertices;
    mutable buoyancy::SurfaceSamples m_samples;        ///< baked from m_vertices at version m_bakedVersion
    mutable std::atomic<std::uint64_t> m_bakedVersion{0};
    mutable std::mutex m_bakeMutex;                    ///< taken only to re-bake (once per setVertices)
    std::uint64_t m_version = 0;
    Eigen::Vector3d m_boundsCentre = Eigen::Vector3d::Zero();
    double m_boundsRadius = 0;
    void updateBounds();
};
