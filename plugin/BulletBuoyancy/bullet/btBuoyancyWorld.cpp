#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletBuoyancy/bullet/btBuoyancyDeviceBackend.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btDynamicsWorld.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace {
/// Largest angle between the world's gravity and the water frame's down direction still taken as "down", rad.
constexpr double kGravityAngleTolerance = 1e-6;

/// "[x, y, z]" of a box corner, m.
std::string cornerText(const Eigen::Vector3d& v) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "[%.6g, %.6g, %.6g]", v.x(), v.y(), v.z());
    return buf;
}

/// "water body \"pool\" (region [..] to [..])".
std::string waterBodyText(const btWaterBody& b) {
    return "water body \"" + b.name + "\" (region " + cornerText(b.regionMin) + " to " + cornerText(b.regionMax) + ")";
}

std::string angleText(double radians) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", radians);
    return buf;
}
}  // namespace

const char* btBuoyancyStatusMessage(btBuoyancyStatus status) {
    switch (status) {
    case btBuoyancyStatus::Ok: return "ok";
    case btBuoyancyStatus::NoGravity: return "the world's gravity is zero: no pressure gradient, no buoyancy";
    case btBuoyancyStatus::GravityNotAlongWaterUp:
        return "the world's gravity does not point down the water frame's up axis: no buoyancy";
    }
    return "unknown status";
}

btBuoyancyWorld::btBuoyancyWorld(btDynamicsWorld* world, const btWaterSurface* water, double fluidDensity)
    : m_dynamicsWorld(world), m_water(water), m_fluidDensity(1000.0), m_gravity(9.81) {
    if (!world) throw std::invalid_argument("btBuoyancyWorld: world: must not be null");
    setFluidDensity(fluidDensity);
    const btVector3 g = world->getGravity();
    const Eigen::Vector3d gv(double(g.x()), double(g.y()), double(g.z()));
    if (!gv.allFinite())
        throw std::invalid_argument("btBuoyancyWorld: the world's gravity " + btWaterFrame::vectorText(gv) +
                                    " m/s^2 is not finite");
    followGravity(gv.x(), gv.y(), gv.z());  // derives the frame from a non-zero gravity
}

btBuoyancyWorld::btBuoyancyWorld(btDynamicsWorld* world, const btWaterSurface* water, const btWaterFrame& frame,
                                 double fluidDensity)
    : m_dynamicsWorld(world), m_water(water), m_fluidDensity(1000.0), m_gravity(9.81) {
    if (!world) throw std::invalid_argument("btBuoyancyWorld: world: must not be null");
    setFluidDensity(fluidDensity);
    const btVector3 g = world->getGravity();
    m_gravityVector = Eigen::Vector3d(double(g.x()), double(g.y()), double(g.z()));
    m_gravityKnown = true;
    setWaterFrame(frame);  // checks it against the world's gravity, and sets the status
}

btBuoyancyWorld::btBuoyancyWorld(const btWaterSurface* water, double fluidDensity, double gravity)
    : m_water(water), m_fluidDensity(1000.0), m_gravity(9.81) {
    setFluidDensity(fluidDensity);
    setGravity(gravity);
    m_gravityKnown = false;  // the world stepping the actions tells (beginSubstepIfNew)
}

void btBuoyancyWorld::setWaterFrame(const btWaterFrame& frame) {
    if (m_dynamicsWorld) {  // the world's gravity now (it may have changed since the last substep)
        const btVector3 g = m_dynamicsWorld->getGravity();
        m_gravityVector = Eigen::Vector3d(double(g.x()), double(g.y()), double(g.z()));
        m_gravityKnown = true;
    }
    const double magnitude = m_gravityVector.norm();
    if (m_gravityKnown && std::isfinite(magnitude) && magnitude > 0) {
        const double angle = frame.angleToGravity(m_gravityVector);
        if (!(angle <= kGravityAngleTolerance))
            throw std::invalid_argument(
                "btBuoyancyWorld: the water frame's up " + btWaterFrame::vectorText(frame.up()) +
                " is not antiparallel to the world's gravity " + btWaterFrame::vectorText(m_gravityVector) +
                " m/s^2 (" + angleText(angle) + " rad apart, 1e-6 allowed): give the frame up = -gravity");
    }
    m_frame = frame;
    m_frameFixed = true;
    ++m_frameVersion;
    if (m_gravityKnown) followGravity(m_gravityVector.x(), m_gravityVector.y(), m_gravityVector.z());  // the status
}

std::string btBuoyancyWorld::getGravityStatusMessage() const {
    switch (m_gravityStatus) {
    case btBuoyancyStatus::Ok: return "ok";
    case btBuoyancyStatus::NoGravity: return btBuoyancyStatusMessage(m_gravityStatus);
    case btBuoyancyStatus::GravityNotAlongWaterUp:
        return "the world's gravity " + btWaterFrame::vectorText(m_gravityVector) +
               " m/s^2 does not point down the water frame's up axis " + btWaterFrame::vectorText(m_frame.up()) +
               ": no buoyancy";
    }
    return "unknown status";
}

