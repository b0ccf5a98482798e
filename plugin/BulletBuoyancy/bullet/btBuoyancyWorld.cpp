#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletBuoyancy/bullet/btBuoyancyDeviceBackend.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

btBuoyancyWorld::btBuoyancyWorld(const btWaterSurface* water, double fluidDensity, double gravity)
    : m_water(water), m_fluidDensity(1000.0), m_gravity(9.81) {
    setFluidDensity(fluidDensity);
    setGravity(gravity);
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
}

void btBuoyancyWorld::beginSubstepIfNew(std::uint64_t& lastSeen, double dt) {
    if (m_substep == 0 || lastSeen == m_substep) {
        ++m_substep;
        m_time += dt;
        // A batching backend computes every registered action's result from here on (at the first request).
        if (m_device) m_device->beginSubstep(dt);
    }
    lastSeen = m_substep;
}

void btBuoyancyWorld::setDeviceBackend(std::unique_ptr<btBuoyancyDeviceBackend> backend) {
    m_device = std::move(backend);
}

std::uint64_t btBuoyancyWorld::registerAction(btBuoyancyAction* action) {
    m_actions.push_back(action);
    return m_registrations++;
}

void btBuoyancyWorld::unregisterAction(btBuoyancyAction* action) {
    m_actions.erase(std::remove(m_actions.begin(), m_actions.end(), action), m_actions.end());
}
