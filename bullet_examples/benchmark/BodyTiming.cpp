#include "benchmark/BodyTiming.h"

#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace buoyancy::bench {

struct SingleBodyRig::Impl {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btFlatWaterSurface water{0.0};
    btBuoyancyWorld buoyancy{&water, 1000.0, 9.81};
    std::unique_ptr<btBuoyantBody> body;
    ~Impl() {
        if (body) world.removeRigidBody(body->getRigidBody());
    }
};

SingleBodyRig::SingleBodyRig(std::shared_ptr<const btBuoyancyShape> shape, const btWaterSurface* water) : m(new Impl) {
    if (water) m->buoyancy.setWater(water);
    btBuoyantBodySettings bs;
    bs.density = 500.0;
    m->body = std::make_unique<btBuoyantBody>(std::move(shape), bs, btTransform::getIdentity());
    m->body->getRigidBody()->setActivationState(DISABLE_DEACTIVATION);
    m->world.addRigidBody(m->body->getRigidBody());
}

SingleBodyRig::~SingleBodyRig() = default;

btBuoyantBody& SingleBodyRig::body() { return *m->body; }
btBuoyancyWorld& SingleBodyRig::buoyancyWorld() { return m->buoyancy; }
const btFlatWaterSurface& SingleBodyRig::water() const { return m->water; }
const btWaterSurface& SingleBodyRig::surface() const { return *m->buoyancy.getWater(); }

Eigen::Isometry3d SingleBodyRig::meshInCom() const {
    const btTransform& t = m->body->getMeshInComFrame();
    Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) e.linear()(i, j) = double(t.getBasis()[i][j]);
    e.translation() = Eigen::Vector3d(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z());
    return e;
}

void SingleBodyRig::place(const Eigen::Isometry3d& meshPose) {
    const Eigen::Isometry3d com = meshPose * meshInCom().inverse();
    btTransform t;
    btMatrix3x3 b;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b[i][j] = btScalar(com.linear()(i, j));
    t.setBasis(b);
    t.setOrigin(btVector3(btScalar(com.translation().x()), btScalar(com.translation().y()), btScalar(com.translation().z())));
    m->body->getRigidBody()->setWorldTransform(t);
}

Eigen::Isometry3d SingleBodyRig::heldMeshPose(const Eigen::Isometry3d& meshPose) {
    place(meshPose);
    // The product the actions form (btBuoyancyAction: body transform · mesh-in-COM frame), in btScalar.
    const btTransform t = m->body->getRigidBody()->getWorldTransform() * m->body->getMeshInComFrame();
    Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) e.linear()(i, j) = double(t.getBasis()[i][j]);
    e.translation() = Eigen::Vector3d(double(t.getOrigin().x()), double(t.getOrigin().y()), double(t.getOrigin().z()));
    return e;
}

Eigen::Vector3d SingleBodyRig::centreOfMass() const {
    const btVector3 c = m->body->getRigidBody()->getCenterOfMassPosition();
    return Eigen::Vector3d(double(c.x()), double(c.y()), double(c.z()));
}

const btBuoyancyResult& SingleBodyRig::evaluate(btBuoyancyAction& action, const Eigen::Isometry3d& meshPose, double time) {
    btRigidBody* rb = m->body->getRigidBody();
    const btScalar dt = btScalar(1.0 / 240.0);
    // The action advances the clock by dt at the start of its substep (btBuoyancyWorld::beginSubstepIfNew) when it
    // was the last to see the current substep; its first call after another action's does not: then once more.
    for (int attempt = 0; attempt < 2; ++attempt) {
        m->buoyancy.setTime(time - double(dt));
        place(meshPose);
        rb->setLinearVelocity(btVector3(0, 0, 0));
        rb->setAngularVelocity(btVector3(0, 0, 0));
        action.updateAction(&m->world, dt);
        if (std::abs(action.getLastResult().time - time) <= 1e-9 * (1.0 + std::abs(time))) break;
    }
    return action.getLastResult();
}

double SingleBodyRig::nsPerSubstep(btActionInterface& action, const Eigen::Isometry3d& meshPose,
                                   const TimingOptions& options, double time) {
    place(meshPose);
    btRigidBody* rb = m->body->getRigidBody();
    btBuoyancyWorld& waterClock = m->buoyancy;
    const btVector3 v0(0.5, -0.3, 0.2), w0(0.2, 0.1, -0.3);
    const btScalar dt = btScalar(1.0 / 240.0);
    using clock = std::chrono::steady_clock;
    auto run = [&](long n) {
        const auto t0 = clock::now();
        for (long i = 0; i < n; ++i) {
            // The actions advance the clock by dt at the start of their substep: this call evaluates the water at
            // time (even i) or time + dt (odd i).
            waterClock.setTime(time - double(dt) + double(i & 1) * double(dt));
            rb->setLinearVelocity(v0);
            rb->setAngularVelocity(w0);
            action.updateAction(&m->world, dt);
        }
        return std::chrono::duration<double>(clock::now() - t0).count();
    };
    // Calibrate: grow the repetition count until one batch lasts minBatchSeconds.
    long reps = 1;
    double s = run(reps);
    while (s < options.minBatchSeconds && reps < (1L << 30)) {
        reps = std::max(reps * 2, long(reps * options.minBatchSeconds / std::max(s, 1e-9) * 1.2));
        s = run(reps);
    }
    double best = s / double(reps);
    for (int b2 = 1; b2 < options.batches; ++b2) best = std::min(best, run(reps) / double(reps));
    return best * 1e9;
}

}  // namespace buoyancy::bench
