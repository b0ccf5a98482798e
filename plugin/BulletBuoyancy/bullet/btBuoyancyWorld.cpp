#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletBuoyancy/bullet/btBuoyancyState.h>

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeviceBackend.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btDynamicsWorld.h>
#include <LinearMath/btIDebugDraw.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace {
/// Largest angle between the world's gravity and the water frame's down direction still taken as "down", rad.
constexpr double kGravityAngleTolerance = 1e-6;

/// "water body \"pool\" (region box [..] to [..])".
std::string waterBodyText(const btWaterBody& b) { return "water body \"" + b.name + "\" (region " + b.regionText() + ")"; }

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


void btBuoyancyWorld::setWater(const btWaterSurface* water) {
    if (water && !m_waterBodies.empty())
        throw std::invalid_argument("btBuoyancyWorld::setWater: the world has " + std::to_string(m_waterBodies.size()) +
                                    " water bodies: an unbounded water and water bodies cannot be combined "
                                    "(removeAllWaterBodies first)");
    m_water = water;
}

int btBuoyancyWorld::addWaterBody(const btWaterBodyInfo& info) {
    const std::string who = "btBuoyancyWorld::addWaterBody: ";
    if (m_dispatching)
        throw std::logic_error(who + "called from a water event callback (inside stepSimulation); add water bodies "
                                     "between steps");
    if (m_inBatch.load())
        throw std::logic_error(who + "called while the world evaluates a substep's bodies; add water bodies between steps");
    btWaterBody body;
    body.name = info.name.empty() ? "water body " + std::to_string(m_waterBodies.size()) : info.name;
    body.surface = info.surface;
    body.fluidDensity = info.fluidDensity;
    const std::string named = who + "\"" + body.name + "\": ";
    if (m_water)
        throw std::invalid_argument(named + "the world has an unbounded water: an unbounded water and water bodies "
                                            "cannot be combined (construct the world with water = nullptr, or "
                                            "setWater(nullptr) first)");
    if (!body.surface) throw std::invalid_argument(named + "surface: must not be null");
    if (!std::isfinite(body.fluidDensity) || !(body.fluidDensity > 0))
        throw std::invalid_argument(named + "fluidDensity: must be a finite number > 0 (got " +
                                    std::to_string(body.fluidDensity) + ")");
    body.setRegion(info, m_frame, named);
    for (const btWaterBody& other : m_waterBodies) {
        // Regions overlap when their interiors meet (regions sharing only a face, an edge or a corner are accepted).
        if (body.overlaps(other, m_frame))
            throw std::invalid_argument(who + waterBodyText(body) + " overlaps " + waterBodyText(other) +
                                        ": the regions of water bodies must not overlap");
    }
    m_waterBodies.push_back(body);
    m_anyWaterBodyTimeVarying = m_anyWaterBodyTimeVarying || body.surface->isTimeVarying();
    return int(m_waterBodies.size()) - 1;
}

void btBuoyancyWorld::removeAllWaterBodies() {
    if (m_dispatching)
        throw std::logic_error("btBuoyancyWorld::removeAllWaterBodies: called from a water event callback (inside "
                               "stepSimulation); change water bodies between steps");
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
        if (!(b.distanceTo(m_frame, centre) <= radius)) continue;  // the sphere does not reach the region
        const double d = b.distanceTo(m_frame, point);
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
        finishPrebuilds();  // the heights queried ahead while Bullet stepped (btBuoyancyThreads.cpp)
        m_prebuildPatches = false;
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
    if (m_dispatching)
        throw std::logic_error("btBuoyancyAction: created from a water event callback of its btBuoyancyWorld (inside "
                               "stepSimulation); create and destroy actions between steps");
    if (m_inBatch.load())
        throw std::logic_error("btBuoyancyAction: created while its btBuoyancyWorld evaluates a substep's bodies in "
                               "parallel; create and destroy actions between steps");
    m_batchDirty = true;
    m_actions.push_back(action);
    m_deviceBodies.push_back(action);
    return m_registrations++;
}

