#pragma once
/// @file BulletTestWorld.h
/// The one Bullet fixture of the physics tests (tests/bullet, tests/reliability; Jolt PhysicsTestContext
/// style): a Bullet world with water (flat at a level, or any btWaterSurface such as Gerstner waves), helpers
/// to add buoyant bodies (and their water graphs), to step with Bullet's fixed substeps, to let bodies settle,
/// and, on request, a check of every body's invariants after every substep (btBuoyancyCheckBody).

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace buoyancy_test {

/// One Bullet world with water, ρ_w = 1000 kg/m³.
class BulletTestWorld {
public:
    /// Flat water at y = waterLevel (m), gravity g (m/s², pointing down −y).
    explicit BulletTestWorld(double waterLevel = 0.0, double g = 9.81);
    /// Water given by `surface` (not owned; must outlive the world), gravity g.
    explicit BulletTestWorld(const btWaterSurface* surface, double g = 9.81);
    ~BulletTestWorld();
    BulletTestWorld(const BulletTestWorld&) = delete;
    BulletTestWorld& operator=(const BulletTestWorld&) = delete;

    /// Add a body with its action; returns the index.
    std::size_t add(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& body,
                    const btTransform& meshPose, const btBuoyancySettings& buoyancy = btBuoyancySettings());
    /// Give body i a water graph (btFloodingAction, added after its buoyancy action); returns the action.
    /// @throws std::invalid_argument as btFloodingAction
    btFloodingAction& addFlooding(std::size_t i, buoyancy::WaterGraph graph,
                                  buoyancy::PermeableSamples holes = buoyancy::PermeableSamples());
    /// A static ground plane y = h: friction 0.8, with rolling (0.1) and spinning (0.05) friction like the
    /// scene runner's seabed. Bullet 3.24 caps a contact's rolling-friction impulse at the coefficient itself per
    /// substep, whatever the load, so it slows light round bodies only; and against a plane a heavy polygonal
    /// prism at 30 Hz can keep rolling (Bullet's convex-vs-plane contact feeds it: tests/scenarios/HardCasesTest.cpp,
    /// PolyhedralSeabed, has the measurements and the polyhedral seabed that stops it).
    void addGround(double h);

    /// Check every body's invariants (btBuoyancyCheckBody with positive-definite inertia) after every substep
    /// from now on; the first broken one is kept in firstViolation().
    void checkInvariants();

    /// Advance by frames of n substeps of dt: stepSimulation(dt·n, n, dt).
    void step(int frames, int substepsPerFrame = 4, double dt = 1.0 / 240.0);
    /// Advance by about `seconds` with frames of n substeps.
    void run(double seconds, int substepsPerFrame = 4, double dt = 1.0 / 240.0);

    btBuoyantBody& body(std::size_t i) { return *m_bodies[i]; }
    btBuoyancyAction& action(std::size_t i) { return *m_actions[i]; }
    btRigidBody* rigid(std::size_t i) { return m_bodies[i]->getRigidBody(); }
    std::size_t size() const { return m_bodies.size(); }
    btDiscreteDynamicsWorld& world() { return *m_world; }
    btBuoyancyWorld& water() { return *m_water; }
    /// Simulated time stepped so far, s.
    double time() const { return m_time; }

    /// Substeps checked so far (after checkInvariants()), and the first broken invariant ("" when none).
    std::uint64_t checkedSubsteps() const { return m_checked; }
    const std::string& firstViolation() const { return m_violation; }
    /// Sum over buoyancy actions of getRejectedCount() (non-finite impulses refused; should stay 0).
    std::uint64_t rejectedTotal() const;

private:
    void init(double g);
    static void tick(btDynamicsWorld* world, btScalar dt);

    btDefaultCollisionConfiguration m_config;
    btCollisionDispatcher m_dispatcher{&m_config};
    btDbvtBroadphase m_broadphase;
    btSequentialImpulseConstraintSolver m_solver;
    std::unique_ptr<btDiscreteDynamicsWorld> m_world;
    btFlatWaterSurface m_flat;
    std::unique_ptr<btBuoyancyWorld> m_water;
    std::vector<std::unique_ptr<btBuoyantBody>> m_bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> m_actions;
    std::vector<std::unique_ptr<btFloodingAction>> m_flooding;
    std::unique_ptr<btStaticPlaneShape> m_groundShape;
    std::unique_ptr<btRigidBody> m_ground;
    double m_time = 0;
    std::uint64_t m_checked = 0;
    std::string m_violation;
};

/// What runTracked saw of one body: worst values over the run and the state at its end.
struct Track {
    bool finite = true;        ///< pose and velocities finite after every frame (false: stopped there)
    double maxSpeed = 0;       ///< largest COM speed, m/s
    double maxOmega = 0;       ///< largest angular speed, rad/s
    double maxY = -1e300;      ///< highest COM, m
    double minY = 1e300;       ///< lowest COM, m
    double minLowest = 1e300;  ///< lowest mesh vertex over the run (after every frame), world y, m
    double maxYAfter = -1e300; ///< highest COM after the first time it was below `afterBelow`
    double maxSpeedBelow = 0;  ///< highest speed while the COM is below `speedBelow`
    /// Mean COM speed over the last `window` seconds (displacement / window: Bullet's stored velocity of a
    /// body at rest is +g·dt, the buoyancy kick that the next substep's gravity cancels), m/s.
    double speed = 0;
    double omega = 0;          ///< angular speed at the end, rad/s
    double y = 0;              ///< COM height at the end, m
    double meanMeshY = 0;      ///< mean mesh-origin height over the last `window` seconds (the mean of a
                               ///< decaying oscillation is its equilibrium), m
    btTransform last;          ///< mesh world transform at the end
};

/// The settle-and-measure loop of the physics tests: step frames of n substeps of dt for about `seconds`,
/// recording body i after every frame (`window`: the final stretch averaged for speed and meanMeshY, s).
Track runTracked(BulletTestWorld& w, double seconds, int substepsPerFrame, double dt, std::size_t i = 0,
                 double afterBelow = -1e300, double speedBelow = -1e300, double window = 1.0);

/// btTransform from a translation and a rotation of `degrees` about `axis`.
btTransform makePose(const btVector3& position, const btVector3& axis = btVector3(0, 0, 1), double degrees = 0);

/// Angle between the body axis closest to vertical and world y, degrees (0 = some face is horizontal).
double tiltDegrees(const btTransform& t);

/// Water level h at which the posed mesh (vertex transform `meshPose`) displaces `volume`, by bisection on
/// the oracle's exact submerged volume: the mesh's own analytic equilibrium level.
double oracleEquilibriumLevel(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris,
                              const btTransform& meshPose, double volume);

}  // namespace buoyancy_test
