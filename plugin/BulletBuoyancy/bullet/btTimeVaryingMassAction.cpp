#include <BulletBuoyancy/bullet/btTimeVaryingMassAction.h>

#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>
#include <stdexcept>

btTimeVaryingMassAction::btTimeVaryingMassAction(btBuoyantBody& body, btBuoyancyWorld* world,
                                                 btBuoyantBodySettings settings, VersionFn version, DensityFn density,
                                                 btFloodingAction* flooding)
    : m_body(&body), m_world(world), m_settings(std::move(settings)), m_versionFn(std::move(version)),
      m_densityFn(std::move(density)), m_flooding(flooding) {
    if (!m_world) throw std::invalid_argument("world: null");
    if (!m_versionFn || !m_densityFn) throw std::invalid_argument("density map: null function");
    if (!(body.getMass() > 0)) throw std::invalid_argument("body: a fixed body has no mass to vary");
    m_settings.fixed = false;
    m_settings.massModel = btBuoyantMassModel::DensityMap;
    apply(m_world->getTime());
    m_world->registerTimeVaryingMassAction(this);
}

btTimeVaryingMassAction::~btTimeVaryingMassAction() { m_world->unregisterTimeVaryingMassAction(this); }

buoyancy::MassProperties btTimeVaryingMassAction::compute(double t) const {
    btBuoyantBodySettings s = m_settings;
    const DensityFn& fn = m_densityFn;
    s.arealDensity = [&fn, t](const Eigen::Vector3d& p) { return fn(t, p); };
    // Shell integrals over the shape's surface samples (design.md 2.1), rescaled to `mass` when given.
    const buoyancy::MassProperties mp = btBuoyantBodyMassProperties(*m_body->getShape(), s);
    if (!(mp.mass > 0) || !std::isfinite(mp.mass) || !mp.centre.allFinite() || !mp.inertia.allFinite())
        throw std::invalid_argument("density map: gives no positive, finite mass at t = " + std::to_string(t));
    return mp;
}

void btTimeVaryingMassAction::commit(const buoyancy::MassProperties& mp, std::int64_t version) {
    if (m_flooding) {
        m_flooding->setDryMassProperties(mp);
        m_flooding->updateBodyMassProperties();
    } else {
        m_body->updateMassProperties(mp.mass, mp.centre, mp.inertia);
    }
    m_version = version;
    ++m_recomputes;
}

void btTimeVaryingMassAction::apply(double t) {
    const std::int64_t version = m_versionFn(t);
    commit(compute(t), version);
}

bool btTimeVaryingMassAction::active() const {
    const btRigidBody* rb = m_body->getRigidBody();
    return rb->getBroadphaseHandle() && rb->getInvMass() != btScalar(0);
}

bool btTimeVaryingMassAction::prepareForBatch(double t) {
    m_batched = true;
    m_batchTime = t;
    m_batchError = nullptr;
    m_batchRecompute = false;
    if (!active() || !std::isfinite(t)) return false;
    m_batchVersion = m_versionFn(t);
    m_batchRecompute = m_batchVersion != m_version;
    return m_batchRecompute;
}

void btTimeVaryingMassAction::computeForBatch() {
    try {
        m_batchResult = compute(m_batchTime);
    } catch (...) {
        m_batchError = std::current_exception();  // handled at the action's turn, as an unbatched recompute would be
    }
}

void btTimeVaryingMassAction::updateAction(btCollisionWorld* collisionWorld, btScalar) {
    // The world's batch checks every time-varying mass action's map at the first one's turn and recomputes the
    // changed ones across the threads; an action outside it (batching off, not in a discrete dynamics world, stepped
    // by hand), or one whose world time moved since (another action advanced the clock), does its own work here.
    if (!m_batched) m_world->evaluateTimeVaryingMassBatch(collisionWorld, this);
    const bool batched = m_batched;
    m_batched = false;
    if (!active()) return;
    const double t = m_world->getTime();
    if (batched && m_batchTime == t) {
        if (!m_batchRecompute) return;
        try {
            if (m_batchError) std::rethrow_exception(m_batchError);
            commit(m_batchResult, m_batchVersion);
            m_body->getRigidBody()->activate();
        } catch (const std::invalid_argument&) {
            // A bad map at run time leaves the body as it was (never NaN into Bullet); retried at the next version.
            m_version = m_batchVersion;
        }
        return;
    }
    if (!std::isfinite(t) || m_versionFn(t) == m_version) return;
    try {
        apply(t);
        m_body->getRigidBody()->activate();
    } catch (const std::invalid_argument&) {
        // A bad map at run time leaves the body as it was (never NaN into Bullet); retried at the next version.
        m_version = m_versionFn(t);
    }
}

// ---- save and restore (btBuoyancyState.h) ----
std::vector<unsigned char> btTimeVaryingMassAction::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::TimeVaryingMass);
    out.i64(m_version);
    out.i64(m_recomputes);
    return out.bytes();
}

void btTimeVaryingMassAction::restoreState(const unsigned char* data, std::size_t size) {
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::TimeVaryingMass, "btTimeVaryingMassAction::restoreState");
    const std::int64_t version = in.i64("map version");
    const std::int64_t recomputes = in.i64("recompute count");
    in.finish();
    m_version = version;
    m_recomputes = recomputes;
}
