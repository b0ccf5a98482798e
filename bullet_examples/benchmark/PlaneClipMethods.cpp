#include "benchmark/PlaneClipMethods.h"

#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace buoyancy::bench {

namespace {

void queryHeights(const btWaterSurface& water, const double* x, const double* z, std::size_t n, double time, double* h,
                  btWaterQueryCache* cache) {
    if (cache)
        water.heightsCached(x, z, n, time, h, *cache);
    else
        water.heights(x, z, n, time, h);
}

Eigen::Vector3d toE(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

}  // namespace

WaterPlane tangentWaterPlane(const btWaterSurface& water, double x, double z, double time, double step,
                             btWaterQueryCache* cache) {
    const double xs[5] = {x, x + step, x - step, x, x};
    const double zs[5] = {z, z, z, z + step, z - step};
    double h[5];
    queryHeights(water, xs, zs, 5, time, h, cache);
    const double hx = (h[1] - h[2]) / (2 * step), hz = (h[3] - h[4]) / (2 * step);
    WaterPlane p;
    p.point = Eigen::Vector3d(x, h[0], z);
    p.normal = Eigen::Vector3d(-hx, 1.0, -hz).normalized();
    return p;
}

WaterPlane fittedWaterPlane(const btWaterSurface& water, double minX, double minZ, double maxX, double maxZ,
                            double time, btWaterQueryCache* cache) {
    const double cx = 0.5 * (minX + maxX), cz = 0.5 * (minZ + maxZ);
    const double xs[5] = {cx, minX, maxX, minX, maxX};
    const double zs[5] = {cz, minZ, minZ, maxZ, maxZ};
    double h[5];
    queryHeights(water, xs, zs, 5, time, h, cache);
    // Least squares over the stencil (centre, 4 corners at (±ex, ±ez)): the columns 1, x − c_x, z − c_z are
    // orthogonal, so a = mean, b = Σ (x − c_x) h / Σ (x − c_x)², c likewise.
    const double ex = 0.5 * (maxX - minX), ez = 0.5 * (maxZ - minZ);
    const double a = (h[0] + h[1] + h[2] + h[3] + h[4]) / 5.0;
    const double b = ex > 0 ? (-h[1] + h[2] - h[3] + h[4]) / (4.0 * ex) : 0.0;
    const double c = ez > 0 ? (-h[1] - h[2] + h[3] + h[4]) / (4.0 * ez) : 0.0;
    WaterPlane p;
    p.point = Eigen::Vector3d(cx, a, cz);
    p.normal = Eigen::Vector3d(-b, 1.0, -c).normalized();
    return p;
}

HydrostaticsResult planeClipHydrostatics(const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                         const WaterPlane& plane, double rho, double g, const Eigen::Vector3d& ref) {
    // The plane's frame: origin on the plane, its y' axis the plane's normal (the shortest rotation from y).
    Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
    frame.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), plane.normal).toRotationMatrix();
    frame.translation() = plane.point;
    const Eigen::Isometry3d toPlane = frame.inverse();
    static const btFlatWaterSurface kPlaneWater(0.0);  // y' = 0
    const HydrostaticsResult local =
        clippedHydrostatics(mesh, toPlane * pose, kPlaneWater, 0.0, rho, g, toPlane * ref);
    HydrostaticsResult r;
    r.submerged_volume = local.submerged_volume;
    r.centre_of_buoyancy = frame * local.centre_of_buoyancy;
    r.force = Eigen::Vector3d(0, rho * g * local.submerged_volume, 0);
    r.torque = local.submerged_volume > 0 ? Eigen::Vector3d((r.centre_of_buoyancy - ref).cross(r.force))
                                          : Eigen::Vector3d::Zero();
    r.waterline_area = local.waterline_area;
    r.wetted_area = local.wetted_area;
    return r;
}

const char* planeMethodName(PlaneMethod method) {
    return method == PlaneMethod::Tangent ? "tangent-plane" : "fitted-plane";
}

HydrostaticsResult planeMethodHydrostatics(PlaneMethod method, const TriangleMesh& mesh,
                                           const Eigen::AlignedBox3d& localBounds, const Eigen::Isometry3d& pose,
                                           const btWaterSurface& water, double time, double rho, double g,
                                           const Eigen::Vector3d& com, btWaterQueryCache* cache) {
    WaterPlane plane;
    if (method == PlaneMethod::Tangent) {
        plane = tangentWaterPlane(water, com.x(), com.z(), time, kTangentPlaneStep, cache);
    } else {
        double minX = 1e300, minZ = 1e300, maxX = -1e300, maxZ = -1e300;
        for (int k = 0; k < 8; ++k) {
            const Eigen::Vector3d c = pose * localBounds.corner(Eigen::AlignedBox3d::CornerType(k));
            minX = std::min(minX, c.x());
            maxX = std::max(maxX, c.x());
            minZ = std::min(minZ, c.z());
            maxZ = std::max(maxZ, c.z());
        }
        plane = fittedWaterPlane(water, minX, minZ, maxX, maxZ, time, cache);
    }
    return planeClipHydrostatics(mesh, pose, plane, rho, g, com);
}

PlaneMethodAction::PlaneMethodAction(btRigidBody* body, PlaneMethod method, const TriangleMesh* mesh,
                                     const btWaterSurface* water, btBuoyancyWorld* clock,
                                     const Eigen::Isometry3d& meshInCom, btActionInterface* drag, double rho, double g)
    : m_body(body), m_method(method), m_mesh(mesh), m_water(water), m_clock(clock), m_meshInCom(meshInCom),
      m_drag(drag), m_rho(rho), m_g(g) {
    if (!body || !mesh || mesh->vertices.empty() || !water || !clock)
        throw std::invalid_argument("PlaneMethodAction: bad arguments");
    for (const auto& v : mesh->vertices) m_bounds.extend(v);
}

void PlaneMethodAction::updateAction(btCollisionWorld* world, btScalar dtStep) {
    const double dt = double(dtStep);
    m_clock->beginSubstepIfNew(m_lastSubstep, dt, world);
    const double time = m_clock->getTime();
    const btTransform& tr = m_body->getWorldTransform();
    Eigen::Isometry3d com = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) com.linear()(i, j) = double(tr.getBasis()[i][j]);
    com.translation() = toE(tr.getOrigin());
    m_last = planeMethodHydrostatics(m_method, *m_mesh, m_bounds, com * m_meshInCom, *m_water, time, m_rho, m_g,
                                     com.translation(), &m_cache);
    if (m_drag) m_drag->updateAction(world, dtStep);
    const Eigen::Vector3d J = m_last.force * dt, L = m_last.torque * dt;
    m_body->applyCentralImpulse(btVector3(btScalar(J.x()), btScalar(J.y()), btScalar(J.z())));
    m_body->applyTorqueImpulse(btVector3(btScalar(L.x()), btScalar(L.y()), btScalar(L.z())));
}

}  // namespace buoyancy::bench