void btBuoyancyWorld::unregisterAction(btBuoyancyAction* action) {
    finishPrebuilds();
    if (m_dispatching) {
        // Called from an action's destructor (noexcept) while an action's events are delivered: refused with a
        // message, never a use of a destroyed action.
        std::fprintf(stderr, "btBuoyancyAction: destroyed from a water event callback of its btBuoyancyWorld (inside "
                             "stepSimulation); create and destroy actions between steps\n");
        std::abort();
    }
    if (m_inBatch.load()) {
        // Called from an action's destructor (noexcept): refused with a message, never a data race.
        std::fprintf(stderr, "btBuoyancyAction: destroyed while its btBuoyancyWorld evaluates a substep's bodies in "
                             "parallel; create and destroy actions between steps\n");
        std::abort();
    }
    m_batchDirty = true;
    m_batch.erase(std::remove(m_batch.begin(), m_batch.end(), action), m_batch.end());
    m_actions.erase(std::remove(m_actions.begin(), m_actions.end(), action), m_actions.end());
    btBuoyancyDeviceBody* const body = action;
    m_deviceBodies.erase(std::remove(m_deviceBodies.begin(), m_deviceBodies.end(), body), m_deviceBodies.end());
}

void btBuoyancyWorld::registerFloodingAction(btFloodingAction* action) {
    if (m_dispatching || m_inBatch.load())
        throw std::logic_error("btFloodingAction: created while its btBuoyancyWorld steps (inside stepSimulation); "
                               "create and destroy actions between steps");
    m_floodingBatchDirty = true;
    m_floodingActions.push_back(action);
}

void btBuoyancyWorld::registerTimeVaryingMassAction(btTimeVaryingMassAction* action) {
    if (m_dispatching || m_inBatch.load())
        throw std::logic_error("btTimeVaryingMassAction: created while its btBuoyancyWorld steps (inside "
                               "stepSimulation); create and destroy actions between steps");
    m_massBatchDirty = true;
    m_massActions.push_back(action);
}

void btBuoyancyWorld::unregisterTimeVaryingMassAction(btTimeVaryingMassAction* action) {
    if (m_inBatch.load()) {
        // Called from an action's destructor (noexcept): refused with a message, never a data race.
        std::fprintf(stderr, "btTimeVaryingMassAction: destroyed while its btBuoyancyWorld recomputes a substep's mass "
                             "properties in parallel; create and destroy actions between steps\n");
        std::abort();
    }
    m_massBatchDirty = true;
    m_massBatch.erase(std::remove(m_massBatch.begin(), m_massBatch.end(), action), m_massBatch.end());
    m_massRecomputes.erase(std::remove(m_massRecomputes.begin(), m_massRecomputes.end(), action),
                           m_massRecomputes.end());
    m_massActions.erase(std::remove(m_massActions.begin(), m_massActions.end(), action), m_massActions.end());
}

void btBuoyancyWorld::unregisterFloodingAction(btFloodingAction* action) {
    if (m_inBatch.load()) {
        // Called from an action's destructor (noexcept): refused with a message, never a data race.
        std::fprintf(stderr, "btFloodingAction: destroyed while its btBuoyancyWorld moves the water of a substep in "
                             "parallel; create and destroy actions between steps\n");
        std::abort();
    }
    m_floodingBatchDirty = true;
    m_floodingBatch.erase(std::remove(m_floodingBatch.begin(), m_floodingBatch.end(), action), m_floodingBatch.end());
    m_floodingActions.erase(std::remove(m_floodingActions.begin(), m_floodingActions.end(), action),
                            m_floodingActions.end());
}

// ---- Events and queries for game logic (btBuoyancyEvents.h) ----

void btBuoyancyWorld::addEventListener(btBuoyancyEventListener* listener) {
    if (!listener) throw std::invalid_argument("btBuoyancyWorld::addEventListener: listener: must not be null");
    if (std::find(m_listeners.begin(), m_listeners.end(), listener) != m_listeners.end()) return;
    m_listeners.push_back(listener);
}

