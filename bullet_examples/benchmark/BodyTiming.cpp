#include "benchmark/BodyTiming.h"

#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
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

SingleBodyRig::SingleBodyRig(std::shared_ptr<const btBuoyancyShape> shape) : m(new Impl) {
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

Eigen::Isometry3d SingleBodyRig::meshInCom() const {
    const btTransform& t = m->body->getMeshInComFrame();
    Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) e.linear()(i, j) = double(t.getBasis()[i][j]);
    e.translation() = Eigen::Vector3d(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z());
    return e;
}

double SingleBodyRig::nsPerSubstep(btActionInterface& action, const Eigen::Isometry3d& meshPose,
                                   const TimingOptions& options) {
    const Eigen::Isometry3d com = meshPose * meshInCom().inverse();
    btTransform t;
    btMatrix3x3 b;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b[i][j] = btScalar(com.linear()(i, j));
    t.setBasis(b);
    t.setOrigin(btVector3(btScalar(com.translation().x()), btScalar(com.translation().y()), btScalar(com.translation().z())));
    btRigidBody* rb = m->body->getRigidBody();
    rb->setWorldTransform(t);
    const btVector3 v0(0.5, -0.3, 0.2), w0(0.2, 0.1, -0.3);
    const btScalar dt = btScalar(1.0 / 240.0);
    using clock = std::chrono::steady_clock;
    auto run = [&](long n) {
        const auto t0 = clock::now();
        for (long i = 0; i < n; ++i) {
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
