#include "cli/RunCommand.h"

#include "cli/ChildProcessImport.h"
#include "cli/CliErrors.h"
#include "cli/SceneFile.h"

#include "bullet/btBuoyancyAction.h"
#include "bullet/btBuoyancyWorld.h"
#include "bullet/btBuoyantBodyBuilder.h"
#include "mesh/MeshImport.h"
#include "mesh/MeshRepair.h"
#include "mesh/PrimitiveMeshes.h"
#include "cli/SceneGraph.h"
#include "cli/SceneWater.h"
#include "graph/btFloodingAction.h"
#include "water/btInteractiveWaterCoupler.h"
#include "water/btWaterSurface.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

namespace buoyancy::cli {

void addRunCommand(CLI::App& app, RunOptions& options) {
    CLI::App* run = app.add_subcommand("run", "Run a scene file headless and write DIR/trajectory.csv");
    run->add_option("scene", options.scene, "Scene JSON file (docs/scene-format.md)")->required();
    run->add_option("--out", options.out, "Output folder (created when missing)")->required();
    run->add_option("--duration", options.duration, "Override the scene's duration, s")->check(CLI::NonNegativeNumber);
    run->add_option("--import-timeout", options.import_timeout, "Time limit of each mesh import, s")
        ->check(CLI::PositiveNumber);
}

namespace {

/// The mesh of a scene body (primitives are made by the library, files imported in a child process).
TriangleMesh sceneMesh(const SceneBody& b, std::size_t index, double importTimeout) {
    const SceneShape& s = b.shape;
    const std::string key = "bodies[" + std::to_string(index) + "].shape";
    try {
        if (s.type == "box") return makeBoxMesh(s.size.x(), s.size.y(), s.size.z());
        if (s.type == "sphere") return makeSphereMesh(s.radius, s.resolution, std::max(4, s.resolution / 2 + 1));
        if (s.type == "cylinder") return makeCylinderMesh(s.radius, s.height, s.resolution);
        TriangleMesh mesh = importMeshInChildProcess(s.file, s.scale, importTimeout);
        prepareMesh(mesh, s.file);
        return mesh;
    } catch (const std::exception& e) {
        throw UsageError(key + ": " + e.what());
    }
}

/// Everything the runner owns, destroyed in the right order (actions and bodies leave the world first).
struct SceneWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    std::unique_ptr<btWaterSurface> water;
    std::unique_ptr<btInteractiveWaterCoupler> waterCoupler;  // interactive water only, the last action
    std::unique_ptr<btBuoyancyWorld> buoyancy;
    std::vector<std::unique_ptr<btBuoyantBody>> bodies;
    std::vector<std::unique_ptr<btBuoyancyAction>> actions;  // null for fixed bodies
    std::vector<std::unique_ptr<btFloodingAction>> floods;   // null without a water graph (issue 6)
    std::unique_ptr<btStaticPlaneShape> groundShape;
    std::unique_ptr<btRigidBody> ground;

    ~SceneWorld() {
        if (waterCoupler) world.removeAction(waterCoupler.get());
        for (auto& f : floods)
            if (f) world.removeAction(f.get());
        for (auto& a : actions)
            if (a) world.removeAction(a.get());
        for (auto& b : bodies) world.removeRigidBody(b->getRigidBody());
        if (ground) world.removeRigidBody(ground.get());
        actions.clear();
    }
};

void writeRows(std::FILE* f, double t, const Scene& scene, SceneWorld& w) {
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const btBuoyantBody& b = *w.bodies[i];
        const btRigidBody* rb = b.getRigidBody();
        // From the body's own transform (not an interpolated motion state).
        const btTransform mesh = b.getMeshWorldTransform();
        const btQuaternion q = mesh.getRotation();
        const btVector3 c = rb->getCenterOfMassPosition();
        const btVector3 v = rb->getLinearVelocity();
        const btVector3 av = rb->getAngularVelocity();
        btBuoyancyResult r;
        if (w.actions[i]) r = w.actions[i]->getLastResult();
        const double waterVolume = i < w.floods.size() && w.floods[i] ? w.floods[i]->getWaterVolume() : 0.0;
        const double values[] = {mesh.getOrigin().x(), mesh.getOrigin().y(), mesh.getOrigin().z(), q.x(), q.y(), q.z(),
                                 q.w(), c.x(), c.y(), c.z(), v.x(), v.y(), v.z(), av.x(), av.y(), av.z(),
                                 r.submergedVolume, b.getMass(), waterVolume,
                                 r.buoyancyForce.x(), r.buoyancyForce.y(), r.buoyancyForce.z(),
                                 r.dragForce.x(), r.dragForce.y(), r.dragForce.z(),
                                 r.centreOfBuoyancy.x(), r.centreOfBuoyancy.y(), r.centreOfBuoyancy.z()};
        for (double x : values)
            if (!std::isfinite(x))
                throw InternalError("non-finite state of body \"" + scene.bodies[i].name + "\" at t = " + std::to_string(t));
        std::fprintf(f, "%.17g,%s", t, scene.bodies[i].name.c_str());
        for (double x : values) std::fprintf(f, ",%.17g", x);
        std::fputc('\n', f);
    }
}

}  // namespace

