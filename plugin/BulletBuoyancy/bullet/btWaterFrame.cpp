#include <BulletBuoyancy/bullet/btWaterFrame.h>

#include <BulletBuoyancy/bullet/btBulletConvert.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace {
/// Largest angle between up and the first horizontal axis's normal plane still taken as perpendicular, rad.
constexpr double kPerpendicularTolerance = 1e-6;

/// v / |v| with the components that are exactly zero kept zero and a lone non-zero one exactly ±1 (so the default
/// frame of a world with gravity (0, −g, 0) is exactly the identity).
Eigen::Vector3d unit(const Eigen::Vector3d& v) {
    Eigen::Vector3d u = v / v.norm();
    for (int i = 0; i < 3; ++i)
        if (v[(i + 1) % 3] == 0 && v[(i + 2) % 3] == 0) u[i] = v[i] > 0 ? 1.0 : -1.0;
    return u;
}

std::string numberText(double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

void requireDirection(const Eigen::Vector3d& v, const char* name) {
    if (!v.allFinite() || !(v.norm() > 0))
        throw std::invalid_argument(std::string("btWaterFrame: ") + name + " " + btWaterFrame::vectorText(v) +
                                    ": must be a finite, non-zero vector");
}
}  // namespace

btWaterFrame::btWaterFrame(const btVector3& origin, const btVector3& up, const btVector3& xAxis)
    : btWaterFrame(buoyancy::toEigen(origin), buoyancy::toEigen(up), buoyancy::toEigen(xAxis)) {}

btWaterFrame::btWaterFrame(const Eigen::Vector3d& origin, const Eigen::Vector3d& up, const Eigen::Vector3d& xAxis) {
    if (!origin.allFinite())
        throw std::invalid_argument("btWaterFrame: origin " + vectorText(origin) + ": must be finite");
    requireDirection(up, "up");
    requireDirection(xAxis, "x axis");
    const Eigen::Vector3d u = unit(up), x0 = unit(xAxis);
    // Angle between x and the horizontal plane, from the component along up (accurate at small angles).
    const double off = std::atan2(std::abs(x0.dot(u)), x0.cross(u).norm());
    if (off > kPerpendicularTolerance)
        throw std::invalid_argument("btWaterFrame: x axis " + vectorText(xAxis) + " is not perpendicular to up " +
                                    vectorText(up) + " (" + numberText(off) + " rad off; 1e-6 allowed)");
    // Remove the tolerated residue so the frame is orthonormal to rounding.
    Eigen::Vector3d x = x0 - x0.dot(u) * u;
    x = x0.dot(u) == 0 ? x0 : unit(x);
    m_rotation.col(0) = x;
    m_rotation.col(1) = u;
    m_rotation.col(2) = x.cross(u);
    m_origin = origin;
    m_identity = m_origin == Eigen::Vector3d::Zero() && m_rotation == Eigen::Matrix3d::Identity();
}

btWaterFrame btWaterFrame::fromUp(const Eigen::Vector3d& up, const Eigen::Vector3d& origin) {
    requireDirection(up, "up");
    const Eigen::Vector3d u = unit(up);
    // World +x projected onto the plane ⟂ up (exactly +x when up ⟂ x); near ±x, world +y projected instead.
    const Eigen::Vector3d ref = std::abs(u.x()) > 0.5 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    const double along = ref.dot(u);
    const Eigen::Vector3d x = along == 0 ? ref : unit(Eigen::Vector3d(ref - along * u));
    return btWaterFrame(origin, u, x);
}

btWaterFrame btWaterFrame::fromGravity(const Eigen::Vector3d& gravity, const Eigen::Vector3d& origin) {
    if (!gravity.allFinite() || !(gravity.norm() > 0))
        throw std::invalid_argument("btWaterFrame: gravity " + vectorText(gravity) +
                                    " m/s^2 has no direction: give the water frame explicitly");
    return fromUp(-gravity, origin);
}

Eigen::Isometry3d btWaterFrame::toWater(const Eigen::Isometry3d& pose) const {
    if (m_identity) return pose;
    Eigen::Isometry3d r = Eigen::Isometry3d::Identity();
    r.linear() = m_rotation.transpose() * pose.linear();
    r.translation() = m_rotation.transpose() * (pose.translation() - m_origin);
    return r;
}

btTransform btWaterFrame::getTransform() const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = m_rotation;
    t.translation() = m_origin;
    return buoyancy::toBullet(t);
}

double btWaterFrame::angleToGravity(const Eigen::Vector3d& gravity) const {
    const Eigen::Vector3d down = -up();
    return std::atan2(down.cross(gravity).norm(), down.dot(gravity));
}

std::string btWaterFrame::vectorText(const Eigen::Vector3d& v) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", v.x() + 0.0, v.y() + 0.0, v.z() + 0.0);  // no "-0"
    return buf;
}
