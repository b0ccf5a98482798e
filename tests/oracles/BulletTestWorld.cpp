#include "oracles/BulletTestWorld.h"

#include <BulletBuoyancy/bullet/btBuoyancyInvariants.h>
#include "oracles/PolyhedralOracle.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>

#include <algorithm>
#include <cmath>

namespace buoyancy_test {

BulletTestWorld::BulletTestWorld(double waterLevel, double g) : m_flat(waterLevel) {
    init(g);
    m_water = std::make_unique<btBuoyancyWorld>(&m_flat, 1000.0, g);
}

BulletTestWorld::BulletTestWorld(const btWaterSurface* surface, double g) {
    init(g);
    m_water = std::make_unique<btBuoyancyWorld>(surface, 1000.0, g);
}

void BulletTestWorld::init(double g) {
    // Several contact points per convex-vs-plane pair (Bullet perturbs the contact normal, 3 × 3 iterations):
    // with the default single point a box or hull resting on the seabed gets one new point per substep, rocks
    // on it and at 30 Hz sank 0.2 m into the ground and kept spinning (property test).
    m_config.setPlaneConvexMultipointIterations();
    m_world = std::make_unique<btDiscreteDynamicsWorld>(&m_dispatcher, &m_broadphase, &m_solver, &m_config);
    m_world->setGravity(btVector3(0, btScalar(-g), 0));
    btGImpactCollisionAlgorithm::registerAlgorithm(&m_dispatcher);
}

BulletTestWorld::~BulletTestWorld() {
    for (auto& a : m_flooding) m_world->removeAction(a.get());
    for (auto& a : m_actions) m_world->removeAction(a.get());
    for (auto& b : m_bodies)
        if (b->getRigidBody()->getBroadphaseHandle()) m_world->removeRigidBody(b->getRigidBody());
    if (m_ground) m_world->removeRigidBody(m_ground.get());
    m_flooding.clear();
    m_actions.clear();
}

std::size_t BulletTestWorld::add(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& body,
                                 const btTransform& meshPose, const btBuoyancySettings& buoyancy) {
    auto b = std::make_unique<btBuoyantBody>(std::move(shape), body, meshPose);
    auto a = std::make_unique<btBuoyancyAction>(*b, m_water.get(), buoyancy);
    m_world->addRigidBody(b->getRigidBody());
    m_world->addAction(a.get());
    m_bodies.push_back(std::move(b));
    m_actions.push_back(std::move(a));
    return m_bodies.size() - 1;
}

btFloodingAction& BulletTestWorld::addFlooding(std::size_t i, buoyancy::WaterGraph graph,
                                               buoyancy::PermeableSamples holes) {
    m_flooding.push_back(std::make_unique<btFloodingAction>(*m_bodies[i], m_water.get(), std::move(graph), std::move(holes)));
    m_world->addAction(m_flooding.back().get());
    return *m_flooding.back();
}

void BulletTestWorld::addGround(double h) {
    m_groundShape = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(h));
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, m_groundShape.get());
    info.m_friction = 0.8;
    info.m_rollingFriction = 0.1;   // a seabed, as the scene runner's "ground" (too weak for heavy bodies: see BulletTestWorld.h)
    info.m_spinningFriction = 0.05; // ... and sunk bodies stop spinning about the vertical
    m_ground = std::make_unique<btRigidBody>(info);
    m_world->addRigidBody(m_ground.get());
}

void BulletTestWorld::checkInvariants() { m_world->setInternalTickCallback(&BulletTestWorld::tick, this); }

void BulletTestWorld::step(int frames, int n, double dt) {
    for (int f = 0; f < frames; ++f) {
        m_world->stepSimulation(btScalar(dt * n), n, btScalar(dt));
        m_time += dt * n;
    }
}

void BulletTestWorld::run(double seconds, int n, double dt) {
    step(static_cast<int>(std::ceil(seconds / (dt * n) - 1e-9)), n, dt);
}

std::uint64_t BulletTestWorld::rejectedTotal() const {
    std::uint64_t r = 0;
    for (const auto& a : m_actions) r += a->getRejectedCount();
    return r;
}

void BulletTestWorld::tick(btDynamicsWorld* world, btScalar) {
    auto* self = static_cast<BulletTestWorld*>(world->getWorldUserInfo());
    ++self->m_checked;
    if (!self->m_violation.empty()) return;
    for (std::size_t i = 0; i < self->m_bodies.size(); ++i) {
        const btRigidBody* body = self->m_bodies[i]->getRigidBody();
        if (!body->getBroadphaseHandle()) continue;  // removed from the world by the test
        const std::string problem = btBuoyancyCheckBody(*body, true);
        if (!problem.empty()) {
            self->m_violation = "body " + std::to_string(i) + ", substep " + std::to_string(self->m_checked) + ": " + problem;
            return;
        }
    }
}

