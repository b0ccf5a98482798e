#pragma once
/// @file MeshTestUtil.h
/// Small independent helpers for the mesh tests (no library code): signed volume by a tetrahedra sum,
/// bounding boxes, and paths to test data.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Geometry>
#include <string>

namespace mesh_test {

/// Σ over triangles of the signed tetrahedron (origin, a, b, c) volume a·(b×c)/6 (divergence theorem).
inline double tetraVolume(const buoyancy::TriangleMesh& m) {
    double v = 0;
    for (const Eigen::Vector3i& t : m.triangles)
        v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
    return v;
}

/// Axis-aligned bounding box of the referenced vertices.
inline Eigen::AlignedBox3d bbox(const buoyancy::TriangleMesh& m) {
    Eigen::AlignedBox3d b;
    for (const Eigen::Vector3i& t : m.triangles)
        for (int k = 0; k < 3; ++k) b.extend(m.vertices[t[k]]);
    return b;
}

/// Append the unit cube [0,1]³ + offset to m: 8 corners numbered k = x + 2y + 4z, two outward triangles per face
/// (the corner numbering and quads of tests/data/meshes/generate.py).
inline void appendUnitCube(buoyancy::TriangleMesh& m, const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
    const int base = int(m.vertices.size());
    for (int k = 0; k < 8; ++k) m.vertices.push_back(offset + Eigen::Vector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1));
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.triangles.emplace_back(base + q[0], base + q[1], base + q[2]);
        m.triangles.emplace_back(base + q[0], base + q[2], base + q[3]);
    }
}

inline std::string data(const std::string& name) { return std::string(BUOYANCY_TEST_DATA_DIR) + "/meshes/" + name; }
inline std::string model(const std::string& rel) { return std::string(BUOYANCY_ASSIMP_MODELS_DIR) + "/" + rel; }

}  // namespace mesh_test
