#pragma once
/// @file TemporalLevelOfDetail.h
/// Temporal level of detail of one body (design.md 2.5 "Fewer evaluations in time"; asked for by
/// btBuoyancySettings::hydrostaticsInterval in the Bullet layer): the body evaluates its hydrostatics and drag exactly
/// at every K-th substep (its evaluation substeps, staggered between bodies by a phase) and, in between, predicts them
/// from its last exact evaluations (HydrostaticsHistory), moved to the actual pose through the hydrostatic stiffness.
/// Each exact evaluation checks the predictor; misses stop the predictions for a while or halve the body's interval,
/// long runs of passes double it back.
///
/// The controller knows nothing of Bullet: it takes the body's pose and centre of mass in the water frame (Eigen), its
/// volume and bounding radius, the water's density and gravity, the substep and its time. The caller decides whether
/// the level of detail applies at all this substep (a straddling, deformable or device-batched body is evaluated
/// exactly) and clears the records whenever they stop describing the body (dry, rejected or primed substeps, another
/// water, another frame).
///
/// Usage per substep:  lod.begin(settings);  if (applies && lod.isEvaluationSubstep(n)) { evaluate; lod.record(...); }
///                     else if (applies && lod.predict(...)) { use the prediction } else { evaluate }.
/// No allocation and no virtual call.

#include <BulletBuoyancy/temporal/HydrostaticsHistory.h>

#include <Eigen/Geometry>

#include <cstdint>

namespace buoyancy {

class StateWriter;
class StateReader;

/// What the temporal level of detail is asked for at a substep (in the Bullet layer, resolved from
/// btBuoyancySettings by btBuoyancyResolveInterval and btBuoyancyResolveReuseTolerance).
struct TemporalLevelOfDetailSettings {
    /// The interval at this substep length, substeps (≥ 1; 1: every substep exact). The controller uses it or a
    /// divisor of it that its checks chose.
    int interval = 1;
    /// The prediction tolerance: the error allowed in the pressure force, as a fraction of ρ g V (dimensionless).
    double tolerance = 1e-4;
};

/// The substep a prediction or a record is made at, and the water the body is in.
struct TemporalLevelOfDetailSubstep {
    std::uint64_t substep = 0;  ///< the world's substep counter (dimensionless)
    double time = 0;            ///< the water's time at this substep, s
    double dt = 0;              ///< the substep's length, s (> 0)
    double density = 1000.0;    ///< ρ_w of the water the body is in, kg/m³
    double gravity = 9.81;      ///< g, m/s² (> 0)
    /// The spacing of the positions the physics engine can store near the body, m (≥ 0; 0: exact): its scalar's
    /// machine epsilon × the body's largest world coordinate. A single-precision Bullet 600 m from its origin rounds
    /// every position to 61 µm, more than the pose check's tolerance on a boat (tens of µm): drifts within a few such
    /// roundings are not taken for a contact (design.md 2.5 "Fewer evaluations in time").
    double positionResolution = 0;
};

/// The temporal level-of-detail controller of one body: its records, its interval and the checks' counters.
/// Everything it carries from one substep to the next is saved by writeState, bit for bit.
class TemporalLevelOfDetail {
public:
    /// A controller for a body of volume `volume` (m³, > 0: the unit solid's) and bounding-sphere radius `radius`
    /// (m, > 0); the defaults (0) are only for a controller assigned later.
    explicit TemporalLevelOfDetail(double volume = 0, double radius = 0) : m_volume(volume), m_radius(radius) {}

    /// The body's phase (its registration order in the world, dimensionless): it evaluates exactly when
    /// (substep + phase) % interval == 0, so that bodies take turns.
    void setPhase(std::uint64_t phase) { m_phase = phase; }
    /// The phase set by setPhase (dimensionless).
    std::uint64_t getPhase() const { return m_phase; }

    /// Start a substep: adopt `settings`' tolerance and interval, or keep the divisor of the interval that the checks
    /// chose (an interval that no longer divides it, a larger one or none yet is replaced by `settings.interval`, and
    /// the check counters start afresh).
    void begin(const TemporalLevelOfDetailSettings& settings);
    /// This substep's interval (set by begin), substeps.
    int getInterval() const { return m_interval; }
    /// This substep's prediction tolerance (set by begin), fraction of ρ g V (dimensionless).
    double getTolerance() const { return m_tolerance; }
    /// True when `substep` (the world's counter) is one of the body's evaluation substeps at this substep's interval.
    bool isEvaluationSubstep(std::uint64_t substep) const {
        return (substep + m_phase) % std::uint64_t(m_interval) == 0;
    }

    /// Fill `predicted` with this substep's extrapolated evaluation, moved to the actual pose, and return true; or
    /// return false when the substep must be evaluated exactly (too few records, a cool-down after a missed check, a
    /// body about to go entirely under water or out of it, or one that left the extrapolated pose).
    /// @param step      the substep (substep counter, time s, dt s, density kg/m³, gravity m/s²)
    /// @param pose      the mesh's pose in the water frame (translation m)
    /// @param com       the centre of mass in the water frame, m
    /// @param bodyLow, bodyHigh    the lowest and highest height of the body's bounding sphere, m
    /// @param waterLow, waterHigh  the water's bounds over its footprint (btWaterSurface::heightBounds), m
    /// @param[out] predicted       the prediction (pressure force N, torque N·m about the COM, drag N and N·m, …);
    ///                             meaningful only when true is returned
    bool predict(const TemporalLevelOfDetailSubstep& step, const Eigen::Isometry3d& pose, const Eigen::Vector3d& com,
                 double bodyLow, double bodyHigh, double waterLow, double waterHigh,
                 HydrostaticsSnapshot& predicted) const;

