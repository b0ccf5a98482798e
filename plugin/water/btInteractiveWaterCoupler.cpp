#include "water/btInteractiveWaterCoupler.h"

#include "bullet/btBuoyancyAction.h"
#include "bullet/btBuoyancyWorld.h"
#include "water/btInteractiveWaterSurface.h"

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
            now.x = double(r.centreOfBuoyancy.x());
            now.z = double(r.centreOfBuoyancy.z());
            now.volume = r.submergedVolume;
            // Footprint radius from the waterline area (a disc of the same area); a fully submerged body
            // has none, so use the radius of a sphere of its displaced volume.
            const double fromArea = std::sqrt(std::max(r.waterlineArea, 0.0) / M_PI);
            now.radius = fromArea > 0 ? fromArea : std::cbrt(3 * now.volume / (4 * M_PI));
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
