#pragma once
/// @file btBuoyancyEvents.h
/// Events and queries for game logic (docs/integration.md "Events and queries"):
/// - per body, the events "enters the water", "leaves the water", "becomes fully submerged" and "surfaces again",
///   decided on its submerged fraction (submerged volume / body volume) with hysteresis (btBuoyancyEventSettings),
///   delivered to the btBuoyancyEventListener objects registered on its btBuoyancyWorld;
/// - per world, what the water is at a point (btWaterQueryResult, btBuoyancyWorld::queryWater), without a body.
///
/// Events are delivered from the serial part of a substep, never from a worker thread: at each body's own
/// btBuoyancyAction turn in Bullet's action order (the order the actions were added to the Bullet world), after the
/// body's buoyancy of that substep was computed. Within one body's turn the events come in the order of the
/// transitions (enter before fully submerged, surfaced before leave), each to every listener in registration order.

#include <LinearMath/btScalar.h>
#include <LinearMath/btVector3.h>

#include <cstdint>

class btBuoyancyAction;
class btRigidBody;
struct btWaterBody;

/// The hysteresis of a world's water events, as fractions of each body's volume under water (0..1). A body is in
/// the water from the substep its submerged fraction reaches enterFraction until it falls to leaveFraction, and fully
/// submerged from the substep it reaches submergedFraction until it falls to surfacedFraction: a body bobbing around
/// one threshold fires no event until it crosses the other one. Validated by btBuoyancyWorld::setEventSettings:
/// 0 ≤ leaveFraction < enterFraction ≤ submergedFraction ≤ 1, and leaveFraction ≤ surfacedFraction < submergedFraction.
struct btBuoyancyEventSettings {
    /// A body out of the water enters it when its submerged fraction is ≥ this, dimensionless (default 0.01: 1 % of
    /// its volume, so a body skimming the surface by a hair does not enter).
    double enterFraction = 0.01;
    /// A body in the water leaves it when its submerged fraction is ≤ this, dimensionless (default 0.001: out of the
    /// water but for a thousandth of its volume).
    double leaveFraction = 0.001;
    /// A body in the water becomes fully submerged when its submerged fraction is ≥ this, dimensionless (default
    /// 0.99: the sampled hydrostatics of a body under waves come within a fraction of a percent of its volume).
    double submergedFraction = 0.99;
    /// A fully submerged body surfaces when its submerged fraction is ≤ this, dimensionless (default 0.97; a body
    /// floating with 97 % to 99 % of its volume under water never fires either event).
    double surfacedFraction = 0.97;

    /// @throws std::invalid_argument naming the field and the rule it breaks (a non-finite value, a value outside
    /// [0, 1], or thresholds out of the order above)
    void validate() const;
};

/// The kind of a water event.
enum class btBuoyancyEventType {
    EnterWater,     ///< the body's submerged fraction reached enterFraction
    LeaveWater,     ///< the body's submerged fraction fell to leaveFraction (or it left its water body's region)
    FullySubmerged, ///< the body's submerged fraction reached submergedFraction
    Surfaced,       ///< a fully submerged body's submerged fraction fell to surfacedFraction
};

/// Name of an event type for logs: "enter", "leave", "submerged", "surfaced".
const char* btBuoyancyEventTypeName(btBuoyancyEventType type);

/// One water event of one body.
struct btBuoyancyEvent {
    btBuoyancyEventType type = btBuoyancyEventType::EnterWater; ///< what happened
    btBuoyancyAction* action = nullptr;   ///< the body's action
    btRigidBody* body = nullptr;          ///< the body (action->getRigidBody(); nullptr for another body type: action->getBody())
    /// The water body entered, left, submerged in or surfaced from: an index in btBuoyancyWorld::getWaterBodies(), or
    /// −1 for the world's unbounded water.
    int waterBody = -1;
    /// That water body (name, surface, density, region), or nullptr for the unbounded water. Valid during the call.
    const btWaterBody* water = nullptr;
    double submergedFraction = 0;         ///< the body's submerged fraction at this substep, 0..1
    double time = 0;                      ///< the water's time at the end of this substep, s (btBuoyancyWorld::getTime)
    std::uint64_t substep = 0;            ///< the substep's number (btBuoyancyWorld::getSubstep)
};

