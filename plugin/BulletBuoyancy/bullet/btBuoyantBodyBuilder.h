#pragma once
/// @file btBuoyantBodyBuilder.h
/// Making the btRigidBody of a floating mesh (design.md 3): mass properties from the same data that
/// gives its buoyancy (solid, shell or given mass, plus point-mass ballast), Bullet's COM frame through a
/// btCompoundShape whose child transform is the inverse of the principal frame, the mesh's world
/// transform for users, and updating mass, COM and inertia in place without moving the mesh.

#include <BulletBuoyancy/bullet/btBuoyancyShape.h>

#include <LinearMath/btMotionState.h>
#include <LinearMath/btTransform.h>

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

class btRigidBody;
class btCollisionShape;
class btCompoundShape;
class btTriangleIndexVertexArray;

/// How the dry mass of the body is distributed.
enum class btBuoyantMassModel {
    Solid, ///< uniform solid of `density`
    Shell, ///< thin shell of `density` and `shellThickness` (design.md 2.1: mass ρ Σ|A_i| t)
    /// Density map: a thin shell whose areal density σ(p) (kg/m², = density × thickness) varies over the surface,
    /// given by `arealDensity` at each surface sample (body frame): a hull thicker at the keel, a painted map.
    /// Mass Σ σ_i |A_i|, centre and inertia from the same samples (design.md 2.1).
    DensityMap,
};

/// What the body collides through.
enum class btBuoyantCollision {
    ConvexHull,   ///< convex hull of the mesh vertices (default; cheap, robust)
    TriangleMesh, ///< the mesh itself: btGImpactMeshShape for dynamic bodies (register
                  ///< btGImpactCollisionAlgorithm with the dispatcher), btBvhTriangleMeshShape for fixed ones
    None,         ///< no contacts (CF_NO_CONTACT_RESPONSE): floats through everything
};

/// A point mass fixed to the body (keel weight, cargo).
struct btBuoyantBallast {
    Eigen::Vector3d position = Eigen::Vector3d::Zero(); ///< mesh frame, m
    double mass = 0;                                    ///< kg, > 0
};

/// How to build one buoyant rigid body (Jolt BodyCreationSettings style).
struct btBuoyantBodySettings {
    ///@name Mass
    btBuoyantMassModel massModel = btBuoyantMassModel::Solid; ///< solid or shell
    double density = 500.0;      ///< material density, kg/m³, > 0 (wood ≈ 500, steel 7850); ignored when mass > 0
    double mass = 0.0;           ///< > 0: the body's dry mass, kg (density scaled to match; ballast extra); 0: use density
    double shellThickness = 0.01; ///< shell thickness, m, > 0 (Shell model only)
    /// DensityMap model only: areal density σ at a body-frame surface point, kg/m², ≥ 0 and finite, not zero
    /// everywhere; `mass` > 0 rescales it.
    std::function<double(const Eigen::Vector3d& point)> arealDensity;
    std::vector<btBuoyantBallast> ballast; ///< point masses added to the dry mass (parallel-axis theorem)
    bool fixed = false;          ///< a static body (mass 0 for Bullet); mass settings are ignored

    ///@name Collision and contact
    btBuoyantCollision collision = btBuoyantCollision::ConvexHull; ///< see btBuoyantCollision
    double collisionMargin = 0.005; ///< Bullet collision margin, m, ≥ 0 (Bullet's default 0.04 is large for small bodies)
    double friction = 0.5;          ///< Coulomb friction, ≥ 0
    double restitution = 0.0;       ///< ≥ 0

    ///@name Rendering
    /// Optional, not owned (must outlive the body): receives the mesh frame's world transform — the frame the model
    /// was made in, not the centre-of-mass frame Bullet moves — interpolated by Bullet like any motion state's, so a
    /// renderer draws the model with it directly. Its getWorldTransform is asked for the mesh frame once, when the
    /// body is built (after being set to the construction pose), and for kinematic bodies every step.
    btMotionState* motionState = nullptr;

    ///@name Sleeping (design.md 3)
    /// Bullet's defaults (0.8 m/s, 1 rad/s) freeze a slowly bobbing body; these let only a calm one sleep.
    double linearSleepingThreshold = 0.02;  ///< m/s, ≥ 0
    double angularSleepingThreshold = 0.02; ///< rad/s, ≥ 0

    /// @throws std::invalid_argument naming the bad field
    void validate() const;
};

/// Mass properties of a body, mesh frame: total mass, centre and inertia about the centre (mesh axes).
/// Composes the shape's unit-density solid or shell data with the settings' density/mass and ballast.
/// @throws std::invalid_argument for bad settings
buoyancy::MassProperties btBuoyantBodyMassProperties(const btBuoyancyShape& shape, const btBuoyantBodySettings& settings);

