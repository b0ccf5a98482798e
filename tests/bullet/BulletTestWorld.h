#pragma once
/// @file BulletTestWorld.h
/// A small fixture for physics tests (Jolt PhysicsTestContext style): a Bullet world with flat water,
/// helpers to add buoyant bodies and to step with Bullet's fixed substeps.

#include "bullet/btBuoyancyAction.h"
#include "bullet/btBuoyancyWorld.h"
#include "bullet/btBuoyantBodyBuilder.h"
#include "water/btWaterSurface.h"

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

namespace buoyancy_test {

/// One Bullet world with flat water at y = 0, ρ_w = 1000, g = 9.81.
class BulletTestWorld {
public:
    explicit BulletTestWorld(double waterLevel = 0.0, double g = 9.81);
    ~BulletTestWorld();

    /// Add a body with its action; returns the index.
    std::size_t add(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& body,
                    const btTransform& meshPose, const btBuoyancySettings& buoyancy = btBuoyancySettings());
    /// A static ground plane y = h.
    void addGround(double h);

    /// Advance by frames of n substeps of dt: stepSimulation(dt·n, n, dt).
    void step(int frames, int substepsPerFrame, double dt);
    /// Advance by about `seconds` with frames of n substeps.
    void run(double seconds, int substepsPerFrame = 4, double dt = 1.0 / 240.0);

    btBuoyantBody& body(std::size_t i) { return *m_bodies[i]; }
    btBuoyancyAction& action(std::size_t i) { return *m_actions[i]; }
    btRigidBody* rigid(std::size_t i) { return m_bodies[i]->getRigidBody(); }
    btDiscreteDynamicsWorld& world() { return *m_world; }
    btBuoyancyWorld& water() { return *m_water; }
    double time() const { return m_time; }

private:
    btDefaultCollisionConfiguration m_config;
    btCollisionDispatcher m_dispatcher{&m_config};
    btDbvtBroadphase m_broadphase;
    btSequentialImpulseConstraintSolver m_solver;
    std::unique_ptr<btDiscreteDynamicsWorld> m_world;
    btFlatWaterSurface m_surface;
    std::unique_ptr<btBuoyancyWorld> m_water;
    std::vector<std::unique_ptr<btBuoyantBody>> m_bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> m_actions;
    std::unique_ptr<btStaticPlaneShape> m_groundShape;
    std::unique_ptr<btRigidBody> m_ground;
    double m_time = 0;
};

/// btTransform from a translation and a rotation of `degrees` about `axis`.
btTransform makePose(const btVector3& position, const btVector3& axis = btVector3(0, 0, 1), double degrees = 0);

/// Angle between the body axis closest to vertical and world y, degrees (0 = some face is horizontal).
double tiltDegrees(const btTransform& t);

/// Water level h at which the posed mesh (vertex transform `meshPose`) displaces `volume`, by bisection on
/// the oracle's exact submerged volume: the mesh's own analytic equilibrium level.
double oracleEquilibriumLevel(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris,
                              const btTransform& meshPose, double volume);

}  // namespace buoyancy_test
