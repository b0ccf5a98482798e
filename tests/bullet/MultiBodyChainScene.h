#pragma once
// A chain of boxes joined by hinges in a btMultiBodyDynamicsWorld, for the multibody tests.

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

namespace buoyancy_test {

// A multibody world with a chain of `n` boxes of half extents `half` along x, joined by hinges about z at their
// shared faces, the base box's pose `start`, every box of density `density`; damping off.
struct ChainScene {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btMultiBodyConstraintSolver solver;
    btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btBoxShape box;
    std::unique_ptr<btMultiBody> chain;
    std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;

    ChainScene(int n, const btVector3& half, double density, const btTransform& start) : box(half) {
        world.setGravity(btVector3(0, btScalar(-9.81), 0));
        const btScalar mass = btScalar(density * 8 * double(half.x() * half.y() * half.z()));
        btVector3 inertia;
        box.calculateLocalInertia(mass, inertia);
        chain = std::make_unique<btMultiBody>(n - 1, mass, inertia, false, false);
        chain->setBaseWorldTransform(start);
        for (int i = 0; i < n - 1; ++i)
            chain->setupRevolute(i, mass, inertia, i - 1, btQuaternion::getIdentity(), btVector3(0, 0, 1),
                                 btVector3(half.x(), 0, 0), btVector3(half.x(), 0, 0), true);
        chain->finalizeMultiDof();
        chain->setLinearDamping(0);
        chain->setAngularDamping(0);
        world.addMultiBody(chain.get());
        for (int link = -1; link < n - 1; ++link) {
            auto c = std::make_unique<btMultiBodyLinkCollider>(chain.get(), link);
            c->setCollisionShape(&box);
            world.addCollisionObject(c.get(), btBroadphaseProxy::DefaultFilter,
                                     btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::DefaultFilter);
            if (link < 0)
                chain->setBaseCollider(c.get());
            else
                chain->getLink(link).m_collider = c.get();
            colliders.push_back(std::move(c));
        }
        btAlignedObjectArray<btQuaternion> q;
        btAlignedObjectArray<btVector3> o;
        chain->updateCollisionObjectWorldTransforms(q, o);
    }
    ~ChainScene() {
        for (auto& c : colliders) world.removeCollisionObject(c.get());
        world.removeMultiBody(chain.get());
    }
};

}  // namespace buoyancy_test
