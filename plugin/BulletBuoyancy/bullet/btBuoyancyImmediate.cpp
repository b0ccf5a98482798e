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

btBuoyancyImmediate::btBuoyancyImmediate(btBuoyancyBody& body, std::shared_ptr<const btBuoyancyShape> shape,
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
    // (Another body type's getGravity() is its own to keep equal to it.)
    if (btRigidBody* body = m_action->getRigidBody(); body && !(body->getGravity() == gravity)) body->setGravity(gravity);
    // The action's substep advances the clock by dt to the end of the step: start it dt earlier.
    if (dt > 0 && std::isfinite(dt)) m_context.setTime(time - dt);
    m_action->updateAction(nullptr, btScalar(dt));
    m_context.setWater(nullptr);  // the caller's surface is not kept (its address is: the warm starts' owner)
    m_lastWater = &water;
    return m_action->getLastResult();
}

std::vector<unsigned char> btBuoyancyImmediate::saveState() const {
    // The evaluation names its warm starts' water by its place in the context: lend it the last water for the save.
    btBuoyancyWorld& context = const_cast<btBuoyancyWorld&>(m_context);
    context.setWater(m_lastWater);
    btBuoyancyStateWriter out(btBuoyancyStateKind::Immediate);
    try {
        out.blob(m_context.saveState());
        out.blob(m_action->saveState());
    } catch (...) {
        context.setWater(nullptr);
        throw;
    }
    context.setWater(nullptr);
    return out.bytes();
}

void btBuoyancyImmediate::restoreState(const unsigned char* data, std::size_t size, const btWaterSurface* water) {
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::Immediate, "btBuoyancyImmediate::restoreState");
    const std::vector<unsigned char> context = in.blob("context");
    const std::vector<unsigned char> action = in.blob("evaluation");
    in.finish();
    const btWaterSurface* next = water ? water : m_lastWater;
    // Each part checks itself; if the second refuses after the first applied, the first is put back as it was.
    m_context.setWater(m_lastWater);
    const std::vector<unsigned char> before = m_context.saveState();
    m_context.setWater(next);  // the warm starts are read for the water of the next steps
    try {
        m_context.restoreState(context);
        m_action->restoreState(action);
    } catch (...) {
        m_context.restoreState(before);
        m_context.setWater(nullptr);
        throw;
    }
    m_context.setWater(nullptr);
    m_lastWater = next;
}
