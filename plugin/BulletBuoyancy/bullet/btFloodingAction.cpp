#include <BulletBuoyancy/bullet/btFloodingAction.h>

#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/graph/WaterMassProperties.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <LinearMath/btIDebugDraw.h>

#include <cmath>
#include <stdexcept>

btFloodingAction::btFloodingAction(btBuoyantBody& body, btBuoyancyWorld* world, buoyancy::WaterGraph graph,
                                   buoyancy::PermeableSamples holes)
    : m_body(&body), m_world(world), m_state(std::move(graph)) {
    if (!m_world) throw std::invalid_argument("world: null");
    if (!(body.getMass() > 0)) throw std::invalid_argument("body: a fixed body cannot hold water");
    m_dry = body.getMassProperties();
    setPermeableSamples(std::move(holes));
    m_state.setPose(m_world->getWaterFrame().toWater(buoyancy::toEigen(body.getMeshWorldTransform())));
    updateBodyMassProperties();
    m_world->registerFloodingAction(this);
}

btFloodingAction::~btFloodingAction() { m_world->unregisterFloodingAction(this); }

void btFloodingAction::setPermeableSamples(buoyancy::PermeableSamples holes) {
    const std::size_t n = holes.size();
    if (holes.py.size() != n || holes.pz.size() != n || holes.openArea.size() != n || holes.node.size() != n)
        throw std::invalid_argument("holes: arrays of different sizes");
    for (std::size_t i = 0; i < n; ++i) {
        if (holes.node[i] < 0 || std::size_t(holes.node[i]) >= m_state.size())
            throw std::invalid_argument("holes: sample " + std::to_string(i) + " maps to no node");
        if (!std::isfinite(holes.openArea[i]) || holes.openArea[i] < 0)
            throw std::invalid_argument("holes: sample " + std::to_string(i) + " has a bad open area");
    }
    m_holes = std::move(holes);
    m_wx.resize(n);
    m_wy.resize(n);
    m_wz.resize(n);
    m_f.resize(n);
    m_scratch.resize(m_state.size());
}

void btFloodingAction::setDryMassProperties(const buoyancy::MassProperties& dry) {
    if (!(dry.mass > 0) || !std::isfinite(dry.mass) || !dry.centre.allFinite() || !dry.inertia.allFinite())
        throw std::invalid_argument("dry mass properties: mass must be > 0 and everything finite");
    m_dry = dry;
    m_dirty = true;
}

void btFloodingAction::updateBodyMassProperties() {
    const double rho = m_world->getFluidDensity();
    const buoyancy::MassProperties total =
        buoyancy::composeMassProperties(m_dry, buoyancy::waterMassProperties(m_state, rho));
    const buoyancy::MassProperties& cur = m_body->getMassProperties();
    // Skip the update (and its eigen-decomposition) when nothing measurable changed.
    const double scale = std::max(cur.inertia.norm(), 1e-30);
    if (!m_dirty && std::abs(total.mass - cur.mass) <= 1e-13 * cur.mass &&
        (total.centre - cur.centre).norm() <= 1e-12 && (total.inertia - cur.inertia).norm() <= 1e-12 * scale)
        return;
    if (!(total.mass > 0) || !total.centre.allFinite() || !total.inertia.allFinite()) return;  // never NaN
    m_body->updateMassProperties(total.mass, total.centre, total.inertia);
    m_dirty = false;
}

void btFloodingAction::updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) {
    const double dt = double(deltaTimeStep);
    if (!(dt > 0) || !std::isfinite(dt)) return;
    // The world's batch moves the water of every flooding action of this substep at the first one's turn; an action
    // outside the batch (batching off, not in a discrete dynamics world, or stepped by hand) flows here.
    if (!m_flowed) m_world->evaluateFloodingBatch(collisionWorld, dt, this);
    if (!m_flowed) flow(dt);
    m_flowed = false;
    if (m_wake) m_body->getRigidBody()->activate();
    if (m_massPending) updateBodyMassProperties();
    m_wake = m_massPending = false;
}

void btFloodingAction::flowForBatch(double dt) { flow(dt); }

void btFloodingAction::flow(double dt) {
    m_flowed = true;
    m_massPending = m_wake = false;
    const btRigidBody* rb = m_body->getRigidBody();
    if (!rb->getBroadphaseHandle() || rb->getInvMass() == btScalar(0)) return;
    // In the water frame (btWaterFrame): heights and levels along its up, the surface's own coordinates.
    const Eigen::Isometry3d pose = m_world->getWaterFrame().toWater(buoyancy::toEigen(m_body->getMeshWorldTransform()));
    if (!pose.matrix().allFinite()) return;
    m_state.setPose(pose);
    const double before = m_state.totalWater();

    // Water flows downhill only where the world's gravity points down the water's up axis: otherwise it stays put.
    if (m_world->getGravityStatus() != btBuoyancyStatus::Ok) return;
    // The unbounded water, or the water body the hull's bounding sphere reaches nearest its centre of mass (the
    // holes all take that water; the water inside keeps the world's density, btBuoyancyWorld::getFluidDensity).
    const btWaterSurface* water = m_world->getWater();
    if (!m_world->getWaterBodies().empty()) {
        const Eigen::Vector3d com = buoyancy::toEigen(rb->getCenterOfMassPosition());
        const int k = m_world->findWaterBody(com, m_body->getShape()->getBoundsRadius(), com);
        water = k >= 0 ? m_world->getWaterBodies()[std::size_t(k)].surface : nullptr;
    }
    const double g = m_world->getGravity();
    const std::size_t n = m_holes.size();
    if (water && n > 0) {
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector3d p = pose * Eigen::Vector3d(m_holes.px[i], m_holes.py[i], m_holes.pz[i]);
            m_wx[i] = p.x();
            m_wy[i] = p.y();
            m_wz[i] = p.z();
        }
        water->heights(m_wx.data(), m_wz.data(), n, m_world->getTime(), m_f.data());
        buoyancy::applyIngress(m_state, m_holes, m_wy.data(), m_f.data(), dt, g, m_scratch, m_world->getFluidDensity());
    }
    m_state.flow(dt, m_world->getFluidDensity(), g);
    m_wake = m_state.totalWater() != before;
    m_massPending = true;
}

