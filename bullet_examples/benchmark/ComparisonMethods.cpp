#include "benchmark/ComparisonMethods.h"

#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace buoyancy::bench {

namespace {

constexpr double kDragCoefficient = 1.0;  // btBuoyancySettings::dragCoefficient default
constexpr double kLinearDamping = 0.3;    // a constant linear damping for the comparison methods, m/s

Eigen::Vector3d toE(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

/// Submerged volume of a sphere of radius r whose centre is `depth` below the surface (cap formula,
/// design.md 5).
inline double sphereSubmerged(double r, double depth) {
    const double h = std::min(2 * r, std::max(0.0, depth + r));
    return M_PI * h * h * (3 * r - h) / 3.0;
}

/// Generalised winding number of a closed mesh at p (Van Oosterom & Strackee solid angles / 4π).
double windingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
    double sum = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Eigen::Vector3d a = mesh.corner(t, 0) - p, b = mesh.corner(t, 1) - p, c = mesh.corner(t, 2) - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double num = a.dot(b.cross(c));
        const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        sum += 2.0 * std::atan2(num, den);
    }
    return sum / (4 * M_PI);
}

void bounds(const TriangleMesh& mesh, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
    lo = hi = mesh.vertices.front();
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
}

void pushProbe(ProbeSet& s, const Eigen::Vector3d& c, double share) {
    s.x.push_back(c.x());
    s.y.push_back(c.y());
    s.z.push_back(c.z());
    s.share.push_back(share);
    s.radius.push_back(std::cbrt(3.0 * share / (4.0 * M_PI)));
}


/// Sum of vertical point forces f_i at points c_i (the comparison methods push straight up): total force,
/// torque about `ref`, the volume ρ g V = Σ f and its centre Σ f c / Σ f.
struct VerticalForceSum {
    double fy = 0;
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();
    void add(double f, const Eigen::Vector3d& c, const Eigen::Vector3d& ref) {
        fy += f;
        moment += f * c;
        torque += (c - ref).cross(Eigen::Vector3d(0, f, 0));
    }
    ComparisonResult result(double rho, double g) const {
        ComparisonResult r;
        r.force = Eigen::Vector3d(0, fy, 0);
        r.torque = torque;
        r.volume = fy / (rho * g);
        r.centre = fy > 0 ? Eigen::Vector3d(moment / fy) : Eigen::Vector3d::Zero();
        return r;
    }
};

}  // namespace

void ComparisonWorkspace::resize(std::size_t n) {
    for (auto* v : {&wx, &wy, &wz, &h, &ax, &ay, &az, &ux, &uy, &uz}) v->resize(n);
}

ProbeSet makeHullProbes(const TriangleMesh& mesh, int target, double volume) {
    if (target < 1) throw std::invalid_argument("hull probes: target count must be >= 1");
    Eigen::Vector3d lo, hi;
    bounds(mesh, lo, hi);
    const Eigen::Vector3d ext = (hi - lo).cwiseMax(1e-9);
    struct Cluster {
        double area = 0;
        Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    };
    std::map<std::tuple<int, int, int>, Cluster> best;
    double cell = ext.maxCoeff() / std::cbrt(double(target));
    const double minCell = 1e-4 * ext.maxCoeff();  // a mesh with fewer triangles than `target` stops here
    for (int iter = 0; iter < 40 && cell >= minCell; ++iter) {
        std::map<std::tuple<int, int, int>, Cluster> cl;
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const Eigen::Vector3d a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
            const Eigen::Vector3d ctr = (a + b + c) / 3.0;
            const double area = 0.5 * (b - a).cross(c - a).norm();
            const Eigen::Vector3d q = (ctr - lo) / cell;
            Cluster& k = cl[{int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z()))}];
            k.area += area;
            k.moment += area * ctr;
        }
        const double n = double(cl.size());
        if (best.empty() || std::abs(n - target) < std::abs(double(best.size()) - target)) best = std::move(cl);
        if (std::abs(n - target) <= 0.25 * target) break;
        cell *= std::pow(n / target, 0.5);  // surface clusters scale like cell⁻²
    }
    double total = 0;
    for (const auto& kv : best) total += kv.second.area;
    ProbeSet s;
    for (const auto& kv : best)
        if (kv.second.area > 0) pushProbe(s, kv.second.moment / kv.second.area, volume * kv.second.area / total);
    s.variant = "hull-" + std::to_string(target);
    return s;
}

