#include "bullet/BulletTestWorld.h"

#include "oracles/PolyhedralOracle.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>

#include <algorithm>
#include <cmath>

namespace buoyancy_test {

BulletTestWorld::BulletTestWorld(double waterLevel, double g) : m_surface(waterLevel) {
    m_world = std::make_unique<btDiscreteDynamicsWorld>(&m_dispatcher, &m_broadphase, &m_solver, &m_config);
    m_world->setGravity(btVector3(0, btScalar(-g), 0));
    btGImpactCollisionAlgorithm::registerAlgorithm(&m_dispatcher);
    m_water = std::make_unique<btBuoyancyWorld>(&m_surface, 1000.0, g);
}

BulletTestWorld::~BulletTestWorld() {
    for (auto& a : m_actions) m_world->removeAction(a.get());
    for (auto& b : m_bodies) m_world->removeRigidBody(b->getRigidBody());
    if (m_ground) m_world->removeRigidBody(m_ground.get());
    m_actions.clear();
}

std::size_t BulletTestWorld::add(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& body,
                                 const btTransform& meshPose, const btBuoyancySettings& buoyancy) {
    m_bodies.push_back(std::make_unique<btBuoyantBody>(std::move(shape), body, meshPose));
    m_world->addRigidBody(m_bodies.back()->getRigidBody());
    m_actions.push_back(std::make_unique<btBuoyancyAction>(*m_bodies.back(), m_water.get(), buoyancy));
    m_world->addAction(m_actions.back().get());
    return m_bodies.size() - 1;
}

void BulletTestWorld::addGround(double h) {
    m_groundShape = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(h));
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, m_groundShape.get());
    info.m_friction = 0.8;
    info.m_rollingFriction = 0.1;   // a seabed, as the scene runner's "ground": sunk round bodies stop rolling
    info.m_spinningFriction = 0.05; // ... and sunk bodies stop spinning about the vertical
    m_ground = std::make_unique<btRigidBody>(info);
    m_world->addRigidBody(m_ground.get());
}

void BulletTestWorld::step(int frames, int n, double dt) {
    for (int f = 0; f < frames; ++f) {
        m_world->stepSimulation(btScalar(dt * n), n, btScalar(dt));
        m_time += dt * n;
    }
}

void BulletTestWorld::run(double seconds, int n, double dt) {
    step(static_cast<int>(std::ceil(seconds / (dt * n) - 1e-9)), n, dt);
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