    /// True when the extrapolated drag of `predicted` may be used: the motion (v m/s, w rad/s, the velocity drag is
    /// evaluated at) is within allowedVelocityDeviation of the extrapolated one.
    /// @param meanWaterVelocity  the mean water velocity of the last computed drag, m/s
    /// @param gravity            g, m/s²
    bool dragFollows(const Eigen::Vector3d& v, const Eigen::Vector3d& w, const Eigen::Vector3d& meanWaterVelocity,
                     const HydrostaticsSnapshot& predicted, double gravity) const;

    /// After an exact evaluation at one of the body's evaluation substeps: check the predictor against it (which may
    /// halve or double the interval, or start a cool-down), then record it (a non-finite one clears the records).
    /// @param step           the substep (as for predict)
    /// @param exact          the exact evaluation (hydrostatics, drag before its stability limit, pose, velocities)
    /// @param effectiveMass  the heave's mass with its added mass, kg (> 0)
    void record(const TemporalLevelOfDetailSubstep& step, const HydrostaticsSnapshot& exact, double effectiveMass);

    /// Set the slope scale of the water over the body at the last exact evaluation (dimensionless: 0 flat water,
    /// WaterPatch::slopeBound on a patch, 1 otherwise); it weighs a horizontal drift in the pose check.
    void setWaterSlope(double slope) { m_lastWaterSlope = slope; }
    /// The slope scale set by setWaterSlope (dimensionless).
    double getWaterSlope() const { return m_lastWaterSlope; }

    /// Forget the records (a dry, rejected or primed substep, another water or frame, a wake-up): the body evaluates
    /// exactly until it has enough again. The interval and the check counters stay.
    void clear() { m_history.clear(); }
    /// Forget the records and the adapted interval (settings changed): the next begin takes the resolved interval.
    void restart() {
        m_history.clear();
        m_adaptedInterval = 0;
    }
    /// The exact evaluations held.
    const HydrostaticsHistory& getHistory() const { return m_history; }

    /// ℓ = V / max(A_waterline, V^(2/3)): the draft change that moves the pressure force by ρ g V, m; the pose and
    /// velocity checks scale with it. @param waterlineArea  m²
    double reuseLength(double waterlineArea) const;
    /// The pose deviation up to which the extrapolated hydrostatics are used, m. @param waterlineArea  m²
    double allowedPoseDeviation(double waterlineArea) const;
    /// The velocity deviation (HydrostaticsHistory::velocityDeviation) up to which the extrapolated drag is used,
    /// m/s. @param waterlineArea  m²  @param relativeSpeed  |v − u_water| + radius |ω|, m/s  @param gravity  g, m/s²
    double allowedVelocityDeviation(double waterlineArea, double relativeSpeed, double gravity) const;

    /// Save (btBuoyancyAction::saveState): the records, then the cool-down, phase, interval, adapted interval, check
    /// misses, passes, passing error sum, probation, tolerance and water slope, bit for bit. The volume and radius are
    /// not saved (they come from the shape).
    void writeState(StateWriter& out) const;
    /// Read what writeState wrote; checked whole first. @throws std::invalid_argument naming the problem (the
    /// controller unchanged)
    void readState(StateReader& in);

private:
    double m_volume = 0;               ///< the body's volume V, m³
    double m_radius = 0;               ///< its bounding-sphere radius, m
    HydrostaticsHistory m_history;   ///< the last exact evaluations at this body's evaluation substeps
    int m_reuseCooldown = 0;           ///< passing checks (or evaluation substeps without one) before predicting again
    std::uint64_t m_phase = 0;         ///< the body evaluates exactly when (substep + m_phase) % interval == 0
    int m_interval = 1;                ///< this substep's interval (m_adaptedInterval), substeps
    /// This body's interval, substeps: the resolved one, halved after repeated misses of the check and doubled back
    /// after a run of passes (record); 0 until the first substep.
    int m_adaptedInterval = 0;
    int m_resolvedInterval = 1;        ///< begin's settings.interval, substeps (not saved: set every substep)
    std::uint8_t m_checkMisses = 0;    ///< the last eight checks, one bit per miss (newest lowest)
    int m_checkPasses = 0;             ///< checks passed in a row at a halved interval
    double m_passingErrorSum = 0;      ///< the sum of those checks' errors, fraction of ρ g V (dimensionless)
    int m_probation = 0;               ///< checks left in which one miss undoes a doubling
    double m_tolerance = 1e-4;         ///< this substep's prediction tolerance, fraction of ρ g V (dimensionless)
    /// Slope scale of the water over the body at the last exact evaluation (dimensionless, setWaterSlope).
    double m_lastWaterSlope = 1.0;
};

}  // namespace buoyancy
