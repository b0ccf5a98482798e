#include "render/RenderFrame.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace buoyancy::render {

namespace {
constexpr float kDegToRad = 3.14159265358979f / 180.f;
}

Eigen::Vector3f RenderCamera::eye() const {
    const float yaw = yawDeg * kDegToRad, pitch = pitchDeg * kDegToRad;
    const Eigen::Vector3f dir(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    return target + distance * dir;
}

Eigen::Matrix4f RenderCamera::view() const {
    // Classic look-at (right-handed, camera looks down −z in eye space).
    const Eigen::Vector3f e = eye();
    const Eigen::Vector3f f = (target - e).normalized();
    Eigen::Vector3f up = Eigen::Vector3f::UnitY();
    if (std::abs(f.dot(up)) > 0.999f) up = Eigen::Vector3f::UnitZ();
    const Eigen::Vector3f s = f.cross(up).normalized();
    const Eigen::Vector3f u = s.cross(f);
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.block<1, 3>(0, 0) = s.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -s.dot(e);
    m(1, 3) = -u.dot(e);
    m(2, 3) = f.dot(e);
    return m;
}

Eigen::Matrix4f RenderCamera::projection(float aspect) const {
    // OpenGL perspective matrix (gluPerspective).
    const float n = std::max(0.01f, distance * 0.01f), f = std::max(200.f, distance * 50.f);
    const float t = 1.f / std::tan(0.5f * fovDeg * kDegToRad);
    Eigen::Matrix4f p = Eigen::Matrix4f::Zero();
    p(0, 0) = t / std::max(aspect, 1e-3f);
    p(1, 1) = t;
    p(2, 2) = (f + n) / (n - f);
    p(2, 3) = 2.f * f * n / (n - f);
    p(3, 2) = -1.f;
    return p;
}

}  // namespace buoyancy::render