int runScene(const RunOptions& options) {
    const Scene scene = loadSceneFile(options.scene);
    const double duration = options.duration ? *options.duration : scene.duration;
    if (!std::isfinite(duration) || duration < 0) throw UsageError("--duration: must be a number >= 0");

    // Build every shape before anything runs (nothing runs on a half-read scene).
    std::vector<std::shared_ptr<const btBuoyancyShape>> shapes;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneBody& b = scene.bodies[i];
        TriangleMesh mesh = sceneMesh(b, i, options.import_timeout);
        try {
            shapes.push_back(btBuoyancyShape::create(std::move(mesh), b.buoyancy));
        } catch (const std::exception& e) {
            throw UsageError("bodies[" + std::to_string(i) + "]: " + e.what());
        }
    }

    // Water graphs and permeable samples (issue 6), also before anything runs.
    std::vector<WaterGraph> graphs(scene.bodies.size());
    std::vector<PermeableSamples> holes(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const SceneFlooding& fl = scene.bodies[i].flooding;
        if (!fl.enabled) continue;
        try {
            graphs[i] = buildSceneWaterGraph(fl, shapes[i]->getMesh());
            holes[i] = buildScenePermeability(fl, graphs[i], shapes[i]->getDragSamples());
        } catch (const std::exception& e) {
            throw UsageError("bodies[" + std::to_string(i) + "].water_graph: " + e.what());
        }
    }

    SceneWorld w;
    w.world.setGravity(btVector3(btScalar(scene.gravity.x()), btScalar(scene.gravity.y()), btScalar(scene.gravity.z())));
    btGImpactCollisionAlgorithm::registerAlgorithm(&w.dispatcher);
    SceneWaterSurface sceneWater = makeSceneWater(scene);
    w.water = std::move(sceneWater.surface);
    w.buoyancy = std::make_unique<btBuoyancyWorld>(w.water.get(), scene.waterDensity, -scene.gravity.y());
    if (scene.groundHeight) {
        w.groundShape = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(*scene.groundHeight));
        btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, w.groundShape.get());
        info.m_friction = 0.8;
        info.m_rollingFriction = 0.1;   // a seabed: round bodies that sink stop rolling (docs/scene-format.md)
        info.m_spinningFriction = 0.05; // ... and stop spinning about the vertical
        w.ground = std::make_unique<btRigidBody>(info);
        w.world.addRigidBody(w.ground.get());
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
        } else {
            w.actions.push_back(nullptr);
            w.floods.push_back(nullptr);
        }
    }

    if (sceneWater.interactive) {  // after every body's action: Bullet calls actions in the order added
        w.waterCoupler = std::make_unique<btInteractiveWaterCoupler>(sceneWater.interactive, w.buoyancy.get());
        w.world.addAction(w.waterCoupler.get());
    }

    std::error_code ec;
    std::filesystem::create_directories(options.out, ec);
    const std::string csvPath = (std::filesystem::path(options.out) / "trajectory.csv").string();
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(csvPath.c_str(), "w"), &std::fclose);
    if (!f) throw UsageError("--out: cannot write " + csvPath);
    std::fputs("t,body,x,y,z,qx,qy,qz,qw,cx,cy,cz,vx,vy,vz,wx,wy,wz,submerged_volume,mass,water_volume,"
               "fbx,fby,fbz,fdx,fdy,fdz,cbx,cby,cbz\n",
               f.get());

    const int n = scene.substepsPerFrame;
    const double frameTime = scene.dt * n;
    const long long frames = static_cast<long long>(std::ceil(duration / frameTime - 1e-9));
    writeRows(f.get(), 0.0, scene, w);
    long long nextOutput = 1;  // index k of the next multiple k·output_interval to report
    for (long long frame = 1; frame <= frames; ++frame) {
        w.world.stepSimulation(btScalar(frameTime), n, btScalar(scene.dt));
        const double t = frame * frameTime;
        // First frame boundary at or after each multiple of the output interval (tolerance for rounding).
        if (t >= nextOutput * scene.outputInterval - 1e-9 * frameTime) {
            writeRows(f.get(), t, scene, w);
            while (nextOutput * scene.outputInterval <= t + 1e-9 * frameTime) ++nextOutput;
        }
    }
    if (std::fflush(f.get()) != 0) throw UsageError("--out: error writing " + csvPath);
    return kExitOk;
}

int runSceneCommand(const std::string& scenePath, const std::string& outDir, std::optional<double> duration) {
    RunOptions options;
    options.scene = scenePath;
    options.out = outDir;
    options.duration = duration;
    try {
        return runScene(options);
    } catch (const UsageError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kExitBadInput;
    } catch (const InternalError& e) {
        std::cerr << "internal error: " << e.what() << '\n';
        return kExitInternal;
    } catch (const std::exception& e) {
        std::cerr << "internal error: " << e.what() << '\n';
        return kExitInternal;
    }
}

}  // namespace buoyancy::cli