void btBuoyancyWorld::removeEventListener(btBuoyancyEventListener* listener) {
    if (!listener) return;
    if (m_dispatching) {
        // The dispatch walks the array by index: the entry is emptied now and dropped when the dispatch ends.
        for (btBuoyancyEventListener*& l : m_listeners)
            if (l == listener) {
                l = nullptr;
                m_listenersRemoved = true;
            }
        return;
    }
    m_listeners.erase(std::remove(m_listeners.begin(), m_listeners.end(), listener), m_listeners.end());
}

void btBuoyancyWorld::setEventSettings(const btBuoyancyEventSettings& settings) {
    settings.validate();
    m_eventSettings = settings;
}

void btBuoyancyWorld::dispatchEvents(btBuoyancyAction& action, const btBuoyancyEventType* types,
                                     const int* waterBodies, int count, double submergedFraction) {
    if (count <= 0 || m_listeners.empty()) return;
    // The flag refuses actions and water bodies made or destroyed by a callback; it is cleared and the listeners
    // removed by a callback are dropped even when a callback throws.
    struct Dispatching {
        btBuoyancyWorld& world;
        explicit Dispatching(btBuoyancyWorld& w) : world(w) { world.m_dispatching = true; }
        ~Dispatching() {
            world.m_dispatching = false;
            if (world.m_listenersRemoved) {
                world.m_listeners.erase(std::remove(world.m_listeners.begin(), world.m_listeners.end(), nullptr),
                                        world.m_listeners.end());
                world.m_listenersRemoved = false;
            }
        }
    } dispatching(*this);
    for (int k = 0; k < count; ++k) {
        btBuoyancyEvent event;
        event.type = types[k];
        event.action = &action;
        event.body = action.getRigidBody();
        event.waterBody = waterBodies[k];
        event.water = waterBodies[k] >= 0 && std::size_t(waterBodies[k]) < m_waterBodies.size()
                          ? &m_waterBodies[std::size_t(waterBodies[k])]
                          : nullptr;
        event.submergedFraction = submergedFraction;
        event.time = m_time;
        event.substep = m_substep;
        // Listeners added by a callback receive the next event on (the count is taken per event).
        const std::size_t n = m_listeners.size();
        for (std::size_t i = 0; i < n; ++i) {
            btBuoyancyEventListener* listener = m_listeners[i];
            if (!listener) continue;
            switch (event.type) {
            case btBuoyancyEventType::EnterWater: listener->onEnterWater(event); break;
            case btBuoyancyEventType::LeaveWater: listener->onLeaveWater(event); break;
            case btBuoyancyEventType::FullySubmerged: listener->onFullySubmerged(event); break;
            case btBuoyancyEventType::Surfaced: listener->onSurfaced(event); break;
            }
        }
    }
}

int btBuoyancyWorld::waterBodyAt(const Eigen::Vector3d& point) const {
    for (std::size_t i = 0; i < m_waterBodies.size(); ++i)
        if (m_waterBodies[i].distanceTo(m_frame, point) == 0.0) return int(i);
    for (std::size_t i = 0; i < m_waterBodies.size(); ++i)
        if (m_waterBodies[i].inColumn(m_frame, point, 0.0)) return int(i);
    return -1;
}

