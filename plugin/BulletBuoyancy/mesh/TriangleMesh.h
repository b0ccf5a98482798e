#pragma once
/// @file TriangleMesh.h
/// The in-memory surface every stage of the pipeline works on: a welded, indexed triangle mesh in
/// double precision, with optional per-corner texture coordinates (UVs).

#include <Eigen/Core>
#include <string>
#include <vector>

namespace buoyancy {

/// A closed triangle mesh in the body (mesh) frame, metres. Triangles are counter-clockwise seen from
/// outside (outward normal = (b − a) × (c − a)). UVs are per corner because a welded vertex can sit on a
/// UV seam and carry several texture coordinates.
struct TriangleMesh {
    std::vector<Eigen::Vector3d> vertices;  ///< #V positions, m (body frame)
    std::vector<Eigen::Vector3i> triangles; ///< #T vertex-index triples, outward CCW
    /// 3·#T texture coordinates (corner k of triangle t at 3t+k), or empty when the mesh has none.
    std::vector<Eigen::Vector2d> corner_uvs;

    /// Number of triangles.
    std::size_t triangleCount() const { return triangles.size(); }
    /// True when every triangle has UVs.
    bool hasUvs() const { return !triangles.empty() && corner_uvs.size() == 3 * triangles.size(); }
    /// Corner position k (0..2) of triangle t, m.
    const Eigen::Vector3d& corner(std::size_t t, int k) const { return vertices[triangles[t][k]]; }
};

/// A problem found while loading or checking a mesh that did not stop it from being used.
struct MeshWarning {
    std::string message; ///< human-readable, e.g. "2 components intersect each other"
};

}  // namespace buoyancy