/// Receives the water events of a world's bodies (btBuoyancyWorld::addEventListener). Override the events you need;
/// the defaults do nothing.
///
/// A callback runs inside Bullet's stepSimulation, at the body's action's turn. It may read anything, apply forces,
/// impulses or velocities to bodies, record, play sounds, and add or remove listeners (taking effect from the next
/// event). It must not add or remove Bullet bodies, actions or constraints of the world being stepped (collect them
/// and do it after stepSimulation returns); creating or destroying a btBuoyancyAction or changing the water bodies
/// is refused (std::logic_error from the constructor, addWaterBody and removeAllWaterBodies; a destructor aborts
/// with a message). An exception thrown by a callback propagates out of stepSimulation, cutting Bullet's step short.
class btBuoyancyEventListener {
public:
    virtual ~btBuoyancyEventListener() = default;
    /// The body entered the water (event.type EnterWater).
    virtual void onEnterWater(const btBuoyancyEvent& event) { (void)event; }
    /// The body left the water (event.type LeaveWater); event.waterBody is the one it left.
    virtual void onLeaveWater(const btBuoyancyEvent& event) { (void)event; }
    /// The body became fully submerged (event.type FullySubmerged).
    virtual void onFullySubmerged(const btBuoyancyEvent& event) { (void)event; }
    /// The fully submerged body surfaced again (event.type Surfaced).
    virtual void onSurfaced(const btBuoyancyEvent& event) { (void)event; }
};

/// A body's in-water and fully-submerged states with the hysteresis of btBuoyancyEventSettings (used by each
/// btBuoyancyAction; public so the rule can be checked on its own). A change of water body while in the water
/// counts as leaving the old one (after surfacing from it when fully submerged) and entering the new one.
struct btBuoyancyWaterState {
    bool inWater = false;    ///< the body is in the water
    bool submerged = false;  ///< the body is fully submerged (only while in the water)
    int waterBody = -1;      ///< the water body it is in (−1: none, or the unbounded water)

    /// The most events one update can give (surfaced and leave from the old water body, enter and fully
    /// submerged in the new one).
    static constexpr int kMaxEvents = 4;
    /// Advance the states with this substep's submerged fraction and water body. A non-finite fraction changes
    /// nothing; the fraction is clamped to [0, 1].
    /// @param fraction    submerged volume / body volume, dimensionless
    /// @param waterBody   the water body the body reaches (−1: none, or the unbounded water)
    /// @param settings    the thresholds (assumed valid)
    /// @param[out] types   the events, in the order they happened (at most kMaxEvents)
    /// @param[out] bodies  each event's water body
    /// @return the number of events
    int update(double fraction, int waterBody, const btBuoyancyEventSettings& settings,
               btBuoyancyEventType types[kMaxEvents], int bodies[kMaxEvents]);
};

/// What the water is at a point of the world (btBuoyancyWorld::queryWater). World coordinates; heights are along
/// the world's water frame's up (btWaterFrame) and measured from the frame's origin.
struct btWaterQueryResult {
    /// A water surface lies above or below the point: the world has an unbounded water, or the point is within the
    /// sides of a water body's region and not below its bottom. When false every other field keeps its default.
    bool hasWater = false;
    /// The point is at or below the surface (depth ≥ 0) in that water.
    bool inWater = false;
    /// The water body: an index in btBuoyancyWorld::getWaterBodies(), −1 for the unbounded water (or none).
    int waterBody = -1;
    /// Its name ("" for the unbounded water or none); points into the world, valid until its water bodies change.
    const char* waterBodyName = "";
    /// Height of the surface above the water frame's origin along up, m (the surface's own height, e.g. a
    /// btFlatWaterSurface's level).
    btScalar surfaceHeight = 0;
    /// The surface point on the line through the point along up, world, m.
    btVector3 surfacePoint = btVector3(0, 0, 0);
    /// Depth of the point below the surface along up, m (> 0 under water, < 0 above it).
    btScalar depth = 0;
    /// Unit normal of the surface at surfacePoint, pointing out of the water, world (up for flat water).
    btVector3 normal = btVector3(0, 0, 0);
    /// Velocity of the water, m/s, world: at the point when it is in the water, else at surfacePoint.
    btVector3 velocity = btVector3(0, 0, 0);
};
