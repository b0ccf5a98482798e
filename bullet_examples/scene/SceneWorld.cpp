#include "scene/SceneWorld.h"

#include "scene/ChildProcessImport.h"
#include "scene/SceneErrors.h"
#include "scene/SceneGraph.h"
#include "scene/ModelPreparation.h"
#include "scene/ModelSize.h"
#include "scene/SceneWater.h"

#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>

#include <cmath>
#include <iostream>
#include <string>

namespace buoyancy::cli {

namespace {

/// The mesh of a scene body (primitives are made by the library, files imported in a child process).
/// @param[out] openTriangles  with "open_top": the triangles that close the model's holes (its openings)
TriangleMesh sceneMesh(const SceneBody& b, std::size_t index, double importTimeout,
                       std::vector<std::size_t>& openTriangles) {
    const SceneShape& s = b.shape;
    const std::string key = "bodies[" + std::to_string(index) + "].shape";
    try {
        if (s.type == "box") return makeBoxMesh(s.size.x(), s.size.y(), s.size.z());
        if (s.type == "sphere") return makeSphereMesh(s.radius, s.resolution, std::max(4, s.resolution / 2 + 1));
        if (s.type == "cylinder") return makeCylinderMesh(s.radius, s.height, s.resolution);
        TriangleMesh mesh = importMeshInChildProcess(s.file, s.scale, importTimeout);
        const PreparedModel prepared =
            prepareModel(mesh, s.file, ModelChoices{s.repair || s.openTop, s.convexHull},
                         "\"repair\": true closes holes and fixes orientation; \"convex_hull\": true replaces the "
                         "model by its hull");
        for (const MeshWarning& w : prepared.report.warnings) std::cerr << "warning: " << key << ": " << w.message << '\n';
        if (s.openTop) {
            if (prepared.report.repair.holes_closed == 0)
                throw UsageError("open_top: " + s.file + " has no hole to open (it is closed): leave \"open_top\" out");
            openTriangles = prepared.report.repair.hole_triangles;
        }
        if (const auto hint = modelSizeHint(mesh, s.scale))
            std::cerr << "warning: " << key << ": " << s.file << ": the model's largest side is " << hint->side
                      << " m (after \"scale\": " << s.scale << "): is it in another unit? e.g. \"scale\": "
                      << hint->suggestedScale << '\n';
        return mesh;
    } catch (const std::exception& e) {
        throw UsageError(key + ": " + e.what());
    }
}

}  // namespace

SceneWorld::~SceneWorld() {
    if (waterCoupler) world.removeAction(waterCoupler.get());
    for (auto& d : densityMaps) world.removeAction(d.get());
    for (auto& f : floods)
        if (f) world.removeAction(f.get());
    for (auto& a : actions)
        if (a) world.removeAction(a.get());
    for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
    if (ground) world.removeRigidBody(ground.get());
    actions.clear();
}

std::unique_ptr<SceneWorld> buildSceneWorld(const Scene& scene, double importTimeout) {
    // Build every shape before anything runs (nothing runs on a half-read scene).
    std::vector<std::shared_ptr<const btBuoyancyShape>> shapes;
    std::vector<std::vector<std::size_t>> openTriangles(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& b = scene.bodies[i];
        TriangleMesh mesh = sceneMesh(b, i, importTimeout, openTriangles[i]);
        try {
            shapes.push_back(btBuoyancyShape::create(std::move(mesh), b.buoyancy));
        } catch (const std::exception& e) {
            throw UsageError("bodies[" + std::to_string(i) + "]: " + e.what());
        }
    }

    // Water graphs and permeable samples, also before anything runs.
    std::vector<WaterGraph> graphs(scene.bodies.size());
    std::vector<PermeableSamples> holes(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneFlooding& fl = scene.bodies[i].flooding;
        if (!fl.enabled) continue;
        try {
            graphs[i] = buildSceneWaterGraph(fl, shapes[i]->getMesh());
            holes[i] = buildScenePermeability(fl, graphs[i], shapes[i]->getDragSamples(), shapes[i]->getMesh());
            if (!openTriangles[i].empty())
                addOpenTriangles(holes[i], shapes[i]->getDragSamples(), graphs[i], openTriangles[i]);
        } catch (const std::exception& e) {
            throw UsageError("bodies[" + std::to_string(i) + "].water_graph: " + e.what());
        }
    }

    auto out = std::make_unique<SceneWorld>();
    SceneWorld& w = *out;
    w.world.setGravity(btVector3(btScalar(scene.gravity.x()), btScalar(scene.gravity.y()), btScalar(scene.gravity.z())));
    btGImpactCollisionAlgorithm::registerAlgorithm(&w.dispatcher);
    // One unbounded water ("water"), or bounded water bodies ("waters") in a world without the unbounded one.
    SceneWaterSurface sceneWater;
    if (scene.waters.empty()) sceneWater = makeSceneWater(scene);
    for (std::size_t i = 0; i < scene.waters.size(); ++i) w.waterBodies.push_back(makeSceneWaterBody(scene, i));
    w.water = std::move(sceneWater.surface);
    w.interactiveWater = sceneWater.interactive;
    // The world's gravity; the water frame as the loader resolved it (checked against the gravity there).
    try {
        w.buoyancy = std::make_unique<btBuoyancyWorld>(&w.world, w.water.get(), scene.waterFrame, scene.waterDensity);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("water.frame: ") + e.what());
    }
    w.buoyancy->setEventSettings(scene.events);  // checked by the loader
    for (std::size_t i = 0; i < scene.waters.size(); ++i) {
        const SceneWaterBody& body = scene.waters[i];
        btWaterBodyInfo info = body.regionInfo();
        info.name = "waters[" + std::to_string(i) + "]";
        info.surface = w.waterBodies[i].get();
        info.fluidDensity = body.density;
        try {
            w.buoyancy->addWaterBody(info);
        } catch (const std::invalid_argument& e) {  // the loader checked the regions: a float rounding can remain
            throw UsageError("waters[" + std::to_string(i) + "]: " + e.what());
        }
    }
    if (scene.groundHeight) {
        // The plane through origin + h·up (the water frame's) with the scene's normal (up unless "ground.normal"
        // slopes it).
        w.groundNormal = scene.groundNormal;
        w.groundOffset = scene.groundNormal.dot(scene.waterFrame.origin() + *scene.groundHeight * scene.waterFrame.up());
        w.groundShape = std::make_unique<btStaticPlaneShape>(
            btVector3(btScalar(w.groundNormal.x()), btScalar(w.groundNormal.y()), btScalar(w.groundNormal.z())),
            btScalar(w.groundOffset));
        btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, w.groundShape.get());
        info.m_friction = 0.8;
        info.m_rollingFriction = 0.1;   // a seabed: round bodies that sink stop rolling (docs/scene-format.md)
        info.m_spinningFriction = 0.05; // ... and stop spinning about the vertical
        w.ground = std::make_unique<btRigidBody>(info);
        w.world.addRigidBody(w.ground.get());
        // Several contact points per convex-vs-plane pair (Bullet perturbs the contact normal, 3 × 3 iterations),
        // as tests/oracles/BulletTestWorld does: with the default single point a box or hull resting on the ground
        // gets one new point per substep, rocks and sinks into it (property test). The ground is the
        // only plane of a scene, so this touches bodies against the ground only.
        w.config.setPlaneConvexMultipointIterations();
    }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& b = scene.bodies[i];
        btTransform pose;
        pose.setIdentity();
        pose.setOrigin(btVector3(btScalar(b.position.x()), btScalar(b.position.y()), btScalar(b.position.z())));
        if (b.degrees != 0)
            pose.setRotation(btQuaternion(btVector3(btScalar(b.axis.x()), btScalar(b.axis.y()), btScalar(b.axis.z())),
                                          btScalar(b.degrees * M_PI / 180.0)));
        try {
            w.bodies.push_back(std::make_unique<btBuoyantBody>(shapes[i], b.body, pose));
        } catch (const std::exception& e) {
            throw UsageError("bodies[" + std::to_string(i) + "]: " + e.what());
        }
        btRigidBody* rb = w.bodies.back()->getRigidBody();
        w.world.addRigidBody(rb);
        if (!b.body.fixed) {
            rb->setLinearVelocity(btVector3(btScalar(b.linearVelocity.x()), btScalar(b.linearVelocity.y()),
                                            btScalar(b.linearVelocity.z())));
            rb->setAngularVelocity(btVector3(btScalar(b.angularVelocity.x()), btScalar(b.angularVelocity.y()),
                                             btScalar(b.angularVelocity.z())));
            w.actions.push_back(std::make_unique<btBuoyancyAction>(*w.bodies.back(), w.buoyancy.get(), b.buoyancy));
            if (b.hydrodynamics.enabled) w.actions.back()->setMarineHydrodynamics(b.hydrodynamics);
            w.world.addAction(w.actions.back().get());
            if (b.flooding.enabled) {  // after the body's buoyancy action (the water clock is current)
                try {
                    w.floods.push_back(std::make_unique<btFloodingAction>(*w.bodies.back(), w.buoyancy.get(),
                                                                          graphs[i], holes[i]));
                } catch (const std::exception& e) {
                    throw UsageError("bodies[" + std::to_string(i) + "].water_graph: " + e.what());
                }
                w.world.addAction(w.floods.back().get());
            } else {
                w.floods.push_back(nullptr);
            }
            if (b.flooding.densityMap.enabled) {  // time-varying dry mass (paper Fig. 15), recomputed when it changes
                const SceneDensityMap map = b.flooding.densityMap;
                const Eigen::Vector3d centre = shapes[i]->getBoundsCentre();
                try {
                    w.densityMaps.push_back(std::make_unique<btTimeVaryingMassAction>(
                        *w.bodies.back(), w.buoyancy.get(), b.body, [map](double t) { return map.version(t); },
                        [map, centre](double t, const Eigen::Vector3d& p) { return map.density(t, p, centre); },
                        w.floods.back().get()));
                } catch (const std::exception& e) {
                    throw UsageError("bodies[" + std::to_string(i) + "].density_map: " + e.what());
                }
                w.world.addAction(w.densityMaps.back().get());
            }
        } else {
            w.actions.push_back(nullptr);
            w.floods.push_back(nullptr);
        }
    }

    if (sceneWater.interactive) {  // after every body's action: Bullet calls actions in the order added
        w.waterCoupler = std::make_unique<btInteractiveWaterCoupler>(sceneWater.interactive, w.buoyancy.get());
        w.world.addAction(w.waterCoupler.get());
    }
    return out;
}

void stepSceneFrame(const Scene& scene, SceneWorld& world) {
    const int n = scene.substepsPerFrame;
    world.world.stepSimulation(btScalar(scene.dt * n), n, btScalar(scene.dt));
}

}  // namespace buoyancy::cli
