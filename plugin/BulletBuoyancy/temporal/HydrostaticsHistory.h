#pragma once
/// @file HydrostaticsHistory.h
/// The records of the temporal level of detail (design.md 2.5 "Fewer evaluations in time"; the controller is
/// TemporalLevelOfDetail, asked for by btBuoyancySettings::hydrostaticsInterval in the Bullet layer): a body evaluates
/// its hydrostatics and drag exactly every K-th substep and, in between, predicts them by extrapolating the last four
/// exact evaluations in time (a cubic). The prediction is refused when the body's pose has left the pose
/// extrapolated the same way (a contact, a teleport, a user impulse) or when the last check of the predictor
/// against an exact evaluation failed; the body is then evaluated exactly.

#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <Eigen/Geometry>

#include <array>
#include <cstdint>

namespace buoyancy {

class StateWriter;
class StateReader;

/// What one substep's evaluation of a body gives and where the body was (world frame, SI units).
struct HydrostaticsSnapshot {
    HydrostaticsResult hydrostatics;  ///< pressure force N, torque about the COM N·m, volume m³, …
    Eigen::Vector3d com = Eigen::Vector3d::Zero();               ///< centre of mass, m
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();      ///< body → world
    Eigen::Vector3d dragForce = Eigen::Vector3d::Zero();         ///< before the stability limit, N
    Eigen::Vector3d dragTorque = Eigen::Vector3d::Zero();        ///< about the COM, before the limit, N·m
    Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();    ///< the velocity drag was evaluated at, m/s
    Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();   ///< rad/s
};

/// The last four exact evaluations of one body at its evaluation substeps (every K-th), and the cubic
/// extrapolation from them.
///
/// Extrapolation (Newton's backward-difference form on equally spaced samples): with x₀ the newest record, x₁,
/// x₂, x₃ the older ones, K substeps apart, the value j substeps after x₀ is, for a = j/K,
/// x(a) = x₀ + a ∇x₀ + a(a+1)/2 ∇²x₀ + a(a+1)(a+2)/6 ∇³x₀ with ∇x₀ = x₀ − x₁, ∇²x₀ = x₀ − 2x₁ + x₂,
/// ∇³x₀ = x₀ − 3x₁ + 3x₂ − x₃ — exact when x is a cubic in time. Its error one interval ahead is x⁗ (K dt)⁴ against
/// the quadratic's x‴ (K dt)³: for a force that varies like the waves, sin ωt, the cubic is ω K dt times as far off
/// (0.08 for the scaling sea's shortest wave at K dt = 1/30 s). Measured in the scaling sea (boat-x4 at 1/30 s, the
/// check's error one interval ahead): median 1.3e-4 of ρ g V with the quadratic, 1.5e-5 with the cubic. The rotation
/// is extrapolated entry by entry and not re-orthonormalised: it only measures how far the body left the predicted
/// pose. Volume and areas extrapolated below zero are clamped to zero.
class HydrostaticsHistory {
public:
    /// Records the extrapolation uses (four: a cubic).
    static constexpr int kRecords = 4;
    /// Records kept: enough for four at twice the spacing (an interval doubled keeps predicting at once).
    static constexpr int kStored = 7;
    /// Numbers per record (see pack).
    static constexpr int kValues = 41;

    /// Forget every record (after a dry, rejected or primed substep, a settings change, a wake-up).
    void clear() { m_count = 0; }

    /// Number of records held (0..kStored).
    int size() const { return m_count; }

    /// Record an exact evaluation made at `substep` (the world's substep counter) and water time `time` (s).
    void push(std::uint64_t substep, double time, const HydrostaticsSnapshot& snapshot);

    /// True when kRecords records `interval` substeps and equal times apart are held, `substep` lies strictly between
    /// the newest and the next evaluation substep (1 ≤ substep − newest < interval) and `time` is where equal
    /// substeps put it (a changed substep length makes the extrapolation meaningless).
    bool canPredict(std::uint64_t substep, double time, int interval) const;

    /// As canPredict, for the next evaluation substep itself (substep − newest = interval): the exact evaluation
    /// there checks the predictor.
    bool canCheck(std::uint64_t substep, double time, int interval) const;

    /// The submerged volume `intervalsBack` intervals before the newest record (0 … kRecords − 1), m³; 0 when the
    /// records are not spaced by `interval`.
    double volume(int intervalsBack, int interval) const;

    /// The body's interval is halved from `interval` (even, ≥ 4): the two missing records, half an interval before
    /// the newest and the second newest, are interpolated (a cubic through the four, well inside their span), so
    /// that predictions go on at the new spacing. Otherwise the history is cleared.

