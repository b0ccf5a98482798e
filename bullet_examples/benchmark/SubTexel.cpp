#include "benchmark/SubTexel.h"

#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>

namespace buoyancy::bench {

HydrostaticsResult subTexelHydrostatics(const SurfaceSamples& samples, const Eigen::Isometry3d& pose,
                                        const btWaterSurface& water, double time, double rho, double g,
                                        const Eigen::Vector3d& ref, SampleWorkspace& ws) {
    transformSamples(samples, pose, ws);
    const std::size_t n = samples.size();
    water.heights(ws.wx.data(), ws.wz.data(), n, time, ws.waterHeight.data());
    double V = 0, Ay = 0, area = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero(), dA = Eigen::Vector3d::Zero(), dpxA = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const double ax = ws.wax[i], ay = ws.way[i], az = ws.waz[i];
        const double an = std::sqrt(ax * ax + ay * ay + az * az);
        const double ny = an > 0 ? ay / an : 0.0;
        const double hv = 0.5 * std::sqrt(std::max(samples.area[i], 0.0)) * std::sqrt(std::max(0.0, 1.0 - ny * ny));
        const double f = ws.waterHeight[i];
        const double y = ws.wy[i];
        double w, yw, Lw;  // wet fraction, wet centroid height, wet strip length
        if (hv > 0) {
            const double bottom = y - hv, top = std::min(f, y + hv);
            Lw = std::max(0.0, top - bottom);
            w = Lw / (2.0 * hv);
            yw = bottom + 0.5 * Lw;
        } else {
            w = y < f ? 1.0 : 0.0;
            yw = y;
            Lw = 0;
        }
        if (!(w > 0)) continue;
        const double d = yw - f;  // ≤ 0 over the wet strip's centroid
        const Eigen::Vector3d p(ws.wx[i] - ref.x(), yw - ref.y(), ws.wz[i] - ref.z());
        const double fr = f - ref.y();
        const Eigen::Vector3d A(ax, ay, az);
        V += w * ay * d;
        first.x() += w * ay * d * p.x();
        // ∫ (y'² − f'²)/2 over the strip: mean of y'² is y_w'² + L_w²/12.
        first.y() += w * ay * 0.5 * (p.y() * p.y() + Lw * Lw / 12.0 - fr * fr);
        first.z() += w * ay * d * p.z();
        dA += (w * d) * A;
        dpxA += (w * d) * p.cross(A);
        Ay += w * ay;
        area += w * samples.area[i];
    }
    HydrostaticsResult r;
    r.submerged_volume = V;
    if (V != 0) r.centre_of_buoyancy = ref + first / V;
    r.force = rho * g * dA;
    r.torque = rho * g * dpxA;
    r.waterline_area = -Ay;
    r.wetted_area = area;
    return r;
}

SubTexelAction::SubTexelAction(btRigidBody* body, const SurfaceSamples* samples, const btWaterSurface* water,
                               const Eigen::Isometry3d& meshInCom, btActionInterface* drag, double rho, double g)
    : m_body(body), m_samples(samples), m_water(water), m_meshInCom(meshInCom), m_drag(drag), m_rho(rho), m_g(g) {}

void SubTexelAction::updateAction(btCollisionWorld* world, btScalar dtStep) {
    const double dt = double(dtStep);
    const btTransform& tr = m_body->getWorldTransform();
    Eigen::Isometry3d com = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) com.linear()(i, j) = double(tr.getBasis()[i][j]);
    com.translation() = Eigen::Vector3d(double(tr.getOrigin().x()), double(tr.getOrigin().y()), double(tr.getOrigin().z()));
    const HydrostaticsResult h =
        subTexelHydrostatics(*m_samples, com * m_meshInCom, *m_water, 0.0, m_rho, m_g, com.translation(), m_ws);
    if (m_drag) m_drag->updateAction(world, dtStep);
    const Eigen::Vector3d J = h.force * dt, L = h.torque * dt;
    m_body->applyCentralImpulse(btVector3(btScalar(J.x()), btScalar(J.y()), btScalar(J.z())));
    m_body->applyTorqueImpulse(btVector3(btScalar(L.x()), btScalar(L.y()), btScalar(L.z())));
}

}  // namespace buoyancy::bench
