#pragma once
/// @file btConvexHullMesh.h
/// The convex hull of a set of points as a closed, outward triangle mesh: what `--convex-hull` and the scene
/// key "convex_hull" replace a model by, and the mesh of a btConvexHullShape. Computed by Bullet's
/// btConvexHullComputer (exact integer arithmetic, so flat faces of many points do not break it).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Core>

#include <string>
#include <vector>

/// Convex hull of `points` (m). Its vertices are input points, in double precision (also in a single-precision
/// Bullet build); coplanar hull faces are split into triangles from one corner; triangles are outward.
/// @param points  at least 4 finite points, not all in one plane
/// @param what  names the input in error messages, e.g. the file name
/// @throws std::invalid_argument naming `what` for fewer than 4 points, a non-finite point, or points that are
///         flat or collinear (the hull encloses no volume)
buoyancy::TriangleMesh btConvexHullMesh(const std::vector<Eigen::Vector3d>& points, const std::string& what);
