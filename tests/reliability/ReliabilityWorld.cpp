#include "reliability/ReliabilityWorld.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>

#include <cfenv>
#include <cmath>
#include <fstream>
#include <unistd.h>

namespace reliability_test {

ReliabilityWorld::ReliabilityWorld() {
    m_world = std::make_unique<btDiscreteDynamicsWorld>(&m_dispatcher, &m_broadphase, &m_solver, &m_config);
    m_world->setGravity(btVector3(0, btScalar(-9.81), 0));
    btGImpactCollisionAlgorithm::registerAlgorithm(&m_dispatcher);
    m_water = std::make_unique<btBuoyancyWorld>(&m_surface, 1000.0, 9.81);
    m_world->setInternalTickCallback(&ReliabilityWorld::tick, this);
}

ReliabilityWorld::~ReliabilityWorld() {
    for (auto& a : m_actions) m_world->removeAction(a.get());
    for (auto& b : m_bodies)
        if (b->getRigidBody()->getBroadphaseHandle()) m_world->removeRigidBody(b->getRigidBody());
    if (m_ground) m_world->removeRigidBody(m_ground.get());
    m_actions.clear();
}

std::size_t ReliabilityWorld::add(std::shared_ptr<const btBuoyancyShape> shape, const btBuoyantBodySettings& body,
                                  const btTransform& meshPose, const btBuoyancySettings& buoyancy) {
    auto b = std::make_unique<btBuoyantBody>(std::move(shape), body, meshPose);
    auto a = std::make_unique<btBuoyancyAction>(*b, m_water.get(), buoyancy);
    m_world->addRigidBody(b->getRigidBody());
    m_world->addAction(a.get());
    m_bodies.push_back(std::move(b));
    m_actions.push_back(std::move(a));
    return m_bodies.size() - 1;
}

void ReliabilityWorld::addGround(double h) {
    m_groundShape = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(h));
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, m_groundShape.get());
    info.m_friction = 0.8;
    m_ground = std::make_unique<btRigidBody>(info);
    m_world->addRigidBody(m_ground.get());
}

void ReliabilityWorld::step(int frames, int n, double dt) {
    for (int f = 0; f < frames; ++f) m_world->stepSimulation(btScalar(dt * n), n, btScalar(dt));
}

std::uint64_t ReliabilityWorld::rejectedTotal() const {
    std::uint64_t r = 0;
    for (const auto& a : m_actions) r += a->getRejectedCount();
    return r;
}

void ReliabilityWorld::tick(btDynamicsWorld* world, btScalar) {
    auto* self = static_cast<ReliabilityWorld*>(world->getWorldUserInfo());
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

ScopedFpTrapsOff::ScopedFpTrapsOff() {
#if defined(__GLIBC__)
    m_saved = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
#endif
}

ScopedFpTrapsOff::~ScopedFpTrapsOff() {
#if defined(__GLIBC__)
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(m_saved);
#endif
}

btTransform pose(const btVector3& position, const btVector3& axis, double degrees) {
    btTransform t;
    t.setIdentity();
    t.setOrigin(position);
    if (degrees != 0) t.setRotation(btQuaternion(axis.normalized(), btScalar(degrees * M_PI / 180.0)));
    return t;
}

std::size_t residentBytes() {
    std::ifstream in("/proc/self/statm");
    std::size_t size = 0, resident = 0;
    in >> size >> resident;
    return resident * std::size_t(::sysconf(_SC_PAGESIZE));
}

}  // namespace reliability_test
