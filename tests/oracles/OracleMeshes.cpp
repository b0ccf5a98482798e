#include "oracles/OracleMeshes.h"

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <cmath>

namespace buoyancy_test {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

OracleMesh oracleBox(double a, double b, double c) {
    OracleMesh m;
    for (int i = 0; i < 8; ++i)
        m.verts.emplace_back((i & 1 ? 0.5 : -0.5) * a, (i & 2 ? 0.5 : -0.5) * b, (i & 4 ? 0.5 : -0.5) * c);
    // Each face as a quad (corners CCW seen from outside) split into two triangles.
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.tris.emplace_back(q[0], q[1], q[2]);
        m.tris.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

OracleMesh oracleTetrahedron(double s) {
    OracleMesh m;
    m.verts = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(s, 0, 0), Eigen::Vector3d(0, s, 0), Eigen::Vector3d(0, 0, s)};
    m.tris = {Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 1, 3), Eigen::Vector3i(0, 3, 2), Eigen::Vector3i(1, 2, 3)};
    return m;
}

OracleMesh oracleSphere(double R, int seg, int rings) {
    OracleMesh m;
    // poles 0 (top) and 1 (bottom), then rings−1 latitude circles of seg vertices, top to bottom
    m.verts.emplace_back(0, R, 0);
    m.verts.emplace_back(0, -R, 0);
    for (int i = 1; i < rings; ++i) {
        const double th = kPi * i / rings;
        for (int j = 0; j < seg; ++j) {
            const double ph = 2 * kPi * j / seg;
            m.verts.emplace_back(R * std::sin(th) * std::cos(ph), R * std::cos(th), R * std::sin(th) * std::sin(ph));
        }
    }
    auto v = [&](int ring, int j) { return 2 + (ring - 1) * seg + ((j % seg) + seg) % seg; };
    for (int j = 0; j < seg; ++j) {
        // outward: with φ increasing from +x towards +z, CCW seen from outside at the top is (pole, j+1, j)
        m.tris.emplace_back(0, v(1, j + 1), v(1, j));
        m.tris.emplace_back(1, v(rings - 1, j), v(rings - 1, j + 1));
        for (int i = 1; i + 1 < rings; ++i) {
            m.tris.emplace_back(v(i, j), v(i, j + 1), v(i + 1, j + 1));
            m.tris.emplace_back(v(i, j), v(i + 1, j + 1), v(i + 1, j));
        }
    }
    return m;
}

OracleMesh oracleTorus(double R, double r, int segMajor, int segMinor) {
    OracleMesh m;
    for (int i = 0; i < segMajor; ++i) {
        const double u = 2 * kPi * i / segMajor;
        for (int j = 0; j < segMinor; ++j) {
            const double w = 2 * kPi * j / segMinor;
            const double rho = R + r * std::cos(w);
            m.verts.emplace_back(rho * std::cos(u), r * std::sin(w), rho * std::sin(u));
        }
    }
    auto v = [&](int i, int j) { return (i % segMajor) * segMinor + (j % segMinor); };
    for (int i = 0; i < segMajor; ++i)
        for (int j = 0; j < segMinor; ++j) {
            m.tris.emplace_back(v(i, j), v(i, j + 1), v(i + 1, j + 1));
            m.tris.emplace_back(v(i, j), v(i + 1, j + 1), v(i + 1, j));
        }
    return m;
}

OracleMesh oracleCylinder(double r, double h, int seg) {
    OracleMesh m;
    m.verts.emplace_back(0, 0.5 * h, 0);
    m.verts.emplace_back(0, -0.5 * h, 0);
    for (int j = 0; j < seg; ++j) {
        const double ph = 2 * kPi * j / seg;
        m.verts.emplace_back(r * std::cos(ph), 0.5 * h, r * std::sin(ph));
        m.verts.emplace_back(r * std::cos(ph), -0.5 * h, r * std::sin(ph));
    }
    auto top = [&](int j) { return 2 + 2 * (j % seg); };
    auto bot = [&](int j) { return 3 + 2 * (j % seg); };
    for (int j = 0; j < seg; ++j) {
        m.tris.emplace_back(0, top(j + 1), top(j));
        m.tris.emplace_back(1, bot(j), bot(j + 1));
        m.tris.emplace_back(top(j), top(j + 1), bot(j + 1));
        m.tris.emplace_back(top(j), bot(j + 1), bot(j));
    }
    return m;
}

buoyancy::TriangleMesh toTriangleMesh(const OracleMesh& m) {
    buoyancy::TriangleMesh t;
    t.vertices = m.verts;
    t.triangles = m.tris;
    return t;
}

}  // namespace buoyancy_test