ProbeSet makeGridProbes(const TriangleMesh& mesh, int target, double volume) {
    if (target < 1) throw std::invalid_argument("grid probes: target count must be >= 1");
    Eigen::Vector3d lo, hi;
    bounds(mesh, lo, hi);
    double cell = std::cbrt(volume / target);
    std::vector<Eigen::Vector3d> inside;
    for (int iter = 0; iter < 12; ++iter) {
        inside.clear();
        const Eigen::Vector3i n = ((hi - lo) / cell).array().ceil().cast<int>().cwiseMax(1);
        const Eigen::Vector3d origin = 0.5 * (lo + hi) - 0.5 * cell * n.cast<double>();
        for (int i = 0; i < n.x(); ++i)
            for (int j = 0; j < n.y(); ++j)
                for (int k = 0; k < n.z(); ++k) {
                    const Eigen::Vector3d p = origin + cell * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
                    if (windingNumber(mesh, p) > 0.5) inside.push_back(p);
                }
        const double m = double(inside.size());
        if (m > 0 && std::abs(m - target) <= 0.25 * target) break;
        cell *= m > 0 ? std::cbrt(m / target) : 0.5;
    }
    if (inside.empty()) throw std::runtime_error("grid probes: no grid cell centre lies inside the mesh");
    ProbeSet s;
    for (const auto& p : inside) pushProbe(s, p, volume / double(inside.size()));
    s.variant = "grid-" + std::to_string(target);
    return s;
}

FaceSet makeFaceSet(const TriangleMesh& mesh) {
    FaceSet f;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Eigen::Vector3d a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
        const Eigen::Vector3d ctr = (a + b + c) / 3.0, A = 0.5 * (b - a).cross(c - a);
        f.cx.push_back(ctr.x());
        f.cy.push_back(ctr.y());
        f.cz.push_back(ctr.z());
        f.ax.push_back(A.x());
        f.ay.push_back(A.y());
        f.az.push_back(A.z());
    }
    return f;
}

ComparisonResult probeHydrostatics(const ProbeSet& p, const Eigen::Isometry3d& pose, const btWaterSurface& water,
                                   double time, double rho, double g, const Eigen::Vector3d& ref, ComparisonWorkspace& ws) {
    const std::size_t n = p.size();
    if (ws.wx.size() != n) ws.resize(n);
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d T = pose.translation();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d w = R * Eigen::Vector3d(p.x[i], p.y[i], p.z[i]) + T;
        ws.wx[i] = w.x();
        ws.wy[i] = w.y();
        ws.wz[i] = w.z();
    }
    water.heights(ws.wx.data(), ws.wz.data(), n, time, ws.h.data());
    VerticalForceSum sum;
    for (std::size_t i = 0; i < n; ++i) {
        const double v = sphereSubmerged(p.radius[i], ws.h[i] - ws.wy[i]);
        if (v <= 0) continue;
        const double f = rho * g * v;
        sum.add(f, Eigen::Vector3d(ws.wx[i], ws.wy[i], ws.wz[i]), ref);
    }
    return sum.result(rho, g);
}

ComparisonResult downwardFaceHydrostatics(const FaceSet& fs, const Eigen::Isometry3d& pose, const btWaterSurface& water,
                                          double time, double rho, double g, const Eigen::Vector3d& ref,
                                          ComparisonWorkspace& ws) {
    const std::size_t n = fs.size();
    if (ws.wx.size() != n) ws.resize(n);
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d T = pose.translation();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d w = R * Eigen::Vector3d(fs.cx[i], fs.cy[i], fs.cz[i]) + T;
        const Eigen::Vector3d a = R * Eigen::Vector3d(fs.ax[i], fs.ay[i], fs.az[i]);
        ws.wx[i] = w.x();
        ws.wy[i] = w.y();
        ws.wz[i] = w.z();
        ws.ax[i] = a.x();
        ws.ay[i] = a.y();
        ws.az[i] = a.z();
    }
    water.heights(ws.wx.data(), ws.wz.data(), n, time, ws.h.data());
    VerticalForceSum sum;
    for (std::size_t i = 0; i < n; ++i) {
        const double depth = ws.h[i] - ws.wy[i];
        if (!(depth > 0) || !(ws.ay[i] < 0)) continue;
        const double f = rho * g * depth * (-ws.ay[i]);
        sum.add(f, Eigen::Vector3d(ws.wx[i], ws.wy[i], ws.wz[i]), ref);
    }
    return sum.result(rho, g);
}

