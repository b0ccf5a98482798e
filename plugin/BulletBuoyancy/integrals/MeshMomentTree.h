#pragma once
/// @file MeshMomentTree.h
/// Tiles with precomputed moments for the exact-mesh method (design.md 2.5): a bounding-sphere hierarchy over
/// the triangles of a mesh whose every node stores the exact surface moments of its triangles in the body
/// frame. Under a rigid pose the hydrostatic integrands (y − f) n, (y − f) p × n, … are polynomials of degree
/// ≤ 2 in the body-frame position when the water height f is at most quadratic over the node, so a node that is
/// entirely under water contributes a closed-form term (exact in flat water), a node entirely above contributes
/// nothing, and only the leaves that straddle the waterline are clipped triangle by triangle. The work per
/// substep grows with the waterline length, not with the triangle count.

#include <BulletBuoyancy/integrals/VertexShares.h>
#include <BulletBuoyancy/mesh/MeshEdges.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Geometry>
#include <vector>

namespace buoyancy {

/// One node of the tree. Moments are about the node's centre c (the centre of its oriented bounding box) (s = q − c, q body frame, m):
/// m0 = ∫ n dA, m1(i, k) = ∫ s_i n_k dA, m2[ij][k] = ∫ s_i s_j n_k dA (ij = xx, xy, xz, yy, yz, zz), where
/// n dA is the outward area element. All exact (the triangles are flat: n is constant over each).
struct MeshMomentNode {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(); ///< node centre (of its oriented box), body frame, m
    double radius = 0;                               ///< radius of the sphere about `centre` holding the node, m
    /// Oriented bounding box about `centre`: unit axes (columns, body frame) from the principal axes of the node's
    /// vertices, and the half extent along each, m. Its extent along any direction u is Σ_k |u·axis_k| half_k.
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    Eigen::Vector3d half = Eigen::Vector3d::Zero();  ///< OBB half extents, m
    Eigen::Vector3d m0 = Eigen::Vector3d::Zero();    ///< ∫ n dA, m²
    Eigen::Matrix3d m1 = Eigen::Matrix3d::Zero();    ///< ∫ s nᵀ dA, m³
    double m2[6][3] = {};                            ///< ∫ s_i s_j n_k dA, m⁴
    double area = 0;                                 ///< Σ triangle areas, m²
    int first = 0;                                   ///< first triangle (in MeshMomentTree::triangles)
    int count = 0;                                   ///< triangle count under the node
    int left = -1;                                   ///< first child index (always this index + 1), −1 for a leaf
    int right = -1;                                  ///< second child index, −1 for a leaf
};

/// The part of a node the traversal reads at every visit, packed into 64 bytes (one cache line): the oriented box in
/// single precision, rounded outward (half extents grown by the rounding of the centre and axes), and the links.
/// The box's third axis is axis0 × axis1 (not stored).
struct alignas(64) MeshMomentBounds {
    float centre[3];  ///< box centre, body frame, m
    float half[3];    ///< half extents along axis0, axis1, axis0 × axis1, m (≥ the double-precision box's)
    float axes[6];    ///< axes[3k + i]: component i of axis k = 0, 1 (unit), body frame
    float radius;     ///< bounding-sphere radius about the centre, m
    int right;        ///< second child (the first is this index + 1); −1 for a leaf
    int first;        ///< leaf: first triangle (in MeshMomentTree::triangles / corners)
    int count;        ///< triangles under the node
};
static_assert(sizeof(MeshMomentBounds) == 64, "one cache line per node visit");

/// The hierarchy of one mesh (immutable once built; shared by every body using the mesh).
struct MeshMomentTree {
    std::vector<MeshMomentNode> nodes;          ///< nodes[0] is the root (empty tree: no triangles); depth-first order
    std::vector<MeshMomentBounds> bounds;       ///< per node, what the traversal reads (same indices as nodes)
    std::vector<Eigen::Vector3i> triangles;     ///< the mesh's triangles in leaf order (vertex indices)
    /// The triangles' corners in leaf order (corners[3k + c] = corner c of triangles[k]), body frame, m: the leaves
    /// read them contiguously instead of through the vertex indices.
    std::vector<Eigen::Vector3d> corners;
    int depth = 0;                              ///< longest root-to-leaf path (nodes)
    double medianLeafRadius = 0;                ///< median bounding-sphere radius of the leaves, m
    /// The mesh's per-vertex shares (VertexShares.h): the evaluation on waves whose curvature makes the typical leaf
    /// too large for the closed form (TreeHydrostatics.cpp), and without a patch.
    VertexShares shares;
    /// The mesh's edges (MeshEdges.h): the evaluation on curved water samples the water at their midpoints.
    MeshEdges edges;
};

/// Build the tree over `mesh`: median split of the triangle centroids along the longest axis of their bounding
/// box, leaves of at most `leafSize` triangles (≥ 1; 4 by default: fewer triangles clipped per straddling leaf, more nodes visited). O(T log T), once per shape.
/// @throws std::invalid_argument for leafSize < 1 or a vertex index out of range
MeshMomentTree buildMeshMomentTree(const TriangleMesh& mesh, int leafSize = 4);

}  // namespace buoyancy
