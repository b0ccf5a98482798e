#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletBuoyancy/bullet/btBuoyancyDeviceBackend.h>

#include <BulletDynamics/Dynamics/btDynamicsWorld.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace {
/// Largest angle between the world's gravity and the water's down direction still taken as "down", rad.
constexpr double kGravityAngleTolerance = 1e-6;

std::string vectorText(double x, double y, double z) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", x, y, z);
    return buf;
}
}  // namespace

const char* btBuoyancyStatusMessage(btBuoyancyStatus status) {
    switch (status) {
    case btBuoyancyStatus::Ok: return "ok";
    case btBuoyancyStatus::NoGravity: return "the world's gravity is zero: no pressure gradient, no buoyancy";
    case btBuoyancyStatus::GravityNotAlongWaterUp:
        return "the world's gravity does not point down the water's up axis (0, 1, 0): no buoyancy";
    }
    return "unknown status";
}

btBuoyancyWorld::btBuoyancyWorld(btDynamicsWorld* world, const btWaterSurface* water, double fluidDensity)
    : m_dynamicsWorld(world), m_water(water), m_fluidDensity(1000.0), m_gravity(9.81) {
    if (!world) throw std::invalid_argument("btBuoyancyWorld: world: must not be null");
    setFluidDensity(fluidDensity);
    const btVector3 g = world->getGravity();
    followGravity(double(g.x()), double(g.y()), double(g.z()));
    if (m_gravityStatus == btBuoyancyStatus::GravityNotAlongWaterUp)
        throw std::invalid_argument("btBuoyancyWorld: the world's gravity " +
                                    vectorText(double(g.x()), double(g.y()), double(g.z())) +
                                    " m/s^2 does not point down the water's up axis (0, 1, 0): the water surfaces are "
                                    "height fields along +y, so give the world a gravity along -y");
}

btBuoyancyWorld::btBuoyancyWorld(const btWaterSurface* water, double fluidDensity, double gravity)
    : m_water(water), m_fluidDensity(1000.0), m_gravity(9.81) {
    setFluidDensity(fluidDensity);
    setGravity(gravity);
}

void btBuoyancyWorld::followGravity(double gx, double gy, double gz) {
    const double magnitude = std::sqrt(gx * gx + gy * gy + gz * gz);
    if (!std::isfinite(magnitude) || magnitude == 0.0) {
        m_gravity = 0.0;
        m_gravityStatus = std::isfinite(magnitude) ? btBuoyancyStatus::NoGravity : btBuoyancyStatus::GravityNotAlongWaterUp;
        return;
    }
    // Angle between g and the water's down (0, −1, 0), from the horizontal part (accurate at small angles).
    const double angle = std::atan2(std::hypot(gx, gz), -gy);
    if (angle > kGravityAngleTolerance) {
        m_gravity = 0.0;
        m_gravityStatus = btBuoyancyStatus::GravityNotAlongWaterUp;
        return;
    }
    m_gravity = magnitude;
    m_gravityStatus = btBuoyancyStatus::Ok;
}

btBuoyancyWorld::~btBuoyancyWorld() = default;

void btBuoyancyWorld::setFluidDensity(double density) {
    if (!std::isfinite(density) || density <= 0.0)
        throw std::invalid_argument("fluidDensity: must be a finite number > 0 (got " + std::to_string(density) + ")");
    m_fluidDensity = density;
}

void btBuoyancyWorld::setGravity(double g) {
    if (!std::isfinite(g) || g < 0.0)
        throw std::invalid_argument("gravity: must be a finite number >= 0 (got " + std::to_string(g) + ")");
    m_gravity = g;
    m_gravityStatus = g > 0.0 ? btBuoyancyStatus::Ok : btBuoyancyStatus::NoGravity;
}

void btBuoyancyWorld::beginSubstepIfNew(std::uint64_t& lastSeen, double dt, const btCollisionWorld* from) {
    if (m_substep == 0 || lastSeen == m_substep) {
        ++m_substep;
        m_time += dt;
        // The world's gravity of this substep: the world given to the constructor, else the one stepping us.
        const btDynamicsWorld* world = m_dynamicsWorld ? m_dynamicsWorld : dynamic_cast<const btDynamicsWorld*>(from);
        if (world) {
            const btVector3 g = world->getGravity();
            followGravity(double(g.x()), double(g.y()), double(g.z()));
        }
        // A batching backend computes every registered action's result from here on (at the first request); else
        // the bodies of the batch are evaluated now, across the threads (btBuoyancyThreads.cpp).
        if (m_device)
            m_device->beginSubstep(dt);
        else if (m_batching)
            evaluateBatch(from ? from : m_dynamicsWorld, dt);
        else
            m_lastBatchSize = 0;
    }
    lastSeen = m_substep;
}

void btBuoyancyWorld::setDeviceBackend(std::unique_ptr<btBuoyancyDeviceBackend> backend) {
    m_device = std::move(backend);
}

std::uint64_t btBuoyancyWorld::registerAction(btBuoyancyAction* action) {
    if (m_inBatch.load())
        throw std::logic_error("btBuoyancyAction: created while its btBuoyancyWorld evaluates a substep's bodies in "
                               "parallel; create and destroy actions between steps");
    m_batchDirty = true;
    m_actions.push_back(action);
    return m_registrations++;
}

void btBuoyancyWorld::unregisterAction(btBuoyancyAction* action) {
    if (m_inBatch.load()) {
        // Called from an action's destructor (noexcept): refused with a message, never a data race.
        std::fprintf(stderr, "btBuoyancyAction: destroyed while its btBuoyancyWorld evaluates a substep's bodies in "
                             "parallel; create and destroy actions between steps\n");
        std::abort();
    }
    m_batchDirty = true;
    m_batch.erase(std::remove(m_batch.begin(), m_batch.end(), action), m_batch.end());
    m_actions.erase(std::remove(m_actions.begin(), m_actions.end(), action), m_actions.end());
}