namespace {
bool finiteVec(const btVector3& v) {
    return std::isfinite(double(v.x())) && std::isfinite(double(v.y())) && std::isfinite(double(v.z()));
}
}  // namespace

Track runTracked(BulletTestWorld& w, double seconds, int n, double dt, std::size_t i, double afterBelow,
                 double speedBelow, double window) {
    Track tr;
    const int frames = static_cast<int>(std::ceil(seconds / (n * dt) - 1e-9));
    const int lastStretch = std::max(0, frames - static_cast<int>(std::round(window / (n * dt))));
    btVector3 pMark(0, 0, 0);
    double tMark = 0;
    int averaged = 0;
    bool below = false;
    for (int f = 0; f < frames; ++f) {
        if (f == lastStretch) {
            pMark = w.rigid(i)->getCenterOfMassPosition();
            tMark = w.time();
        }
        w.step(1, n, dt);
        const btRigidBody* rb = w.rigid(i);
        const btTransform& t = rb->getWorldTransform();
        const bool ok = finiteVec(t.getOrigin()) && finiteVec(t.getBasis()[0]) && finiteVec(t.getBasis()[1]) &&
                        finiteVec(t.getBasis()[2]) && finiteVec(rb->getLinearVelocity()) &&
                        finiteVec(rb->getAngularVelocity());
        if (!ok) {
            tr.finite = false;
            return tr;
        }
        const double y = double(t.getOrigin().y());
        tr.maxSpeed = std::max(tr.maxSpeed, double(rb->getLinearVelocity().length()));
        tr.maxOmega = std::max(tr.maxOmega, double(rb->getAngularVelocity().length()));
        tr.maxY = std::max(tr.maxY, y);
        tr.minY = std::min(tr.minY, y);
        if (y < speedBelow) tr.maxSpeedBelow = std::max(tr.maxSpeedBelow, double(rb->getLinearVelocity().length()));
        if (y < afterBelow) below = true;
        if (below) tr.maxYAfter = std::max(tr.maxYAfter, y);
        const btTransform mesh = w.body(i).getMeshWorldTransform();
        for (const Eigen::Vector3d& v : w.body(i).getShape()->getMesh().vertices)
            tr.minLowest = std::min(tr.minLowest, double((mesh * btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()))).y()));
        if (f >= lastStretch) {
            tr.meanMeshY += double(w.body(i).getMeshWorldTransform().getOrigin().y());
            ++averaged;
        }
    }
    const btRigidBody* rb = w.rigid(i);
    tr.speed = double((rb->getCenterOfMassPosition() - pMark).length()) / std::max(1e-9, w.time() - tMark);
    tr.omega = double(rb->getAngularVelocity().length());
    tr.y = double(rb->getCenterOfMassPosition().y());
    tr.meanMeshY /= std::max(1, averaged);
    tr.last = w.body(i).getMeshWorldTransform();
    return tr;
}

btTransform makePose(const btVector3& position, const btVector3& axis, double degrees) {
    btTransform t;
    t.setIdentity();
    t.setOrigin(position);
    if (degrees != 0) t.setRotation(btQuaternion(axis.normalized(), btScalar(degrees * M_PI / 180.0)));
    return t;
}

double tiltDegrees(const btTransform& t) {
    double best = 0;
    for (int k = 0; k < 3; ++k) best = std::max(best, std::abs(double(t.getBasis()[1][k])));
    return std::acos(std::min(1.0, best)) * 180.0 / M_PI;
}

double oracleEquilibriumLevel(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris,
                              const btTransform& meshPose, double volume) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) pose.linear()(i, j) = double(meshPose.getBasis()[i][j]);
        pose.translation()[i] = double(meshPose.getOrigin()[i]);
    }
    const std::vector<Eigen::Vector3d> posed = oraclePose(verts, pose);
    double lo = posed[0].y(), hi = posed[0].y();
    for (const auto& v : posed) {
        lo = std::min(lo, v.y());
        hi = std::max(hi, v.y());
    }
    for (int it = 0; it < 100; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (oracleSubmergedMoments(posed, tris, mid).volume < volume) lo = mid;
        else hi = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace buoyancy_test