void btBuoyancyWorld::followGravity(double gx, double gy, double gz) {
    m_gravityVector = Eigen::Vector3d(gx, gy, gz);
    m_gravityKnown = true;
    const double magnitude = m_gravityVector.norm();
    if (!std::isfinite(magnitude) || magnitude == 0.0) {
        m_gravity = 0.0;
        m_gravityStatus = std::isfinite(magnitude) ? btBuoyancyStatus::NoGravity : btBuoyancyStatus::GravityNotAlongWaterUp;
        return;
    }
    // The default frame follows the first non-zero gravity and stays (a later change is checked against it).
    if (!m_frameFixed) {
        m_frame = btWaterFrame::fromGravity(m_gravityVector);
        m_frameFixed = true;
        ++m_frameVersion;
    }
    if (!(m_frame.angleToGravity(m_gravityVector) <= kGravityAngleTolerance)) {
        m_gravity = 0.0;
        m_gravityStatus = btBuoyancyStatus::GravityNotAlongWaterUp;
        return;
    }
    m_gravity = magnitude;
    m_gravityStatus = btBuoyancyStatus::Ok;
}

btBuoyancyWorld::~btBuoyancyWorld() = default;

void btBuoyancyWorld::setWater(const btWaterSurface* water) {
    if (water && !m_waterBodies.empty())
        throw std::invalid_argument("btBuoyancyWorld::setWater: the world has " + std::to_string(m_waterBodies.size()) +
                                    " water bodies: an unbounded water and water bodies cannot be combined "
                                    "(removeAllWaterBodies first)");
    m_water = water;
}

int btBuoyancyWorld::addWaterBody(const btWaterBodyInfo& info) {
    const std::string who = "btBuoyancyWorld::addWaterBody: ";
    if (m_inBatch.load())
        throw std::logic_error(who + "called while the world evaluates a substep's bodies; add water bodies between steps");
    btWaterBody body;
    body.name = info.name.empty() ? "water body " + std::to_string(m_waterBodies.size()) : info.name;
    body.surface = info.surface;
    body.fluidDensity = info.fluidDensity;
    body.regionMin = Eigen::Vector3d(double(info.regionMin.x()), double(info.regionMin.y()), double(info.regionMin.z()));
    body.regionMax = Eigen::Vector3d(double(info.regionMax.x()), double(info.regionMax.y()), double(info.regionMax.z()));
    const std::string named = who + "\"" + body.name + "\": ";
    if (m_water)
        throw std::invalid_argument(named + "the world has an unbounded water: an unbounded water and water bodies "
                                            "cannot be combined (construct the world with water = nullptr, or "
                                            "setWater(nullptr) first)");
    if (!body.surface) throw std::invalid_argument(named + "surface: must not be null");
    if (!std::isfinite(body.fluidDensity) || !(body.fluidDensity > 0))
        throw std::invalid_argument(named + "fluidDensity: must be a finite number > 0 (got " +
                                    std::to_string(body.fluidDensity) + ")");
    static const char* const axes[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(body.regionMin[k]))
            throw std::invalid_argument(named + "regionMin." + axes[k] + ": must be finite");
        if (!std::isfinite(body.regionMax[k]))
            throw std::invalid_argument(named + "regionMax." + axes[k] + ": must be finite");
        if (!(body.regionMin[k] < body.regionMax[k]))
            throw std::invalid_argument(named + "regionMax." + axes[k] + ": must be greater than regionMin." + axes[k] +
                                        " (" + cornerText(body.regionMin) + " to " + cornerText(body.regionMax) + ")");
    }
    for (const btWaterBody& other : m_waterBodies) {
        // Boxes overlap when their open interiors meet on every axis (touching faces are accepted).
        const bool overlap = (body.regionMin.array() < other.regionMax.array()).all() &&
                             (other.regionMin.array() < body.regionMax.array()).all();
        if (overlap)
            throw std::invalid_argument(who + waterBodyText(body) + " overlaps " + waterBodyText(other) +
                                        ": the regions of water bodies must not overlap");
    }
    m_waterBodies.push_back(body);
    m_anyWaterBodyTimeVarying = m_anyWaterBodyTimeVarying || body.surface->isTimeVarying();
    return int(m_waterBodies.size()) - 1;
}

void btBuoyancyWorld::removeAllWaterBodies() {
    if (m_inBatch.load())
        throw std::logic_error("btBuoyancyWorld::removeAllWaterBodies: called while the world evaluates a substep's "
                               "bodies; change water bodies between steps");
    m_waterBodies.clear();
    m_anyWaterBodyTimeVarying = false;
}

int btBuoyancyWorld::findWaterBody(const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& point) const {
    int best = -1;
    double bestDistance = 0;
    for (std::size_t i = 0; i < m_waterBodies.size(); ++i) {
        const btWaterBody& b = m_waterBodies[i];
        if (!(b.distanceTo(centre) <= radius)) continue;  // the sphere does not reach the box
        const double d = b.distanceTo(point);
        if (best < 0 || d < bestDistance) {
            best = int(i);
            bestDistance = d;
        }
    }
    return best;
}

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
    // Gravity along the water frame's down (for actions stepped without a dynamics world).
    m_gravityVector = -g * m_frame.up();
    m_gravityKnown = true;
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
