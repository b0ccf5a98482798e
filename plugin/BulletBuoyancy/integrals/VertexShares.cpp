/// @file VertexShares.cpp
/// Per-vertex constants of the exact-mesh integrals (VertexShares.h; the formulas are in its file comment).

#include <BulletBuoyancy/integrals/VertexShares.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

VertexShares buildVertexShares(const TriangleMesh& mesh) {
    VertexShares s;
    const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
    for (std::size_t v = 0; v < nv; ++v)
        if (!mesh.vertices[v].allFinite())
            throw std::invalid_argument("buildVertexShares: vertex " + std::to_string(v) + " is not finite");
    for (auto* a : {&s.qx, &s.qy, &s.qz, &s.bx, &s.by, &s.bz, &s.tx, &s.ty, &s.tz, &s.area}) a->assign(nv, 0.0);
    for (auto& a : s.m) a.assign(nv, 0.0);
    for (auto& c : s.corner) c.resize(nt);
    for (auto* a : {&s.ax, &s.ay, &s.az, &s.absArea}) a->resize(nt);
    for (std::size_t v = 0; v < nv; ++v) {
        s.qx[v] = mesh.vertices[v].x();
        s.qy[v] = mesh.vertices[v].y();
        s.qz[v] = mesh.vertices[v].z();
    }
    for (std::size_t t = 0; t < nt; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] < 0 || std::size_t(tri[k]) >= nv)
                throw std::invalid_argument("buildVertexShares: triangle " + std::to_string(t) + " has vertex index " +
                                            std::to_string(tri[k]) + " out of range");
        const Eigen::Vector3d& q0 = mesh.vertices[std::size_t(tri[0])];
        const Eigen::Vector3d& q1 = mesh.vertices[std::size_t(tri[1])];
        const Eigen::Vector3d& q2 = mesh.vertices[std::size_t(tri[2])];
        const Eigen::Vector3d A = 0.5 * (q1 - q0).cross(q2 - q0);
        const Eigen::Vector3d sum = q0 + q1 + q2;
        s.ax[t] = A.x();
        s.ay[t] = A.y();
        s.az[t] = A.z();
        s.absArea[t] = A.norm();
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = std::size_t(tri[k]);
            s.corner[k][t] = tri[k];
            // Corner weight of the edge-midpoint rule: w = (q_v + q_0 + q_1 + q_2) / 12 (VertexShares.h).
            const Eigen::Vector3d w = (mesh.vertices[v] + sum) / 12.0;
            const Eigen::Vector3d wxA = w.cross(A);
            s.bx[v] += A.x() / 3.0;
            s.by[v] += A.y() / 3.0;
            s.bz[v] += A.z() / 3.0;
            s.tx[v] += wxA.x();
            s.ty[v] += wxA.y();
            s.tz[v] += wxA.z();
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) s.m[3 * i + j][v] += w[i] * A[j];
            s.area[v] += s.absArea[t] / 3.0;
        }
    }
    return s;
}

}  // namespace buoyancy
