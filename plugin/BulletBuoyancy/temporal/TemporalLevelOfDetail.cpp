#include <BulletBuoyancy/temporal/TemporalLevelOfDetail.h>

#include <BulletBuoyancy/state/StateBlob.h>

#include <algorithm>
#include <cmath>

namespace buoyancy {

void TemporalLevelOfDetail::begin(const TemporalLevelOfDetailSettings& settings) {
    // This body's interval: the resolved one, or a divisor of it after repeated misses (record).
    const int resolved = settings.interval;
    m_resolvedInterval = resolved;
    if (m_adaptedInterval <= 0 || m_adaptedInterval > resolved || resolved % m_adaptedInterval != 0) {
        m_adaptedInterval = resolved;
        m_checkMisses = 0;
        m_checkPasses = 0;
    }
    m_interval = m_adaptedInterval;
    m_tolerance = settings.tolerance;
}

double TemporalLevelOfDetail::reuseLength(double waterlineArea) const {
    // ℓ = V / A_waterline: the draft change that moves the pressure force by ρ g V; a body under water
    // (A_waterline = 0) is bounded by V^(1/3).
    const double volume = m_volume;
    const double volume23 = std::cbrt(volume) * std::cbrt(volume);
    return volume / std::max(waterlineArea, volume23);
}

double TemporalLevelOfDetail::allowedPoseDeviation(double waterlineArea) const {
    // A drift δ changes the pressure force by about ρ g A_waterline δ, a fraction δ / ℓ of ρ g V: allow the
    // tolerance's worth.
    return m_tolerance * reuseLength(waterlineArea);
}

double TemporalLevelOfDetail::allowedVelocityDeviation(double waterlineArea, double relativeSpeed,
                                                       double gravity) const {
    // The velocity scale of ℓ: sqrt(g ℓ) (the speed of a body falling through its draft); drag changes by a
    // fraction of the tolerance when the velocity leaves the extrapolated one by that. A moving body may also
    // deviate by kDragReuseFraction of its speed through the water: quadratic drag then changes by twice that
    // fraction of itself (linear damping and skin friction by that fraction), 1 %, below the error the default drag
    // clusters accept (0.35–4.3 % of the drag force against every fine sample, docs/benchmarks drag_lod.csv).
    constexpr double kDragReuseFraction = 0.005;
    return std::max(m_tolerance * std::sqrt(gravity * reuseLength(waterlineArea)), kDragReuseFraction * relativeSpeed);
}

bool TemporalLevelOfDetail::dragFollows(const Eigen::Vector3d& v, const Eigen::Vector3d& w,
                                        const Eigen::Vector3d& meanWaterVelocity,
                                        const HydrostaticsSnapshot& predicted, double gravity) const {
    return HydrostaticsHistory::velocityDeviation(v, w, predicted, m_radius) <=
           allowedVelocityDeviation(predicted.hydrostatics.waterline_area,
                                    (v - meanWaterVelocity).norm() + m_radius * w.norm(), gravity);
}

bool TemporalLevelOfDetail::predict(const TemporalLevelOfDetailSubstep& step, const Eigen::Isometry3d& pose,
                                    const Eigen::Vector3d& com, double bodyLow, double bodyHigh, double waterLow,
                                    double waterHigh, HydrostaticsSnapshot& predicted) const {
    const int interval = m_interval;
    if (m_reuseCooldown > 0 || !m_history.canPredict(step.substep, step.time, interval)) return false;
    predicted = m_history.extrapolate(step.substep, interval);
    // A body about to go entirely under water or out of it: the submerged volume saturates there (a kink in time
    // that no polynomial follows; measured: a boat overrun by a crest was predicted 0.12 % of ρ g V off). While the
    // body straddles the surface, two more intervals at the last interval's rate of volume change must keep it
    // within the tolerance of both ends.
    const double volume = m_volume, v0 = m_history.volume(0, interval);
    if (predicted.hydrostatics.waterline_area > 0) {
        const double reach = 2.0 * std::abs(v0 - m_history.volume(1, interval));
        if (!(v0 + reach <= (1.0 - m_tolerance) * volume && v0 - reach >= m_tolerance * volume)) return false;
    } else if (v0 > 0.5 * volume ? !(bodyHigh < waterLow) : !(bodyLow > waterHigh)) {
        // Entirely under water (or out of it) at the last evaluation, and now within reach of the surface: the body
        // may be surfacing (or landing), which no extrapolation of the records sees. Measured: a boat thrown clear of
        // the swell was predicted dry for 6 substeps while it plunged back in, 0.35 % of ρ g V off at the end.
        return false;
    }
    // Pose check: a body moved by a contact, a teleport or an impulse leaves the extrapolated pose. With the
    // waterplane's moments the prediction follows the actual height and attitude to first order (the hydrostatic
    // stiffness correction below), and what is left is a horizontal drift over sloped water and the second-order
    // terms; without them, the drift.
    const double radius = m_radius;
    double deviation;
    if (predicted.hydrostatics.waterplane.valid)
        deviation = HydrostaticsHistory::correctedPoseDeviation(com, pose.linear(), predicted, radius,
                                                                m_lastWaterSlope);
    else
        deviation = HydrostaticsHistory::poseDeviation(com, pose.linear(), predicted, radius, m_lastWaterSlope);
    hydrostaticStiffnessCorrection(predicted, com, pose.linear(), step.density * step.gravity);
    // Rounding of the stored positions: each record and the pose now are rounded to the engine's resolution, and the
    // cubic extrapolation weighs the four records by up to 4, 6, 4 and 1 (15 × half a resolution), so a drift of
    // kRoundingResolutions resolutions over the water's slope is noise, not a contact (design.md 2.5).
    constexpr double kRoundingResolutions = 8.0;
    const double roundingFloor = m_lastWaterSlope * kRoundingResolutions * step.positionResolution;
    return deviation <= std::max(allowedPoseDeviation(predicted.hydrostatics.waterline_area), roundingFloor) &&
           predicted.hydrostatics.force.allFinite() && predicted.hydrostatics.torque.allFinite() &&
           predicted.dragForce.allFinite() && predicted.dragTorque.allFinite();
}

void TemporalLevelOfDetail::record(const TemporalLevelOfDetailSubstep& step, const HydrostaticsSnapshot& exact,
                                   double effectiveMass) {
    const std::uint64_t substep = step.substep;
    const int interval = m_interval;
    const HydrostaticsResult& h = exact.hydrostatics;
    const double scale = step.density * step.gravity * m_volume;
    const double diameter = 2.0 * m_radius;
    // Check the predictor against this exact evaluation (one interval past the newest record: a little further than
    // any substep it predicted). A miss makes the body evaluate exactly until two checks in a row pass (one pass after
    // a miss was often luck: in a fleet of 200 boats in the scaling sea the worst predicted substep fell from 0.095 % to
    // 0.054 % of ρ g V with this and the next rule, at the same share of substeps predicted). Two misses in a row, or
    // three in the last four checks: the body's motion is too fast for its interval (the extrapolation's error grows
    // like the interval⁴), which is halved
    // (down to 2, and only to a divisor of the resolved interval); it is doubled back after 16 passes in a row whose
    // mean error × 2⁴ stays within half the tolerance, or after 64 (a miss in the first four checks after a
    // doubling halves it again at once). The records are kept across the switches (HydrostaticsHistory keeps
    // seven, and interpolates the two a halving needs), so predictions go on without a warm-up. Measured: an
    // undamped sphere bobbing at ω = 4.4 rad/s missed half its checks at 1/30 s and lost 0.5 % of its amplitude a
    // minute through the exact intervals the misses forced; with the halving 0.3 %. A single miss (a wave
    // overrunning a deck) keeps the interval.
    const double time = step.time;
    bool halve = false;
    if (m_history.canCheck(substep, time, interval)) {
        HydrostaticsSnapshot p = m_history.extrapolate(substep, interval);
        // As a prediction at this pose would be.
        hydrostaticStiffnessCorrection(p, exact.com, exact.rotation, step.density * step.gravity);
        // The predictions reach a = (K − 1)/K of the interval, where the cubic's remainder a(a+1)(a+2)(a+3)/24 is
        // that fraction of its value at a = 1 (0.76 at K = 8, 0.56 at K = 4): the error of the furthest prediction.
        const double a = double(interval - 1) / double(interval);
        const double reach = a * (a + 1.0) * (a + 2.0) * (a + 3.0) / 24.0;
        const double error = reach * std::max((p.hydrostatics.force - h.force).norm() / scale,
                                              (p.hydrostatics.torque - h.torque).norm() / (scale * diameter));
        const bool miss = !(error <= m_tolerance);
        const int probation = m_probation;
        if (m_probation > 0) --m_probation;
        m_checkMisses = std::uint8_t((m_checkMisses << 1) | (miss ? 1 : 0));
        const int resolved = m_resolvedInterval;
        if (miss) {
            m_checkPasses = 0;
            m_passingErrorSum = 0;
            const int bits = (m_checkMisses & 1) + ((m_checkMisses >> 1) & 1) + ((m_checkMisses >> 2) & 1) +
                             ((m_checkMisses >> 3) & 1);
            const bool twoInARow = (m_checkMisses & 3) == 3;
            if ((bits >= 3 || twoInARow || probation > 0) && interval % 2 == 0 && interval / 2 >= 2) {
                m_adaptedInterval = interval / 2;  // this substep is on the halved interval's grid too
                m_checkMisses = 0;
                m_probation = 0;
                halve = true;  // the records' spacing, once this evaluation is pushed
            } else {
                m_reuseCooldown = 2;  // predictions resume after two passing checks in a row
            }
        } else {
            if (m_reuseCooldown > 0) --m_reuseCooldown;
            m_passingErrorSum += error;
            // Doubled, the error would grow ≈ 2⁴ times: doubled after 16 passes when the mean error so grown stays
            // within half the tolerance, else after 64.
            ++m_checkPasses;
            const bool smooth =
                m_checkPasses >= 16 && 16.0 * m_passingErrorSum / double(m_checkPasses) <= 0.5 * m_tolerance;
            if (interval < resolved && (smooth || m_checkPasses >= 64) &&
                resolved % (2 * interval) == 0 &&
                (substep + m_phase) % std::uint64_t(2 * interval) == 0) {
                m_adaptedInterval = 2 * interval;  // on the doubled interval's grid: the next record is 2K away
                m_checkPasses = 0;
                m_passingErrorSum = 0;
                m_checkMisses = 0;  // (the records kept include every other one at the doubled spacing)
                m_probation = 4;    // a miss in the next four checks halves it again at once
            }
        }
    } else if (m_reuseCooldown > 0) {
        --m_reuseCooldown;
    }
    // Stiffness check: extrapolating over an interval is only accurate while the heave is slow against it
    // (ω K dt ≤ 0.3 with ω² = ρ g A_waterline / m_eff, design.md 2.7); a light, stiff body evaluates exactly.
    const double omega2 = step.density * step.gravity * h.waterline_area / effectiveMass;
    const double period = double(interval) * step.dt;  // K dt, s
    if (!(omega2 * period * period <= 0.09)) m_reuseCooldown = std::max(m_reuseCooldown, 1);
    const bool finite = h.force.allFinite() && h.torque.allFinite() && std::isfinite(h.submerged_volume) &&
                        exact.dragForce.allFinite() && exact.dragTorque.allFinite();
    if (finite) {
        m_history.push(substep, time, exact);
        if (halve) m_history.halveSpacing(interval);
    } else {
        m_history.clear();
    }
}

void TemporalLevelOfDetail::writeState(StateWriter& out) const {
    m_history.writeState(out);
    out.i32(m_reuseCooldown);
    out.u64(m_phase);
    out.i32(m_interval);
    out.i32(m_adaptedInterval);
    out.u8(m_checkMisses);
    out.i32(m_checkPasses);
    out.f64(m_passingErrorSum);
    out.i32(m_probation);
    out.f64(m_tolerance);
    out.f64(m_lastWaterSlope);
}

void TemporalLevelOfDetail::readState(StateReader& in) {
    // Everything is read into locals first, then committed (a bad blob leaves the controller as it was).
    HydrostaticsHistory history;
    history.readState(in);
    const int reuseCooldown = in.i32("reuse cool-down");
    const std::uint64_t phase = in.u64("phase");
    const int interval = in.i32("interval");
    const int adaptedInterval = in.i32("adapted interval");
    const std::uint8_t checkMisses = in.u8("check misses");
    const int checkPasses = in.i32("check passes");
    const double passingErrorSum = in.f64("passing error sum");
    const int probation = in.i32("probation");
    const double tolerance = in.f64("tolerance");
    const double lastWaterSlope = in.f64("last water slope");
    m_history = history;
    m_reuseCooldown = reuseCooldown;
    m_phase = phase;
    m_interval = interval;
    m_adaptedInterval = adaptedInterval;
    m_checkMisses = checkMisses;
    m_checkPasses = checkPasses;
    m_passingErrorSum = passingErrorSum;
    m_probation = probation;
    m_tolerance = tolerance;
    m_lastWaterSlope = lastWaterSlope;
}

}  // namespace buoyancy