/// A floating body: owns its btRigidBody and collision shapes (not added to any world).
class btBuoyantBody {
public:
    /// Build the body with its mesh frame at `meshWorldTransform` (the COM frame is derived from it).
    /// @throws std::invalid_argument for bad settings or non-finite mass properties (nothing is left built)
    btBuoyantBody(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& settings,
                  const btTransform& meshWorldTransform);
    ~btBuoyantBody();
    btBuoyantBody(const btBuoyantBody&) = delete;
    btBuoyantBody& operator=(const btBuoyantBody&) = delete;

    /// The Bullet body (its transform is the COM/principal frame). Add it to a world yourself; remove it
    /// (and its action) before destroying this object.
    btRigidBody* getRigidBody() const { return m_body.get(); }
    /// The shared buoyancy data.
    const std::shared_ptr<const btBuoyancyShape>& getShape() const { return m_shape; }
    /// The mesh frame expressed in the body's COM frame (the compound child transform).
    const btTransform& getMeshInComFrame() const { return m_meshInCom; }
    /// The mesh frame in world: body transform · getMeshInComFrame().
    btTransform getMeshWorldTransform() const;
    /// Current total mass, kg (0 for a fixed body).
    double getMass() const { return m_massProperties.mass; }
    /// Current mass properties, mesh frame (centre and inertia about it, mesh axes).
    const buoyancy::MassProperties& getMassProperties() const { return m_massProperties; }

    /// Change mass, centre and inertia in place (design.md 3): setMassProps then updateInertiaTensor,
    /// the COM frame moved so the mesh does not move, the compound child updated, and the COM velocity set
    /// to the velocity of the new COM point (v' = v + ω × Δc): the velocity field of the mesh is unchanged.
    /// Gravity already accumulated for the current stepSimulation call keeps the old mass until the next
    /// call (Bullet applies gravity once per call) — a documented lag of at most one frame.
    /// @param mass      kg, > 0
    /// @param centre    new COM, mesh frame, m
    /// @param inertia   about `centre`, mesh axes, kg·m² (symmetric, positive semi-definite)
    /// @throws std::invalid_argument for a fixed body or non-finite / non-positive input (body unchanged)
    void updateMassProperties(double mass, const Eigen::Vector3d& centre, const Eigen::Matrix3d& inertia);

    ///@name Save and restore (btBuoyancyState.h, docs/integration.md "Save and restore")
    /// The body's mass properties (mass, centre and inertia, mesh frame) as a versioned blob of bytes: what a water
    /// graph (btFloodingAction) or a time-varying density map (btTimeVaryingMassAction) changes. Not the Bullet body's
    /// transform, velocities or activation (save those yourself). Call between stepSimulation calls.
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote: the mass properties are set back in place — Bullet's mass and inertia, the mesh
    /// frame in the COM frame and the compound's child — without moving the COM frame or changing the velocities (the
    /// Bullet body's own state is restored by the caller, before or after). Read and checked whole before anything
    /// changes.
    /// @param data, size  the blob (size in bytes)
    /// @throws std::invalid_argument naming the problem, the body unchanged: not a state blob, another format version
    ///         or precision, another kind of blob, truncated or corrupted, a fixed body's blob for a dynamic body (or the
    ///         other way round), or mass properties that are not finite and positive
    void restoreState(const unsigned char* data, std::size_t size);
    /// restoreState of a whole vector. @throws std::invalid_argument (see above)
    void restoreState(const std::vector<unsigned char>& blob) { restoreState(blob.data(), blob.size()); }
    ///@}

private:
    void applyMassProperties(const buoyancy::MassProperties& mp, btTransform& outMeshInCom, btVector3& outMoments) const;

    std::shared_ptr<const btBuoyancyShape> m_shape;
    btBuoyantBodySettings m_settings;
    buoyancy::MassProperties m_massProperties;
    btTransform m_meshInCom;
    std::vector<int> m_indices;
    std::vector<btScalar> m_vertices;
    std::unique_ptr<btTriangleIndexVertexArray> m_meshInterface;
    std::unique_ptr<btCollisionShape> m_childShape;
    std::unique_ptr<btCompoundShape> m_compound;
    std::unique_ptr<btMotionState> m_motionState; ///< maps the COM frame to the user's mesh-frame motion state
    std::unique_ptr<btRigidBody> m_body;
};

/// The mesh's world transform of any body whose mesh sits at `meshInCom` in its COM frame.
btTransform btBuoyantMeshWorldTransform(const btRigidBody& body, const btTransform& meshInCom);
