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

inline std::string data(const std::string& name) { return std::string(BUOYANCY_TEST_DATA_DIR) + "/meshes/" + name; }
inline std::string model(const std::string& rel) { return std::string(BUOYANCY_ASSIMP_MODELS_DIR) + "/" + rel; }

}  // namespace mesh_test