    void halveSpacing(int interval);

    /// The records extrapolated to `substep` (call only when canPredict or canCheck). Its waterplane moments are
    /// valid when every record's were.
    HydrostaticsSnapshot extrapolate(std::uint64_t substep, int interval) const;

    /// How far a pose is from the extrapolated one, as a change of draft, m: |Δcom_y| + waterSlope · |Δcom_xz| +
    /// radius · |ΔR|_F / √2. |ΔR|_F / √2 is the angle of a small rotation, so the last term bounds how far any point
    /// within `radius` of the COM moved; a horizontal shift δ changes the water height under the body by at most
    /// waterSlope · δ (0 in flat water: the pressure force does not depend on where the body is).
    /// @param waterSlope  bound on the water surface's slope over the body's footprint, dimensionless (0 flat water,
    ///                    1 when unknown)
    static double poseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                const HydrostaticsSnapshot& predicted, double radius, double waterSlope = 1.0);

    /// What is left of poseDeviation once the prediction follows the actual height and attitude to first order
    /// (the linear hydrostatic stiffness, hydrostaticStiffnessCorrection in TemporalLevelOfDetail::predict), as a
    /// change of draft, m:
    /// waterSlope · (|Δcom_xz| + radius θ) + 8 (|Δcom_y| + radius θ)² / radius, θ = |ΔR|_F / √2. The first term is
    /// the water height change under a waterplane point that moves sideways; the second bounds the second-order
    /// terms, a waterline area that changes with draft by up to 16 A / radius (a flare of ≈ 45° on a body of that
    /// radius) giving ½ · 16 A / radius · δ² of volume.
    static double correctedPoseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                         const HydrostaticsSnapshot& predicted, double radius, double waterSlope);

    /// How far a motion is from the extrapolated one, m/s: |Δv| + radius · |Δω|.
    static double velocityDeviation(const Eigen::Vector3d& linearVelocity, const Eigen::Vector3d& angularVelocity,
                                    const HydrostaticsSnapshot& predicted, double radius);

    /// Save and restore (TemporalLevelOfDetail::writeState, inside btBuoyancyAction::saveState): every record held,
    /// bit for bit.
    void writeState(StateWriter& out) const;
    /// Read what writeState wrote. @throws std::invalid_argument for a bad record count (the history unchanged)
    void readState(StateReader& in);

private:
    /// The newest record and the three `interval` substeps apart before it (indices into m_records), equally
    /// spaced in time; false when they are not all held.
    bool find(int interval, int index[kRecords]) const;
    /// Records equally spaced, `substep` at most `interval` past the newest, `time` consistent with both.
    bool spaced(std::uint64_t substep, double time, int interval, std::uint64_t maxAhead) const;
    /// One exact evaluation: the world substep, its water time (s) and the snapshot's numbers.
    struct Record {
        std::uint64_t substep = 0;
        double time = 0;
        std::array<double, kValues> x{};
        bool waterplane = false;  ///< the snapshot's waterplane moments were valid
    };
    static std::array<double, kValues> pack(const HydrostaticsSnapshot& s);
    static HydrostaticsSnapshot unpack(const std::array<double, kValues>& x);
    std::array<Record, kStored> m_records;  ///< newest first
    int m_count = 0;
};

/// Move a pressure force, torque (about the COM) and submerged volume evaluated at one pose (predicted.com,
/// predicted.rotation) to a nearby pose (COM `com`, m; `rotation` body → world) through the linear hydrostatic
/// stiffness (design.md 2.7; Faltinsen, "Sea Loads on Ships and Offshore Structures", 1990, ch. 2): a waterplane
/// point at (x', z') from the COM rises by δy + φ_z x' − φ_x z' (δy the COM's rise, φ the small rotation between the
/// attitudes), the slab of water it leaves changes the volume by −∫ that dA and the torque by ρ g ∫ (z', ·, −x') × that
/// dA, and the submerged part turns with the body (its buoyancy acts through the turned centre of buoyancy). Heave
/// through waterline_area always; roll and pitch only when hydrostatics.waterplane.valid. Exact to first order in
/// the pose change (tests/bullet/TemporalLodTest.cpp checks it against exact evaluations).
/// @param rhoG  ρ g, N/m³
void hydrostaticStiffnessCorrection(HydrostaticsSnapshot& predicted, const Eigen::Vector3d& com,
                                    const Eigen::Matrix3d& rotation, double rhoG);

}  // namespace buoyancy
