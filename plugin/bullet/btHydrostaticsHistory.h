#pragma once
/// @file btHydrostaticsHistory.h
/// Temporal level of detail (issue 9; btBuoyancySettings::hydrostaticsInterval): a body evaluates its
/// hydrostatics and drag exactly every K-th substep and, in between, predicts them by extrapolating the last three
/// exact evaluations quadratically in time. The prediction is refused when the body's pose has left the pose
/// extrapolated the same way (a contact, a teleport, a user impulse) or when the last check of the predictor
/// against an exact evaluation failed; the action then evaluates exactly.

#include "integrals/Hydrostatics.h"

#include <Eigen/Geometry>

#include <array>
#include <cstdint>

/// What one substep's evaluation of a body gives and where the body was (world frame, SI units).
struct btHydrostaticsSnapshot {
    buoyancy::HydrostaticsResult hydrostatics;  ///< pressure force N, torque about the COM N·m, volume m³, …
    Eigen::Vector3d com = Eigen::Vector3d::Zero();               ///< centre of mass, m
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();      ///< body → world
    Eigen::Vector3d dragForce = Eigen::Vector3d::Zero();         ///< before the stability limit, N
    Eigen::Vector3d dragTorque = Eigen::Vector3d::Zero();        ///< about the COM, before the limit, N·m
    Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();    ///< the velocity drag was evaluated at, m/s
    Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();   ///< rad/s
};

/// The last three exact evaluations of one body at its evaluation substeps (every K-th), and the quadratic
/// extrapolation between them.
///
/// Extrapolation (Newton's backward-difference form on equally spaced samples): with x₀ the newest record, x₁
/// and x₂ the older ones, K substeps apart, the value j substeps after x₀ is, for a = j/K,
/// x(a) = x₀ + a ∇x₀ + a(a+1)/2 ∇²x₀ with ∇x₀ = x₀ − x₁, ∇²x₀ = x₀ − 2x₁ + x₂ — exact when x is a quadratic in
/// time. The rotation is extrapolated entry by entry and not re-orthonormalised: it only measures how far the body
/// left the predicted pose. Volume and areas extrapolated below zero are clamped to zero.
class btHydrostaticsHistory {
public:
    /// Forget every record (after a dry, rejected or primed substep, a settings change, a wake-up).
    void clear() { m_count = 0; }

    /// Number of records held (0..3).
    int size() const { return m_count; }

    /// Record an exact evaluation made at `substep` (the world's substep counter) and water time `time` (s).
    void push(std::uint64_t substep, double time, const btHydrostaticsSnapshot& snapshot);

    /// True when three records `interval` substeps and equal times apart are held, `substep` lies strictly between
    /// the newest and the next evaluation substep (1 ≤ substep − newest < interval) and `time` is where equal
    /// substeps put it (a changed substep length makes the extrapolation meaningless).
    bool canPredict(std::uint64_t substep, double time, int interval) const;

    /// As canPredict, for the next evaluation substep itself (substep − newest = interval): the exact evaluation
    /// there checks the predictor.
    bool canCheck(std::uint64_t substep, double time, int interval) const;

    /// The records extrapolated to `substep` (call only when canPredict or canCheck).
    btHydrostaticsSnapshot extrapolate(std::uint64_t substep, int interval) const;

    /// How far a pose is from the extrapolated one, m: |Δcom| + radius · |ΔR|_F / √2 (|ΔR|_F / √2 is the angle
    /// of a small rotation, so the second term bounds how far any point within `radius` of the COM moved).
    static double poseDeviation(const Eigen::Vector3d& com, const Eigen::Matrix3d& rotation,
                                const btHydrostaticsSnapshot& predicted, double radius);

    /// How far a motion is from the extrapolated one, m/s: |Δv| + radius · |Δω|.
    static double velocityDeviation(const Eigen::Vector3d& linearVelocity, const Eigen::Vector3d& angularVelocity,
                                    const btHydrostaticsSnapshot& predicted, double radius);

private:
    static constexpr int kValues = 36;  ///< numbers per record (see pack)
    /// Records equally spaced, `substep` at most `interval` past the newest, `time` consistent with both.
    bool spaced(std::uint64_t substep, double time, int interval, std::uint64_t maxAhead) const;
    /// One exact evaluation: the world substep, its water time (s) and the snapshot's numbers.
    struct Record {
        std::uint64_t substep = 0;
        double time = 0;
        std::array<double, kValues> x{};
    };
    static std::array<double, kValues> pack(const btHydrostaticsSnapshot& s);
    static btHydrostaticsSnapshot unpack(const std::array<double, kValues>& x);
    std::array<Record, 3> m_records;  ///< newest first
    int m_count = 0;
};
