#pragma once
/// @file ReliabilityWorld.h
/// Fixture of the reliability tests (issue 10): a Bullet world with flat water whose internal tick
/// callback checks every rigid body's invariants (btBuoyancyCheckBody) after every substep.

#include "bullet/btBuoyancyAction.h"
#include "bullet/btBuoyancyInvariants.h"
#include "bullet/btBuoyancyWorld.h"
#include "bullet/btBuoyantBodyBuilder.h"
#include "water/btWaterSurface.h"

#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace reliability_test {

/// A world with flat water at y = 0 (ρ_w = 1000, g = 9.81) whose tick callback checks every body.
class ReliabilityWorld {
public:
    ReliabilityWorld();
    ~ReliabilityWorld();

    /// Add a btBuoyantBody and its action to the world; returns its index.
    std::size_t add(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& body,
                    const btTransform& meshPose, const btBuoyancySettings& buoyancy = btBuoyancySettings());
    /// A static ground plane y = h (checked like the others, as a static body).
    void addGround(double h);
    /// stepSimulation(dt·n, n, dt), `frames` times.
    void step(int frames, int substepsPerFrame = 4, double dt = 1.0 / 240.0);

    btBuoyantBody& body(std::size_t i) { return *m_bodies[i]; }
    btBuoyancyAction& action(std::size_t i) { return *m_actions[i]; }
    btRigidBody* rigid(std::size_t i) { return m_bodies[i]->getRigidBody(); }
    std::size_t size() const { return m_bodies.size(); }
    btDiscreteDynamicsWorld& world() { return *m_world; }
    btBuoyancyWorld& water() { return *m_water; }
    btFlatWaterSurface& surface() { return m_surface; }

    /// Substeps checked so far, and the first broken invariant seen ("" when none), with the body index.
    std::uint64_t checkedSubsteps() const { return m_checked; }
    const std::string& firstViolation() const { return m_violation; }
    /// Sum over actions of getRejectedCount() (non-finite impulses refused; should stay 0).
    std::uint64_t rejectedTotal() const;

private:
    static void tick(btDynamicsWorld* world, btScalar dt);

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
    std::uint64_t m_checked = 0;
    std::string m_violation;
};

/// Masks the floating-point traps of test_main.cpp (FPE build) for a test that feeds NaN or overflowing
/// values on purpose: comparing a NaN raises FE_INVALID even where the code handles it. Restores on exit.
class ScopedFpTrapsOff {
public:
    ScopedFpTrapsOff();
    ~ScopedFpTrapsOff();
    ScopedFpTrapsOff(const ScopedFpTrapsOff&) = delete;
    ScopedFpTrapsOff& operator=(const ScopedFpTrapsOff&) = delete;

private:
    int m_saved = 0;
};

/// btTransform from a translation and a rotation of `degrees` about `axis`.
btTransform pose(const btVector3& position, const btVector3& axis = btVector3(0, 0, 1), double degrees = 0);

/// Resident set size of this process, bytes (/proc/self/statm, field 2 × page size).
std::size_t residentBytes();

}  // namespace reliability_test
