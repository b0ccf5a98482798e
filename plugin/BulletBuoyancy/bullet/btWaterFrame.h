#pragma once
/// @file btWaterFrame.h
/// The frame a water surface is a height field in (design.md 3, "Any up axis"). Every btWaterSurface answers in
/// its own coordinates (x, y, z) with y up: the water is y = f(x, z, t). The frame places those coordinates in the
/// world: an origin, the up axis (−ĝ of the world) and a first horizontal axis; the second horizontal axis completes
/// a right-handed frame, ẑ_water = x̂_water × ŷ_water (so the frame (x̂, up, ẑ) has the orientation of (x̂, ŷ, ẑ)).
///
///   world point p  →  water coordinates  q = Rᵀ (p − o),   R = [x̂_water | up | ẑ_water] (columns, world)
///   water vector u →  world vector        Ru
///
/// The Bullet layer maps each body's pose and velocities into the water frame, runs the Bullet-free core (which is
/// y-up) there and maps the forces, torques and points back: one rigid transform per body and substep, so every
/// water type and every feature (drag, flooding, the OpenCL backend) works in any up direction.
///
/// The default frame follows the world's gravity: up = −ĝ/|g|, origin (0, 0, 0), first horizontal axis world +x
/// whenever up ⟂ x (so a +y-up world keeps today's (x, z), and a +z-up world has x̂_water = +x, ẑ_water = −y). No single
/// rule suits every up direction continuously; for other ups the first horizontal axis is world +x projected onto
/// the horizontal plane, or world +y projected when up is within 60° of ±x (fromUp). A rotated scene therefore
/// rotates its frame too (btWaterFrame(origin, up, x)).

#include <LinearMath/btTransform.h>

#include <Eigen/Geometry>

#include <string>

/// A right-handed orthonormal frame: origin (m, world), up and first horizontal axis (unit vectors, world).
class btWaterFrame {
public:
    /// The identity frame: origin (0, 0, 0), up +y, first horizontal axis +x (the water's coordinates are the world's).
    btWaterFrame() = default;
    /// An explicit frame.
    /// @param origin  the point of water coordinates (0, 0, 0), m, world; a surface's height is measured along up from it
    /// @param up      the up axis (any length > 0; normalised), world
    /// @param xAxis   the first horizontal axis (any length > 0; normalised), world; perpendicular to up within 1e-6 rad
    /// @throws std::invalid_argument naming the bad vector (zero, not finite, or not perpendicular to up)
    btWaterFrame(const btVector3& origin, const btVector3& up, const btVector3& xAxis);
    /// The double-precision form of the constructor above (same checks).
    btWaterFrame(const Eigen::Vector3d& origin, const Eigen::Vector3d& up, const Eigen::Vector3d& xAxis);

    /// The default frame for `up` (any length > 0): first horizontal axis world +x whenever up ⟂ x, else +x projected
    /// onto the plane ⟂ up, or +y projected when |up·x̂| > cos 60° (see the file comment). @throws std::invalid_argument
    static btWaterFrame fromUp(const Eigen::Vector3d& up, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
    /// The default frame of a world with gravity `gravity` (m/s², world): fromUp(−gravity).
    /// @throws std::invalid_argument for a zero or non-finite gravity (no up direction)
    static btWaterFrame fromGravity(const Eigen::Vector3d& gravity, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

    /// Origin, m, world.
    const Eigen::Vector3d& origin() const { return m_origin; }
    /// Up (unit), world.
    Eigen::Vector3d up() const { return m_rotation.col(1); }
    /// First horizontal axis (unit), world.
    Eigen::Vector3d xAxis() const { return m_rotation.col(0); }
    /// Second horizontal axis (unit), world: xAxis × up.
    Eigen::Vector3d zAxis() const { return m_rotation.col(2); }
    /// R: columns xAxis, up, zAxis (water → world rotation).
    const Eigen::Matrix3d& rotation() const { return m_rotation; }
    /// True for the identity frame (origin 0, axes the world's): the maps below are then the identity (and skipped).
    bool isIdentity() const { return m_identity; }

    ///@name Maps between world and water coordinates (double precision)
    ///@{
    /// World point (m) → water coordinates (m).
    Eigen::Vector3d toWaterPoint(const Eigen::Vector3d& p) const {
        return m_identity ? p : Eigen::Vector3d(m_rotation.transpose() * (p - m_origin));
    }
    /// World vector (force N, torque N·m, velocity m/s, angular velocity rad/s, acceleration m/s²) → water frame.
    Eigen::Vector3d toWaterVector(const Eigen::Vector3d& v) const {
        return m_identity ? v : Eigen::Vector3d(m_rotation.transpose() * v);
    }
    /// Water coordinates (m) → world point (m).
    Eigen::Vector3d toWorldPoint(const Eigen::Vector3d& q) const {
        return m_identity ? q : Eigen::Vector3d(m_rotation * q + m_origin);
    }
    /// Water-frame vector → world vector (same units).
    Eigen::Vector3d toWorldVector(const Eigen::Vector3d& u) const { return m_identity ? u : Eigen::Vector3d(m_rotation * u); }
    /// A pose (body → world) as a pose body → water coordinates.
    Eigen::Isometry3d toWater(const Eigen::Isometry3d& pose) const;
    /// A 3 × 3 world-frame tensor (e.g. the inverse inertia, 1/(kg·m²)) in water axes: Rᵀ M R.
    Eigen::Matrix3d toWaterTensor(const Eigen::Matrix3d& m) const {
        return m_identity ? m : Eigen::Matrix3d(m_rotation.transpose() * m * m_rotation);
    }
    ///@}

    /// The frame as a Bullet transform (water coordinates → world).
    btTransform getTransform() const;
    /// Angle between up and −gravity, rad (π/2 for a zero gravity is not returned: the caller checks |g| first).
    double angleToGravity(const Eigen::Vector3d& gravity) const;
    /// "(x, y, z)" with 6 significant digits, for messages.
    static std::string vectorText(const Eigen::Vector3d& v);

private:
    friend class btBuoyancyWorld;  // restoreState sets a saved frame bit for bit
    Eigen::Vector3d m_origin = Eigen::Vector3d::Zero();
    Eigen::Matrix3d m_rotation = Eigen::Matrix3d::Identity();
    bool m_identity = true;
};
