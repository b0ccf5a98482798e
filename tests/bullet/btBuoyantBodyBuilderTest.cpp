// btBuoyantBody with the user's own motion state: it receives the mesh frame's world transform, not the
// centre-of-mass frame. The expected transform is computed here from the body's COM transform and the mesh
// offset, and from the ballast's position (its COM shift, by the lever rule), not read back from the motion state.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>

TEST_CASE("btBuoyantBody: a motion state gets the mesh frame, also after the mass moves", "[bullet][dynamics]") {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, btScalar(-9.81), 0));
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancy(&world, &water);

    // A 1 m cube of 400 kg/m³ with 100 kg of ballast 0.4 m off-centre along x: the COM sits at
    // x = 100 · 0.4 / 500 = 0.08 m in the mesh frame, so the mesh frame is not the COM frame.
    btBuoyantBodySettings settings;
    settings.density = 400;
    settings.ballast.push_back({Eigen::Vector3d(0.4, 0, 0), 100.0});
    btDefaultMotionState user;
    settings.motionState = &user;
    btTransform start;
    start.setIdentity();
    start.setOrigin(btVector3(1, 0.3, -2));
    start.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(0.2)));
    btBuoyantBody body(btBuoyancyShape::create(buoyancy::makeBoxMesh(1, 1, 1)), settings, start);
    btBuoyancyAction action(body, &buoyancy);
    world.addRigidBody(body.getRigidBody());
    world.addAction(&action);

    auto meshFrameFromCom = [&] {
        // mesh = COM · (mesh in COM); the mesh origin lies 0.08 m from the COM along the mesh's −x axis.
        const btTransform& com = body.getRigidBody()->getCenterOfMassTransform();
        return com * body.getMeshInComFrame();
    };
    auto close = [](const btTransform& a, const btTransform& b) {
        return (a.getOrigin() - b.getOrigin()).length() < 1e-5 &&
               std::abs(std::abs(a.getRotation().dot(b.getRotation())) - 1) < 1e-6;
    };
    btTransform reported;
    user.getWorldTransform(reported);
    CHECK(close(reported, start));  // set to the construction pose
    const btVector3 comOffset = body.getRigidBody()->getCenterOfMassPosition() - start.getOrigin();
    CHECK(comOffset.length() == Approx(0.08).epsilon(1e-4));

    for (int i = 0; i < 90; ++i) world.stepSimulation(btScalar(1.0 / 60.0), 0);  // one step, no interpolation
    user.getWorldTransform(reported);
    CHECK(close(reported, meshFrameFromCom()));
    CHECK((reported.getOrigin() - body.getRigidBody()->getCenterOfMassPosition()).length() == Approx(0.08).epsilon(1e-3));

    // The mass moves (the ballast is dropped): the motion state still gets the mesh frame.
    const buoyancy::MassProperties dry = body.getShape()->getUnitSolid();
    body.updateMassProperties(400.0 * dry.volume, dry.centre, 400.0 * dry.inertia);
    for (int i = 0; i < 30; ++i) world.stepSimulation(btScalar(1.0 / 60.0), 0);  // one step, no interpolation
    user.getWorldTransform(reported);
    CHECK(close(reported, meshFrameFromCom()));
    CHECK((reported.getOrigin() - body.getRigidBody()->getCenterOfMassPosition()).length() < 1e-5);

    world.removeAction(&action);
    world.removeRigidBody(body.getRigidBody());
}
