#include <BulletBuoyancy/bullet/btBuoyancyImmediate.h>

#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>
#include <stdexcept>

btBuoyancyImmediate::btBuoyancyImmediate(btRigidBody* body, const btBuoyancySettings& settings)
    : m_context(nullptr, 1000.0, 0.0) {
    m_context.setBatching(false);  // one body, evaluated in its own call
    m_action = std::make_unique<btBuoyancyAction>(body, &m_context, settings);
    m_action->m_outsideWorld = true;
}

btBuoyancyImmediate::btBuoyancyImmediate(btRigidBody* body, std::shared_ptr<const btBuoyancyShape> shape,
                                         const btBuoyancySettings& settings, const btTransform& meshInCom)
    : m_context(nullptr, 1000.0, 0.0) {
    m_context.setBatching(false);
    m_action = std::make_unique<btBuoyancyAction>(body, std::move(shape), &m_context, settings, meshInCom);
    m_action->m_outsideWorld = true;
}

const btBuoyancyResult& btBuoyancyImmediate::applyBuoyancyImpulse(const btWaterSurface& water, const btVector3& gravity,
                                                                  double fluidDensity, double time, double dt) {
    const double gx = double(gravity.x()), gy = double(gravity.y()), gz = double(gravity.z());
    if (!std::isfinite(gx) || !std::isfinite(gy) || !std::isfinite(gz))
        throw std::invalid_argument("applyBuoyancyImpulse: gravity is not finite");
    if (!std::isfinite(time)) throw std::invalid_argument("applyBuoyancyImpulse: time is not finite");
    if (fluidDensity != m_context.getFluidDensity()) m_context.setFluidDensity(fluidDensity);  // checks it
    m_context.setWater(&water);
    m_context.followGravity(gx, gy, gz);
    // The weight the loop applies: the added mass counts on it (the body's own gravity, as Bullet's world sets it).
    btRigidBody* body = m_action->getRigidBody();
    if (!(body->getGravity() == gravity)) body->setGravity(gravity);
    // The action's substep advances the clock by dt to the end of the step: start it dt earlier.
    if (dt > 0 && std::isfinite(dt)) m_context.setTime(time - dt);
    m_action->updateAction(nullptr, btScalar(dt));
    m_context.setWater(nullptr);  // the caller's surface is not kept
    return m_action->getLastResult();
}

std::vector<unsigned char> btBuoyancyImmediate::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::Immediate);
    out.blob(m_context.saveState());
    out.blob(m_action->saveState());
    return out.bytes();
}

void btBuoyancyImmediate::restoreState(const unsigned char* data, std::size_t size) {
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::Immediate, "btBuoyancyImmediate::restoreState");
    const std::vector<unsigned char> context = in.blob("context");
    const std::vector<unsigned char> action = in.blob("evaluation");
    in.finish();
    // Each part checks itself; if the second refuses after the first applied, the first is put back as it was.
    const std::vector<unsigned char> before = m_context.saveState();
    m_context.restoreState(context);
    try {
        m_action->restoreState(action);
    } catch (...) {
        m_context.restoreState(before);
        throw;
    }
}