ComparisonAction::ComparisonAction(btRigidBody* body, const ProbeSet* probes, const FaceSet* faces,
                                   const btWaterSurface* water, const Eigen::Isometry3d& meshInCom, double rho, double g,
                                   btBuoyancyWorld* clock, bool drag)
    : m_body(body), m_probes(probes), m_faces(faces), m_water(water), m_meshInCom(meshInCom), m_rho(rho), m_g(g),
      m_clock(clock), m_drag(drag) {
    if (!body || !water || (!probes == !faces)) throw std::invalid_argument("ComparisonAction: bad arguments");
    m_ws.resize(probes ? probes->size() : faces->size());
}

void ComparisonAction::updateAction(btCollisionWorld* world, btScalar dtStep) {
    const double dt = double(dtStep);
    if (m_clock) {
        m_clock->beginSubstepIfNew(m_lastSubstep, dt, world);
        m_time = m_clock->getTime();
    } else {
        m_time += dt;
    }
    const btTransform& tr = m_body->getWorldTransform();
    Eigen::Isometry3d com = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) com.linear()(i, j) = double(tr.getBasis()[i][j]);
    com.translation() = toE(tr.getOrigin());
    const Eigen::Isometry3d pose = com * m_meshInCom;
    const Eigen::Vector3d c = com.translation();
    m_last = m_probes ? probeHydrostatics(*m_probes, pose, *m_water, m_time, m_rho, m_g, c, m_ws)
                      : downwardFaceHydrostatics(*m_faces, pose, *m_water, m_time, m_rho, m_g, c, m_ws);
    if (!m_drag) {
        const Eigen::Vector3d J = m_last.force * dt, L = m_last.torque * dt;
        m_body->applyCentralImpulse(btVector3(btScalar(J.x()), btScalar(J.y()), btScalar(J.z())));
        m_body->applyTorqueImpulse(btVector3(btScalar(L.x()), btScalar(L.y()), btScalar(L.z())));
        return;
    }
    // Drag (design.md 2.6) on the wetted elements.
    const std::size_t n = m_ws.wx.size();
    m_water->velocities(m_ws.wx.data(), m_ws.wy.data(), m_ws.wz.data(), n, m_time, m_ws.ux.data(), m_ws.uy.data(),
                        m_ws.uz.data());
    const Eigen::Vector3d v = toE(m_body->getLinearVelocity()), w = toE(m_body->getAngularVelocity());
    const double kd = 0.5 * m_rho * kDragCoefficient, kl = m_rho * kLinearDamping;
    Eigen::Vector3d F = Eigen::Vector3d::Zero(), T = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        const double depth = m_ws.h[i] - m_ws.wy[i];
        double wet;
        double area;
        if (m_probes) {
            const double r = m_probes->radius[i];
            wet = sphereSubmerged(r, depth) / m_probes->share[i];
            area = M_PI * r * r;
        } else {
            wet = depth > 0 ? 1.0 : 0.0;
            area = 0;
        }
        if (!(wet > 0)) continue;
        const Eigen::Vector3d r(m_ws.wx[i] - c.x(), m_ws.wy[i] - c.y(), m_ws.wz[i] - c.z());
        const Eigen::Vector3d vi = v + w.cross(r) - Eigen::Vector3d(m_ws.ux[i], m_ws.uy[i], m_ws.uz[i]);
        Eigen::Vector3d f;
        if (m_probes) {
            f = -(kd * wet * area * vi.norm() + kl * wet * area) * vi;
        } else {
            const Eigen::Vector3d A(m_ws.ax[i], m_ws.ay[i], m_ws.az[i]);
            const double av = A.dot(vi), an = A.norm();
            f = Eigen::Vector3d::Zero();
            if (av > 0) f -= kd * av * vi;
            if (an > 0) f -= (kl * av / an) * A;
        }
        F += f;
        T += r.cross(f);
    }
    const Eigen::Vector3d J = (m_last.force + F) * dt, L = (m_last.torque + T) * dt;
    m_body->applyCentralImpulse(btVector3(btScalar(J.x()), btScalar(J.y()), btScalar(J.z())));
    m_body->applyTorqueImpulse(btVector3(btScalar(L.x()), btScalar(L.y()), btScalar(L.z())));
}

}  // namespace buoyancy::bench