btWaterQueryResult btBuoyancyWorld::queryWater(const btVector3& point) const {
    const Eigen::Vector3d p(double(point.x()), double(point.y()), double(point.z()));
    if (!p.allFinite())
        throw std::invalid_argument("btBuoyancyWorld::queryWater: point " + btWaterFrame::vectorText(p) +
                                    " is not finite");
    btWaterQueryResult r;
    const btWaterSurface* surface = m_water;
    int index = -1;
    if (!m_waterBodies.empty()) {
        index = waterBodyAt(p);
        if (index < 0) return r;
        surface = m_waterBodies[std::size_t(index)].surface;
        r.waterBodyName = m_waterBodies[std::size_t(index)].name.c_str();
    }
    if (!surface) return r;
    r.hasWater = true;
    r.waterBody = index;
    // In water coordinates the surface is y = f(x, z, t): its height, and its slope by central differences.
    const Eigen::Vector3d q = m_frame.toWaterPoint(p);
    const double wavelength = surface->shortestWavelength();
    const double step = std::isfinite(wavelength) && wavelength > 0 ? 1e-3 * wavelength : 1e-3;
    const double xs[5] = {q.x(), q.x() + step, q.x() - step, q.x(), q.x()};
    const double zs[5] = {q.z(), q.z(), q.z(), q.z() + step, q.z() - step};
    double hs[5] = {0, 0, 0, 0, 0};
    surface->heights(xs, zs, 5, m_time, hs);
    const double h = hs[0];
    const Eigen::Vector3d slopeNormal(-(hs[1] - hs[2]) / (2 * step), 1.0, -(hs[3] - hs[4]) / (2 * step));
    const double depth = h - q.y();
    r.inWater = depth >= 0;
    const Eigen::Vector3d onSurface(q.x(), h, q.z());
    const Eigen::Vector3d at = r.inWater ? q : onSurface;
    double vx = 0, vy = 0, vz = 0;
    surface->velocities(&at.x(), &at.y(), &at.z(), 1, m_time, &vx, &vy, &vz);
    const Eigen::Vector3d normal = m_frame.toWorldVector(slopeNormal.normalized());
    const Eigen::Vector3d surfaceWorld = m_frame.toWorldPoint(onSurface);
    const Eigen::Vector3d velocity = m_frame.toWorldVector(Eigen::Vector3d(vx, vy, vz));
    r.surfaceHeight = btScalar(h);
    r.depth = btScalar(depth);
    r.surfacePoint = btVector3(btScalar(surfaceWorld.x()), btScalar(surfaceWorld.y()), btScalar(surfaceWorld.z()));
    r.normal = btVector3(btScalar(normal.x()), btScalar(normal.y()), btScalar(normal.z()));
    r.velocity = btVector3(btScalar(velocity.x()), btScalar(velocity.y()), btScalar(velocity.z()));
    return r;
}

void btBuoyancyWorld::debugDrawWater(btIDebugDraw* drawer, const btVector3& centre, btScalar halfSize,
                                     int cellsPerSide, const btVector3& colour) const {
    const std::string who = "btBuoyancyWorld::debugDrawWater: ";
    if (!drawer) throw std::invalid_argument(who + "drawer: must not be null");
    if (!std::isfinite(double(halfSize)) || !(halfSize > 0))
        throw std::invalid_argument(who + "halfSize: must be a finite number > 0 (got " +
                                    std::to_string(double(halfSize)) + ")");
    if (cellsPerSide < 1 || cellsPerSide > 1024)
        throw std::invalid_argument(who + "cellsPerSide: must be in 1..1024 (got " + std::to_string(cellsPerSide) + ")");
    const Eigen::Vector3d c(double(centre.x()), double(centre.y()), double(centre.z()));
    if (!c.allFinite()) throw std::invalid_argument(who + "centre: must be finite");
    const int m = cellsPerSide + 1;
    std::vector<double> xs(std::size_t(m) * m), zs(xs.size()), hs(xs.size());
    std::vector<btVector3> points(xs.size());
    std::vector<std::uint8_t> drawn(xs.size());
    // One surface over the water-frame rectangle [x0, x1] × [z0, z1]; a water body's points outside its region's
    // sides (a frame whose axes are not the box's, a footprint that is not a rectangle) are left out with the segments
    // that end there.
    const auto drawGrid = [&](const btWaterSurface& surface, double x0, double x1, double z0, double z1,
                              const btWaterBody* body) {
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j) {
                const std::size_t k = std::size_t(i) * m + j;
                xs[k] = i == cellsPerSide ? x1 : x0 + (x1 - x0) * double(i) / cellsPerSide;
                zs[k] = j == cellsPerSide ? z1 : z0 + (z1 - z0) * double(j) / cellsPerSide;
            }
        surface.heights(xs.data(), zs.data(), xs.size(), m_time, hs.data());
        const double slack = body ? 1e-9 * (1.0 + (body->regionMax - body->regionMin).norm()) : 0.0;
        for (std::size_t k = 0; k < xs.size(); ++k) {
            const Eigen::Vector3d w = m_frame.toWorldPoint(Eigen::Vector3d(xs[k], hs[k], zs[k]));
            points[k] = btVector3(btScalar(w.x()), btScalar(w.y()), btScalar(w.z()));
            drawn[k] = std::isfinite(hs[k]) && (!body || body->withinSides(m_frame, w, slack));
        }
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j) {
                const std::size_t k = std::size_t(i) * m + j;
                if (!drawn[k]) continue;
                if (j + 1 < m && drawn[k + 1]) drawer->drawLine(points[k], points[k + 1], colour);
                if (i + 1 < m && drawn[k + m]) drawer->drawLine(points[k], points[k + m], colour);
            }
    };
    if (m_waterBodies.empty()) {
        if (!m_water) return;
        const Eigen::Vector3d q = m_frame.toWaterPoint(c);
        const double s = double(halfSize);
        drawGrid(*m_water, q.x() - s, q.x() + s, q.z() - s, q.z() + s, nullptr);
        return;
    }
    for (const btWaterBody& body : m_waterBodies) {
        // The footprint: the water-frame x, z extent of the region.
        double x0 = 0, x1 = 0, z0 = 0, z1 = 0;
        body.footprintBounds(m_frame, x0, x1, z0, z1);
        drawGrid(*body.surface, x0, x1, z0, z1, &body);
    }
}

