#pragma once
/// @file BakeTestMeshes.h
/// UV-mapped closed meshes built inside the tests (independent of plugin/mesh) and exact reference sums
/// over their triangles, for the bake and atlas tests.

#include <BulletBuoyancy/mesh/TriangleMesh.h>
#include "oracles/OracleMeshes.h"

#include <Eigen/Geometry>
#include <cmath>
#include <functional>

namespace bake_test {

constexpr double kPi = 3.14159265358979323846;

/// Box a×b×c from the oracle box, each face a UV chart: face f in cell (f mod 3, f div 3) of a 3×2 grid,
/// inset by `margin` (UV units) on every side.
inline buoyancy::TriangleMesh uvBox(double a, double b, double c, double margin = 0.04) {
    buoyancy::TriangleMesh m = buoyancy_test::toTriangleMesh(buoyancy_test::oracleBox(a, b, c));
    m.corner_uvs.resize(3 * m.triangles.size());
    for (int f = 0; f < 6; ++f) {
        const double x0 = (f % 3) / 3.0 + margin, x1 = (f % 3 + 1) / 3.0 - margin;
        const double y0 = (f / 3) / 2.0 + margin, y1 = (f / 3 + 1) / 2.0 - margin;
        const Eigen::Vector2d q[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
        // oracleBox: triangles (q0, q1, q2) and (q0, q2, q3) of quad f
        m.corner_uvs[6 * f + 0] = q[0];
        m.corner_uvs[6 * f + 1] = q[1];
        m.corner_uvs[6 * f + 2] = q[2];
        m.corner_uvs[6 * f + 3] = q[0];
        m.corner_uvs[6 * f + 4] = q[2];
        m.corner_uvs[6 * f + 5] = q[3];
    }
    return m;
}

/// A closed parametric surface P(s, t), s, t in [0,1], on a grid of nu × nv quads: s wraps around; rows
/// t = 0 and t = 1 collapse to one pole vertex each when `poles`, else t wraps as well. Per-corner UVs are
/// (s, t) mapped into [margin, 1 − margin]². Triangles are oriented away from inner(s, t).
inline buoyancy::TriangleMesh parametricMesh(int nu, int nv, bool poles,
                                             const std::function<Eigen::Vector3d(double, double)>& P,
                                             const std::function<Eigen::Vector3d(double, double)>& inner,
                                             double margin = 0.01) {
    buoyancy::TriangleMesh m;
    const int rows = poles ? nv + 1 : nv;  // distinct vertex rows
    std::vector<int> index(static_cast<std::size_t>(rows) * nu);
    for (int i = 0; i < rows; ++i) {
        const double t = static_cast<double>(i) / nv;
        if (poles && (i == 0 || i == nv)) {
            m.vertices.push_back(P(0, t));
            for (int j = 0; j < nu; ++j) index[i * nu + j] = static_cast<int>(m.vertices.size()) - 1;
            continue;
        }
        for (int j = 0; j < nu; ++j) {
            index[i * nu + j] = static_cast<int>(m.vertices.size());
            m.vertices.push_back(P(static_cast<double>(j) / nu, t));
        }
    }
    auto vid = [&](int i, int j) { return index[(i % rows) * nu + (j % nu)]; };
    auto uv = [&](int i, int j) {
        return Eigen::Vector2d(margin + (1 - 2 * margin) * j / nu, margin + (1 - 2 * margin) * i / nv);
    };
    auto addTri = [&](int i0, int j0, int i1, int j1, int i2, int j2) {
        Eigen::Vector3i t(vid(i0, j0), vid(i1, j1), vid(i2, j2));
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return;
        Eigen::Vector2d u0 = uv(i0, j0), u1 = uv(i1, j1), u2 = uv(i2, j2);
        const Eigen::Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
        const double sm = (j0 + j1 + j2) / (3.0 * nu), tm = (i0 + i1 + i2) / (3.0 * nv);
        if ((b - a).cross(c - a).dot((a + b + c) / 3 - inner(sm, tm)) < 0) {
            std::swap(t[1], t[2]);
            std::swap(u1, u2);
        }
        m.triangles.push_back(t);
        m.corner_uvs.push_back(u0);
        m.corner_uvs.push_back(u1);
        m.corner_uvs.push_back(u2);
    };
    for (int i = 0; i < nv; ++i)
        for (int j = 0; j < nu; ++j) {
            addTri(i, j, i, j + 1, i + 1, j + 1);
            addTri(i, j, i + 1, j + 1, i + 1, j);
        }
    return m;
}

/// UV sphere of radius R with its latitude/longitude parameterisation as UVs (one chart, seam at s = 0).
inline buoyancy::TriangleMesh uvSphere(double R, int nu, int nv) {
    return parametricMesh(
        nu, nv, true,
        [R](double s, double t) {
            const double th = kPi * t, ph = 2 * kPi * s;
            return Eigen::Vector3d(R * std::sin(th) * std::cos(ph), -R * std::cos(th), R * std::sin(th) * std::sin(ph));
        },
        [](double, double) { return Eigen::Vector3d::Zero(); });
}

/// Torus about y (tube centre radius Rm, tube radius r) with its angle parameterisation as UVs.
inline buoyancy::TriangleMesh uvTorus(double Rm, double r, int nu, int nv) {
    return parametricMesh(
        nu, nv, false,
        [Rm, r](double s, double t) {
            const double a = 2 * kPi * s, b = 2 * kPi * t;
            return Eigen::Vector3d((Rm + r * std::cos(b)) * std::cos(a), r * std::sin(b), (Rm + r * std::cos(b)) * std::sin(a));
        },
        [Rm](double s, double) { return Eigen::Vector3d(Rm * std::cos(2 * kPi * s), 0, Rm * std::sin(2 * kPi * s)); });
}

/// The same mesh with every UV mirrored (u → 1 − u): every UV triangle turns clockwise.
inline buoyancy::TriangleMesh mirroredUvs(buoyancy::TriangleMesh m) {
    for (Eigen::Vector2d& uv : m.corner_uvs) uv.x() = 1 - uv.x();
    return m;
}

/// Exact sums over the triangles (written here, independent of the library).
struct MeshSums {
    double area = 0;                                   ///< Σ |triangle|, m²
    double volume = 0;                                 ///< Σ signed tetrahedra (0, a, b, c), m³
    Eigen::Vector3d areaMoment = Eigen::Vector3d::Zero(); ///< ∫_S p dA = Σ |tri| centroid, m³
};

inline MeshSums meshSums(const buoyancy::TriangleMesh& m) {
    MeshSums s;
    for (const Eigen::Vector3i& t : m.triangles) {
        const Eigen::Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
        const double area = 0.5 * (b - a).cross(c - a).norm();
        s.area += area;
        s.volume += a.dot(b.cross(c)) / 6.0;
        s.areaMoment += area * (a + b + c) / 3.0;
    }
    return s;
}

}  // namespace bake_test
