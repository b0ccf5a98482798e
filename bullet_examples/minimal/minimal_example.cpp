// The smallest complete use of BulletBuoyancy (shown in README.md): your own btRigidBody with its btBoxShape, the
// water, one action; step the Bullet world, read the result.
#include <BulletBuoyancy/BulletBuoyancy.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>

int main() {
    // 1. A Bullet world and a body, as usual: a 1 m box dropped from 1 m.
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, -9.81, 0));
    btBoxShape box(btVector3(0.5, 0.5, 0.5));
    btRigidBody body(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &box));
    body.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)));
    world.addRigidBody(&body);

    // 2. The water (any btWaterSurface), the world's buoyancy context (fresh water, the world's gravity) and the
    //    body's action: its geometry is the body's collision shape.
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancyWorld(&world, &water, 1000.0);
    btBuoyancyAction action(&body, &buoyancyWorld);
    action.setBodyMassFromShape(150);  // balsa, kg/m^3: mass and exact inertia of the box
    world.addAction(&action);

    // 3. Step: 60 Hz frames of four 240 Hz substeps.
    for (int frame = 0; frame < 60 * 20; ++frame) world.stepSimulation(1.0 / 60, 4, 1.0 / 240);

    const btBuoyancyResult& r = action.getLastResult();
    std::printf("after 20 s: centre at y = %.4f m, submerged volume %.4f m^3\n",
                double(body.getCenterOfMassPosition().y()), r.submergedVolume);
    world.removeAction(&action);
    world.removeRigidBody(&body);
    // A body of 150 kg/m^3 floats with 15 % of its volume under water (Archimedes).
    return std::fabs(r.submergedVolume - 0.15) < 0.005 ? 0 : 1;
}
