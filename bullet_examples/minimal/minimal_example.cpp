// The smallest complete use of BulletBuoyancy (shown in README.md): load a mesh, make its body and its
// buoyancy action, step a Bullet world, read the result. Usage: minimal_example [MESH] (default: a 1 m box).
#include <BulletBuoyancy/BulletBuoyancy.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
    // 1. A Bullet world as usual.
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, -9.81, 0));

    // 2. The water (any btWaterSurface) and the per-world buoyancy context: fresh water, the world's gravity.
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancyWorld(&world, &water, 1000.0);

    // 3. A closed mesh (untrusted files belong in a child process: see bullet_examples/scene/ChildProcessImport.h).
    buoyancy::TriangleMesh mesh = argc > 1 ? buoyancy::importMeshFile(argv[1]) : buoyancy::makeBoxMesh(1, 1, 1);
    buoyancy::prepareMesh(mesh, argc > 1 ? argv[1] : "box");
    auto shape = btBuoyancyShape::create(std::move(mesh));  // samples + mass properties, shareable

    // 4. The rigid body (balsa: 150 kg/m^3) dropped from 1 m, and its action.
    btBuoyantBodySettings bodySettings;
    bodySettings.density = 150;
    btBuoyantBody body(shape, bodySettings, btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)));
    world.addRigidBody(body.getRigidBody());
    btBuoyancyAction action(body, &buoyancyWorld);
    world.addAction(&action);

    // 5. Step: 60 Hz frames of four 240 Hz substeps.
    for (int frame = 0; frame < 60 * 20; ++frame) world.stepSimulation(1.0 / 60, 4, 1.0 / 240);

    const btTransform pose = body.getMeshWorldTransform();
    const btBuoyancyResult& r = action.getLastResult();
    std::printf("after 20 s: mesh origin at y = %.4f m, submerged volume %.4f m^3 (%.1f %% of the body)\n",
                double(pose.getOrigin().y()), r.submergedVolume, 100 * r.submergedVolume / shape->getVolume());

    world.removeAction(&action);
    world.removeRigidBody(body.getRigidBody());
    // A body of 150 kg/m^3 floats with 15 % of its volume under water (Archimedes).
    return std::fabs(r.submergedVolume / shape->getVolume() - 0.15) < 0.005 ? 0 : 1;
}