// ---- save and restore (btBuoyancyState.h) ----
std::vector<unsigned char> btBuoyancyWorld::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::World);
    out.f64(m_time);
    out.u64(m_substep);
    out.u64(m_frameVersion);
    out.boolean(m_frameFixed);
    out.f64s(m_frame.m_origin.data(), 3);
    out.f64s(m_frame.m_rotation.data(), 9);
    out.boolean(m_frame.m_identity);
    out.f64(m_gravity);
    out.f64s(m_gravityVector.data(), 3);
    out.boolean(m_gravityKnown);
    out.u8(std::uint8_t(m_gravityStatus));
    out.u64(m_lastBatchSize);
    return out.bytes();
}

void btBuoyancyWorld::restoreState(const unsigned char* data, std::size_t size) {
    if (m_dispatching || m_inBatch.load())
        throw std::logic_error("btBuoyancyWorld::restoreState: called during a step (an event callback or the batch); "
                               "restore between stepSimulation calls");
    finishPrebuilds();
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::World, "btBuoyancyWorld::restoreState");
    const double time = in.f64("time");
    const std::uint64_t substep = in.u64("substep");
    const std::uint64_t frameVersion = in.u64("frame version");
    const bool frameFixed = in.boolean("frame fixed");
    btWaterFrame frame;
    in.f64s(frame.m_origin.data(), 3, "frame origin");
    in.f64s(frame.m_rotation.data(), 9, "frame rotation");
    frame.m_identity = in.boolean("frame is identity");
    const double gravity = in.f64("gravity");
    Eigen::Vector3d gravityVector;
    in.f64s(gravityVector.data(), 3, "gravity vector");
    const bool gravityKnown = in.boolean("gravity known");
    const std::uint8_t status = in.u8("gravity status");
    if (status > std::uint8_t(btBuoyancyStatus::GravityNotAlongWaterUp))
        in.fail("gravity status " + std::to_string(status) + " is not a btBuoyancyStatus");
    const std::uint64_t lastBatchSize = in.u64("last batch size");
    in.finish();
    m_time = time;
    m_substep = substep;
    m_frameVersion = frameVersion;
    m_frameFixed = frameFixed;
    m_frame = frame;
    m_gravity = gravity;
    m_gravityVector = gravityVector;
    m_gravityKnown = gravityKnown;
    m_gravityStatus = static_cast<btBuoyancyStatus>(status);
    m_lastBatchSize = std::size_t(lastBatchSize);
}