void btFloodingAction::debugDraw(btIDebugDraw* debugDrawer) {
    if (!debugDrawer) return;
    const btTransform t = m_body->getMeshWorldTransform();
    for (std::size_t i = 0; i < m_state.size(); ++i) {
        if (!(m_state.water(int(i)) > 0)) continue;
        const btVector3 c = t * buoyancy::toBullet(m_state.waterCentroid(int(i)));
        const btScalar s = 0.05;
        debugDrawer->drawLine(c - btVector3(s, 0, 0), c + btVector3(s, 0, 0), btVector3(0, 0.3, 1));
        debugDrawer->drawLine(c - btVector3(0, s, 0), c + btVector3(0, s, 0), btVector3(0, 0.3, 1));
        debugDrawer->drawLine(c - btVector3(0, 0, s), c + btVector3(0, 0, s), btVector3(0, 0.3, 1));
    }
}

// ---- save and restore (btBuoyancyState.h) ----
std::vector<unsigned char> btFloodingAction::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::Flooding);
    const buoyancy::WaterGraphState::Dynamic d = m_state.dynamicState();
    out.u64(m_state.size());
    out.f64Vector(d.water);
    out.f64Vector(d.centreY);
    out.f64Vector(d.bottom);
    out.f64Vector(d.level);
    out.f64Vector(d.half);
    for (unsigned char f : d.full) out.u8(f);
    out.f64s(d.up.data(), 3);
    out.f64(d.entered);
    out.f64(d.enteredC);
    out.f64(d.drained);
    out.f64(d.drainedC);
    out.f64(d.initial);
    out.u64(d.rng);
    out.u64(m_holes.size());
    out.f64Vector(m_holes.px);
    out.f64Vector(m_holes.py);
    out.f64Vector(m_holes.pz);
    out.f64Vector(m_holes.openArea);
    for (int k : m_holes.node) out.i32(k);
    out.f64(m_dry.mass);
    out.f64(m_dry.volume);
    out.f64(m_dry.area);
    out.f64s(m_dry.centre.data(), 3);
    out.f64s(m_dry.inertia.data(), 9);
    out.boolean(m_dirty);
    return out.bytes();
}

void btFloodingAction::restoreState(const unsigned char* data, std::size_t size) {
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::Flooding, "btFloodingAction::restoreState");
    const std::size_t n = m_state.size();
    in.expectCount(in.u64("node count"), n, "the water graph's node count");
    buoyancy::WaterGraphState::Dynamic d;
    for (std::vector<double>* v : {&d.water, &d.centreY, &d.bottom, &d.level, &d.half}) {
        *v = in.f64Vector("node values");
        in.expectCount(v->size(), n, "a per-node array's size");
    }
    d.full.resize(n);
    for (unsigned char& f : d.full) f = in.u8("full flag");
    in.f64s(d.up.data(), 3, "up in body axes");
    d.entered = in.f64("entered volume");
    d.enteredC = in.f64("entered volume compensation");
    d.drained = in.f64("drained volume");
    d.drainedC = in.f64("drained volume compensation");
    d.initial = in.f64("initial volume");
    d.rng = in.u64("random generator state");
    const std::uint64_t holeCount = in.u64("permeable sample count");
    buoyancy::PermeableSamples holes;
    for (std::vector<double>* v : {&holes.px, &holes.py, &holes.pz, &holes.openArea}) {
        *v = in.f64Vector("permeable samples");
        in.expectCount(v->size(), holeCount, "a permeable sample array's size");
    }
    for (double a : holes.openArea)
        if (!std::isfinite(a) || a < 0) in.fail("a permeable sample has a bad open area");
    holes.node.resize(holes.px.size());
    for (int& k : holes.node) {
        k = in.i32("permeable sample node");
        if (k < 0 || std::size_t(k) >= n)
            in.fail("a permeable sample maps to node " + std::to_string(k) + ", the graph has " + std::to_string(n));
    }
    buoyancy::MassProperties dry;
    dry.mass = in.f64("dry mass");
    dry.volume = in.f64("dry volume");
    dry.area = in.f64("dry area");
    in.f64s(dry.centre.data(), 3, "dry centre");
    in.f64s(dry.inertia.data(), 9, "dry inertia");
    const bool dirty = in.boolean("dirty");
    in.finish();
    // Commit: the samples and sizes are checked above, so neither call throws (and the first would change nothing).
    setPermeableSamples(std::move(holes));
    m_state.setDynamicState(d);
    m_dry = dry;
    m_dirty = dirty;
}
