/// @file MeshMomentTree.cpp
/// Build of the moment hierarchy (declared in MeshMomentTree.h).

#include <BulletBuoyancy/integrals/MeshMomentTree.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

/// Index of (i, j), i ≤ j, in the packed symmetric order xx, xy, xz, yy, yz, zz.
constexpr int kSym[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};

/// Add the exact moments of the flat triangle (a, b, c) about `centre` to `node`.
/// ∫_T s dA = area · (a + b + c)/3 and ∫_T s sᵀ dA = area/12 · (a aᵀ + b bᵀ + c cᵀ + S Sᵀ), S = a + b + c
/// (exact for a flat triangle; e.g. Eberly, "Polyhedral Mass Properties", 2002), each times the constant n.
void addTriangleMoments(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0, const Eigen::Vector3d& c0,
                        MeshMomentNode& node) {
    const Eigen::Vector3d a = a0 - node.centre, b = b0 - node.centre, c = c0 - node.centre;
    const Eigen::Vector3d A = 0.5 * (b - a).cross(c - a);  // area vector (outward)
    const double area = A.norm();
    node.area += area;
    node.m0 += A;
    if (area == 0) return;
    const Eigen::Vector3d S = a + b + c;
    const Eigen::Vector3d n = A / area;
    node.m1 += (area / 3.0) * S * n.transpose();
    const Eigen::Matrix3d second = (area / 12.0) * (a * a.transpose() + b * b.transpose() + c * c.transpose() + S * S.transpose());
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j)
            for (int k = 0; k < 3; ++k) node.m2[kSym[i][j]][k] += second(i, j) * n[k];
}

struct Builder {
    const TriangleMesh& mesh;
    int leafSize;
    std::vector<Eigen::Vector3d> centroid;
    std::vector<int> order;
    MeshMomentTree tree;

    /// Corner v of the k-th triangle in the current order.
    const Eigen::Vector3d& corner(int k, int v) const {
        return mesh.vertices[std::size_t(mesh.triangles[std::size_t(order[std::size_t(k)])][v])];
    }

    /// Build the node over order[first, first + count) and return its index.
    int build(int first, int count, int level) {
        tree.depth = std::max(tree.depth, level);
        const int index = int(tree.nodes.size());
        tree.nodes.emplace_back();
        // Bounding box of the centroids: the split axis.
        Eigen::Vector3d clo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), chi = -clo;
        for (int k = first; k < first + count; ++k) {
            clo = clo.cwiseMin(centroid[std::size_t(order[std::size_t(k)])]);
            chi = chi.cwiseMax(centroid[std::size_t(order[std::size_t(k)])]);
        }
        MeshMomentNode node;
        // Oriented box: principal axes of the corners (covariance eigenvectors), centred on the extents along them.
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (int k = first; k < first + count; ++k)
            for (int v = 0; v < 3; ++v) mean += corner(k, v);
        mean /= double(3 * count);
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (int k = first; k < first + count; ++k)
            for (int v = 0; v < 3; ++v) cov += (corner(k, v) - mean) * (corner(k, v) - mean).transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
        node.axes = eig.info() == Eigen::Success && eig.eigenvectors().allFinite() ? eig.eigenvectors()
                                                                                     : Eigen::Matrix3d::Identity();
        node.axes.col(2) = node.axes.col(0).cross(node.axes.col(1));  // right-handed: axis2 = axis0 × axis1
        Eigen::Vector3d olo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), ohi = -olo;
        for (int k = first; k < first + count; ++k)
            for (int v = 0; v < 3; ++v) {
                const Eigen::Vector3d a = node.axes.transpose() * corner(k, v);
                olo = olo.cwiseMin(a);
                ohi = ohi.cwiseMax(a);
            }
        node.centre = node.axes * (0.5 * (olo + ohi));
        node.half = 0.5 * (ohi - olo);
        for (int k = first; k < first + count; ++k) {
            for (int v = 0; v < 3; ++v) node.radius = std::max(node.radius, (corner(k, v) - node.centre).norm());
            addTriangleMoments(corner(k, 0), corner(k, 1), corner(k, 2), node);
        }
        node.first = first;
        node.count = count;
        if (count > leafSize) {
            int axis = 0;
            (chi - clo).maxCoeff(&axis);
            const int half = count / 2;
            std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                             [&](int x, int y) { return centroid[std::size_t(x)][axis] < centroid[std::size_t(y)][axis]; });
            node.left = build(first, half, level + 1);
            node.right = build(first + half, count - half, level + 1);
        }
        tree.nodes[std::size_t(index)] = node;
        return index;
    }
};

}  // namespace

MeshMomentTree buildMeshMomentTree(const TriangleMesh& mesh, int leafSize) {
    if (leafSize < 1) throw std::invalid_argument("buildMeshMomentTree: leafSize must be >= 1, got " + std::to_string(leafSize));
    const std::size_t nt = mesh.triangles.size();
    Builder b{mesh, leafSize, {}, {}, {}};
    b.centroid.resize(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        for (int v = 0; v < 3; ++v)
            if (mesh.triangles[t][v] < 0 || std::size_t(mesh.triangles[t][v]) >= mesh.vertices.size())
                throw std::invalid_argument("buildMeshMomentTree: triangle " + std::to_string(t) +
                                            " has a vertex index out of range");
        b.centroid[t] = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
    }
    b.order.resize(nt);
    std::iota(b.order.begin(), b.order.end(), 0);
    if (nt == 0) return {};
    b.tree.nodes.reserve(2 * (nt / std::size_t(leafSize) + 1));
    b.build(0, int(nt), 1);
    b.tree.triangles.resize(nt);
    b.tree.corners.resize(3 * nt);
    for (std::size_t k = 0; k < nt; ++k) {
        b.tree.triangles[k] = mesh.triangles[std::size_t(b.order[k])];
        for (int c = 0; c < 3; ++c) b.tree.corners[3 * k + std::size_t(c)] = mesh.vertices[std::size_t(b.tree.triangles[k][c])];
    }
    std::vector<double> leafRadii;
    for (const MeshMomentNode& n : b.tree.nodes)
        if (n.left < 0) leafRadii.push_back(n.radius);
    std::nth_element(leafRadii.begin(), leafRadii.begin() + std::ptrdiff_t(leafRadii.size() / 2), leafRadii.end());
    b.tree.medianLeafRadius = leafRadii[leafRadii.size() / 2];
    b.tree.shares = buildVertexShares(mesh);
    b.tree.edges = buildMeshEdges(mesh);
    // Packed bounds: float, rounded outward. A float centre/axis is off by ≤ 2⁻²⁴ relative; the box stays conservative
    // when the half extents grow by that much of |centre| + Σ half (plus a tiny absolute floor).
    b.tree.bounds.resize(b.tree.nodes.size());
    for (std::size_t i = 0; i < b.tree.nodes.size(); ++i) {
        const MeshMomentNode& n = b.tree.nodes[i];
        MeshMomentBounds& o = b.tree.bounds[i];
        const double slack = 4.0 * 0x1p-24 * (n.centre.norm() + n.half.sum()) + 1e-12;
        for (int k = 0; k < 3; ++k) {
            o.centre[k] = float(n.centre[k]);
            o.half[k] = float(n.half[k] + slack);
        }
        for (int k = 0; k < 2; ++k)
            for (int c = 0; c < 3; ++c) o.axes[3 * k + c] = float(n.axes(c, k));
        o.radius = float(n.radius + slack);
        o.right = n.right;
        o.first = n.first;
        o.count = n.count;
    }
    return std::move(b.tree);
}

}  // namespace buoyancy
