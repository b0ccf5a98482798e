#pragma once
/// @file ComponentIntersections.h
/// Which closed components of a mesh cross each other (prepareMesh's "components intersect" warning).

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <utility>
#include <vector>

namespace buoyancy {

/// Pairs (i, j), i < j, of components with at least one proper triangle–triangle intersection (an edge of one
/// triangle crosses the interior of the other; touching and coplanar contact do not count), sorted.
/// One bounding-volume hierarchy over all triangles (median split, leaves of ≤ 4): each triangle is tested
/// only against triangles of other components whose boxes overlap its own, and a pair of components stops
/// being tested once it is known to intersect. Cost O(n log n + k) for n triangles and k overlapping boxes
/// of different components (the former per-pair hash grid put a large triangle into up to 16M cells
/// and took 26 s on a fuzzer input of 4096 triangles).
/// @param mesh  vertices and triangles (indices valid, coordinates finite)
/// @param triangleComponent  component index of each triangle, 0..components−1
std::vector<std::pair<int, int>> intersectingComponentPairs(const TriangleMesh& mesh,
                                                            const std::vector<int>& triangleComponent);

}  // namespace buoyancy
