#pragma once
/// @file UvTriangleOverlap.h
/// Which UV triangles overlap another one with positive area (design.md 1.2: overlapping UVs make two
/// surface pieces share texels). Used by the layout check and to verify generated charts.

#include <Eigen/Core>
#include <vector>

namespace buoyancy {

/// Flag every triangle whose UV triangle overlaps another one's with an area larger than
/// relTolerance × the smaller of the two UV areas. Triangles sharing an edge or a corner only touch.
/// Broad phase: a uniform grid over the UVs' bounding box, each triangle entered in the cells of its
/// bounding box (conservative); narrow phase: the exact area of the two triangles' intersection.
/// @param[in] uvs     3·#T corner UVs (corner k of triangle t at 3t + k)
/// @param[in] active  #T flags; inactive triangles (e.g. degenerate or non-finite) are ignored
/// @return #T flags, 1 where the triangle overlaps another
std::vector<char> findOverlappingUvTriangles(const std::vector<Eigen::Vector2d>& uvs, const std::vector<char>& active,
                                             double relTolerance = 1e-9);

}  // namespace buoyancy
