#include <BulletBuoyancy/bullet/btInteractiveWaterCoupler.h>

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

btInteractiveWaterCoupler::btInteractiveWaterCoupler(btInteractiveWaterSurface* water, const btBuoyancyWorld* world,
                                                     double coupling)
    : m_water(water), m_world(world), m_coupling(coupling) {
    if (!water || !world) throw std::invalid_argument("btInteractiveWaterCoupler: water and world must not be null");
    if (!(coupling > 0 && coupling <= 1)) throw std::invalid_argument("coupling: must be in (0, 1]");
}

void btInteractiveWaterCoupler::updateAction(btCollisionWorld*, btScalar deltaTimeStep) {
    const double dt = double(deltaTimeStep);
    for (const btBuoyancyAction* a : m_world->getActions()) {
        const btBuoyancyResult& r = a->getLastResult();
        Footprint now;
        if (r.submergedVolume > 0 && std::isfinite(r.submergedVolume)) {
            // Footprint: the disc of the body's bounding sphere under its bounds centre. It covers every point
            // at which the body reads the water (mesh corners, samples), so the raised ring is always outside
            // the body, and its radius never changes, so consecutive substeps move the same cells. (A disc
            // from the waterline area left a box's corners in the raised ring: the body read the water it had
            // just pushed up, sank less, and the loop heaped water under it; the radius also jumped whenever
            // the waterline area did, e.g. when a dropped crate went fully under.)
            const btTransform pose = a->getBody().getWorldTransform() * a->getMeshInComFrame();
            const Eigen::Vector3d& c = a->getShape()->getBoundsCentre();
            const btVector3 centre = pose * btVector3(btScalar(c.x()), btScalar(c.y()), btScalar(c.z()));
            // The surface's own (water-frame) horizontal coordinates.
            const Eigen::Vector3d q = m_world->getWaterFrame().toWaterPoint(
                Eigen::Vector3d(double(centre.x()), double(centre.y()), double(centre.z())));
            now.x = q.x();
            now.z = q.z();
            now.volume = r.submergedVolume;
            now.radius = a->getShape()->getBoundsRadius();
        }
        Footprint& before = m_last[a];
        if (before.volume != 0) m_water->addVolumeChange(before.x, before.z, -m_coupling * before.volume, before.radius);
        if (now.volume != 0) m_water->addVolumeChange(now.x, now.z, m_coupling * now.volume, now.radius);
        before = now;
    }
    // Forget actions that left the context (their water goes back).
    for (auto it = m_last.begin(); it != m_last.end();) {
        const auto& acts = m_world->getActions();
        if (std::find(acts.begin(), acts.end(), it->first) == acts.end()) {
            if (it->second.volume != 0)
                m_water->addVolumeChange(it->second.x, it->second.z, -m_coupling * it->second.volume, it->second.radius);
            it = m_last.erase(it);
        } else {
            ++it;
        }
    }
    m_water->step(dt);
}

double btInteractiveWaterCoupler::displacedVolume() const {
    double v = 0;
    for (const auto& kv : m_last) v += kv.second.volume;
    return v;
}

// ---- save and restore (btBuoyancyState.h) ----
std::vector<unsigned char> btInteractiveWaterCoupler::saveState() const {
    btBuoyancyStateWriter out(btBuoyancyStateKind::InteractiveWater);
    const btInteractiveWaterSurface::Dynamic d = m_water->dynamicState();
    out.u32(std::uint32_t(m_water->cellsX()));
    out.u32(std::uint32_t(m_water->cellsZ()));
    out.f64Vector(d.eta);
    out.f64Vector(d.velocity);
    out.f64(d.offset);
    out.f64(d.min);
    out.f64(d.max);
    // The footprints in the order of the world's actions (the map's own order is not reproducible); those of actions
    // no longer registered are dropped at the next substep anyway and not saved.
    const std::vector<btBuoyancyAction*>& actions = m_world->getActions();
    std::vector<std::pair<std::uint32_t, Footprint>> saved;
    for (std::size_t i = 0; i < actions.size(); ++i) {
        const auto it = m_last.find(actions[i]);
        if (it != m_last.end()) saved.emplace_back(std::uint32_t(i), it->second);
    }
    out.u64(saved.size());
    for (const auto& [index, f] : saved) {
        out.u32(index);
        out.f64(f.x);
        out.f64(f.z);
        out.f64(f.volume);
        out.f64(f.radius);
    }
    return out.bytes();
}

void btInteractiveWaterCoupler::restoreState(const unsigned char* data, std::size_t size) {
    btBuoyancyStateReader in(data, size, btBuoyancyStateKind::InteractiveWater, "btInteractiveWaterCoupler::restoreState");
    in.expectCount(in.u32("cells along x"), std::uint32_t(m_water->cellsX()), "the grid's cell count along x");
    in.expectCount(in.u32("cells along z"), std::uint32_t(m_water->cellsZ()), "the grid's cell count along z");
    const std::size_t cells = std::size_t(m_water->cellsX()) * std::size_t(m_water->cellsZ());
    btInteractiveWaterSurface::Dynamic d;
    d.eta = in.f64Vector("elevations");
    in.expectCount(d.eta.size(), cells, "the grid's elevation count");
    d.velocity = in.f64Vector("velocities");
    in.expectCount(d.velocity.size(), cells, "the grid's velocity count");
    d.offset = in.f64("level offset");
    d.min = in.f64("height minimum");
    d.max = in.f64("height maximum");
    const std::vector<btBuoyancyAction*>& actions = m_world->getActions();
    const std::uint64_t count = in.u64("footprint count");
    if (count > in.remaining() / 36) in.fail("the footprint count " + std::to_string(count) + " exceeds the payload");
    std::unordered_map<const btBuoyancyAction*, Footprint> last;
    for (std::uint64_t k = 0; k < count; ++k) {
        const std::uint32_t index = in.u32("footprint action index");
        if (index >= actions.size())
            in.fail("a footprint belongs to action " + std::to_string(index) + ", the world has " +
                    std::to_string(actions.size()) + " actions");
        Footprint f;
        f.x = in.f64("footprint x");
        f.z = in.f64("footprint z");
        f.volume = in.f64("footprint volume");
        f.radius = in.f64("footprint radius");
        last[actions[index]] = f;
    }
    in.finish();
    m_water->setDynamicState(d);  // sizes checked above: does not throw
    m_last = std::move(last);
}
