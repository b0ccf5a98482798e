#include <BulletBuoyancy/bullet/btInteractiveWaterCoupler.h>

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
            const btTransform pose = a->getRigidBody()->getWorldTransform() * a->getMeshInComFrame();
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
