#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace {
std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}
}  // namespace

void btBuoyancyEventSettings::validate() const {
    const char* const names[4] = {"enterFraction", "leaveFraction", "submergedFraction", "surfacedFraction"};
    const double values[4] = {enterFraction, leaveFraction, submergedFraction, surfacedFraction};
    for (int i = 0; i < 4; ++i)
        // std::isfinite first: an ordered comparison with NaN raises FE_INVALID (bad input must not trap).
        if (!std::isfinite(values[i]) || values[i] < 0 || values[i] > 1)
            throw std::invalid_argument(std::string("btBuoyancyEventSettings::") + names[i] +
                                        ": must be a finite fraction in [0, 1] (got " + number(values[i]) + ")");
    if (!(leaveFraction < enterFraction))
        throw std::invalid_argument("btBuoyancyEventSettings::leaveFraction: must be below enterFraction (got " +
                                    number(leaveFraction) + " and " + number(enterFraction) +
                                    "): the gap between them is the hysteresis");
    if (!(surfacedFraction < submergedFraction))
        throw std::invalid_argument("btBuoyancyEventSettings::surfacedFraction: must be below submergedFraction (got " +
                                    number(surfacedFraction) + " and " + number(submergedFraction) +
                                    "): the gap between them is the hysteresis");
    if (!(enterFraction <= submergedFraction))
        throw std::invalid_argument("btBuoyancyEventSettings::submergedFraction: must not be below enterFraction (got " +
                                    number(submergedFraction) + " and " + number(enterFraction) +
                                    "): a fully submerged body is in the water");
    if (!(leaveFraction <= surfacedFraction))
        throw std::invalid_argument("btBuoyancyEventSettings::surfacedFraction: must not be below leaveFraction (got " +
                                    number(surfacedFraction) + " and " + number(leaveFraction) +
                                    "): a body surfaces before it leaves the water");
}

const char* btBuoyancyEventTypeName(btBuoyancyEventType type) {
    switch (type) {
    case btBuoyancyEventType::EnterWater: return "enter";
    case btBuoyancyEventType::LeaveWater: return "leave";
    case btBuoyancyEventType::FullySubmerged: return "submerged";
    case btBuoyancyEventType::Surfaced: return "surfaced";
    }
    return "unknown";
}

int btBuoyancyWaterState::update(double fraction, int body, const btBuoyancyEventSettings& settings,
                                 btBuoyancyEventType types[kMaxEvents], int bodies[kMaxEvents]) {
    if (!std::isfinite(fraction)) return 0;
    const double f = std::min(std::max(fraction, 0.0), 1.0);
    int n = 0;
    const auto emit = [&](btBuoyancyEventType type, int where) {
        types[n] = type;
        bodies[n] = where;
        ++n;
    };
    // Leaving: the fraction fell to the leave threshold, or the body is now in another water body's region.
    if (inWater && (f <= settings.leaveFraction || body != waterBody)) {
        if (submerged) emit(btBuoyancyEventType::Surfaced, waterBody);
        emit(btBuoyancyEventType::LeaveWater, waterBody);
        inWater = submerged = false;
        waterBody = -1;
    }
    if (!inWater && f >= settings.enterFraction) {
        inWater = true;
        waterBody = body;
        emit(btBuoyancyEventType::EnterWater, waterBody);
    }
    if (inWater && !submerged && f >= settings.submergedFraction) {
        submerged = true;
        emit(btBuoyancyEventType::FullySubmerged, waterBody);
    } else if (inWater && submerged && f <= settings.surfacedFraction) {
        submerged = false;
        emit(btBuoyancyEventType::Surfaced, waterBody);
    }
    return n;
}
