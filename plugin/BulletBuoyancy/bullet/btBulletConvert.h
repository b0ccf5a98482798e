#pragma once
/// @file btBulletConvert.h
/// Conversions between Bullet's btScalar types (float or double) and our double-precision Eigen types.

#include <LinearMath/btTransform.h>

#include <Eigen/Geometry>

namespace buoyancy {

/// btVector3 → Eigen (double).
inline Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(double(v.x()), double(v.y()), double(v.z())); }

/// Eigen → btVector3 (rounded to btScalar).
inline btVector3 toBullet(const Eigen::Vector3d& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }

/// btTransform → rigid Eigen transform (double).
inline Eigen::Isometry3d toEigen(const btTransform& t) {
    Eigen::Isometry3d r = Eigen::Isometry3d::Identity();
    const btMatrix3x3& b = t.getBasis();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.linear()(i, j) = double(b[i][j]);
    r.translation() = toEigen(t.getOrigin());
    return r;
}

/// Rigid Eigen transform → btTransform.
inline btTransform toBullet(const Eigen::Isometry3d& t) {
    const Eigen::Matrix3d& m = t.linear();
    btMatrix3x3 b(btScalar(m(0, 0)), btScalar(m(0, 1)), btScalar(m(0, 2)), btScalar(m(1, 0)), btScalar(m(1, 1)),
                  btScalar(m(1, 2)), btScalar(m(2, 0)), btScalar(m(2, 1)), btScalar(m(2, 2)));
    return btTransform(b, toBullet(Eigen::Vector3d(t.translation())));
}

}  // namespace buoyancy
