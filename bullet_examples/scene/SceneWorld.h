#pragma once
/// @file SceneWorld.h
/// The Bullet world a scene file describes (docs/scene-format.md), built the same way for the headless runner
/// (`buoyancy run`), the offscreen pictures (`--png`), the example scenes and the scene browser: every body
/// with its btBuoyancyAction (and btFloodingAction when it has a water graph), the water surface, the ground.

#include "scene/SceneFile.h"

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>
#include <BulletBuoyancy/bullet/btTimeVaryingMassAction.h>
#include <BulletBuoyancy/bullet/btInteractiveWaterCoupler.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

namespace buoyancy::cli {

/// Everything a running scene owns, destroyed in the right order (actions and bodies leave the world first).
/// Vectors `bodies`, `actions` and `floods` are parallel to Scene::bodies.
struct SceneWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    std::unique_ptr<btWaterSurface> water;
    btInteractiveWaterSurface* interactiveWater = nullptr;    ///< points into `water` for "interactive" water
    std::unique_ptr<btInteractiveWaterCoupler> waterCoupler;  ///< interactive water only, the last action
    /// The surfaces of the scene's "waters" (parallel to Scene::waters; empty with the single "water").
    std::vector<std::unique_ptr<btWaterSurface>> waterBodies;
    std::unique_ptr<btBuoyancyWorld> buoyancy;
    std::vector<std::unique_ptr<btBuoyantBody>> bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> actions;  ///< null for fixed bodies
    std::vector<std::unique_ptr<btFloodingAction>> floods;   ///< null without a water graph
    std::vector<std::unique_ptr<btTimeVaryingMassAction>> densityMaps; ///< bodies with a "density_map" only
    std::unique_ptr<btCollisionShape> groundShape;
    std::unique_ptr<btRigidBody> ground;
    Eigen::Vector3d groundNormal = Eigen::Vector3d::UnitY();  ///< unit normal of the ground plane (world)
    double groundOffset = 0;  ///< the ground plane is {p : groundNormal · p = groundOffset}, m

    SceneWorld() = default;
    SceneWorld(const SceneWorld&) = delete;
    SceneWorld& operator=(const SceneWorld&) = delete;
    ~SceneWorld();

    /// Simulated time: the water clock of the buoyancy world, s.
    double time() const { return buoyancy ? buoyancy->getTime() : 0.0; }
};

/// Build the world of `scene`: every mesh (primitives by the library, files imported in a child process with
/// `importTimeout` s each), shapes, water graphs and permeability are made and checked before anything is added.
/// @throws UsageError naming the body and key for bad input
std::unique_ptr<SceneWorld> buildSceneWorld(const Scene& scene, double importTimeout);

/// One frame of the scene: stepSimulation(dt·n, n, dt) with n = substeps_per_frame.
void stepSceneFrame(const Scene& scene, SceneWorld& world);

}  // namespace buoyancy::cli
