/// @file TreeHydrostatics.cpp
/// Exact-mesh hydrostatics through the moment tree (declared in Hydrostatics.h; design.md 2.5 "tiles with
/// precomputed moments"). Same fields as ClippedHydrostatics.cpp (design.md 2.2–2.3), same result in flat water
/// to rounding; the triangles of the leaves that straddle the waterline are clipped exactly as there (on waves with
/// the corner heights from the leaf's second-order expansion of the water patch).
///
/// A node entirely under water, with the water height over it expanded to second order about the node centre P
/// (world, relative to the reference r): f = f0 + G·d + ½ dᵀ H d, d = p − P = R s (s body frame about the node
/// centre c), G = (f_x, 0, f_z), H = [[f_xx, 0, f_xz], [0, 0, 0], [f_xz, 0, f_zz]]. Then
///   D = y − f = c0 + e·s − ½ sᵀ H_b s,  c0 = P_y − f0,  e = Rᵀ(ŷ − G),  H_b = Rᵀ H R,
/// and with u = Rᵀŷ (n_y = u·n) and the node moments μ0 = ∫n, μ1 = ∫s nᵀ, μ2 = ∫s sᵀ n (MeshMomentTree.h):
///   ∫ D n        = c0 μ0 + μ1ᵀ e − ½ H_b : μ2                                   (exact for quadratic f)
///   V            = u · ∫ D n
///   ∫ D s × n    = c0 ε:μ1 + Σ_i e_i ∫ s_i s × n                                (the −½ sᵀH s term, cubic in s, dropped)
///   ∫ s D n_y    = c0 μ1 u + Σ_j e_j ∫ s s_j n_y                                (idem)
///   ∫ D² n_y     = c0² μ0·u + 2 c0 e·μ1 u + eᵀ(μ2·u)e − c0 H_b:(μ2·u)           (terms of order ≥ 3 in s dropped)
/// In flat water G = H = 0 and every formula is exact. On waves the dropped terms are O(|H| ρ³) per unit area for a
/// node of radius ρ (measured against clipping every triangle in tests/integrals/TreeHydrostaticsTest.cpp).
/// Classification of a node: D ranges over it within c0 ± (Σ_k |e·a_k| h_k + ½ K ρ²) (a_k, h_k its oriented box, K the
/// patch's curvature scale): entirely above → skipped, entirely below → closed form (on waves only if its radius keeps
/// the expansion's third-order remainder within kExpansionTolerance), else its children / its triangles. A straddling
/// leaf's triangles are clipped in the body frame (D linear over each, from its corners) into the same body-frame sums.
/// Torque and first moments about r follow from the node's offset c − q_r, q_r = Rᵀ(r − t).

#include <BulletBuoyancy/integrals/BodyFrameSums.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/integrals/WetTriangleIntegrals.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace buoyancy {
namespace {

/// Height tolerance of the second-order water expansion over a node, as a fraction of the body's mean thickness V / A
/// (volume over surface area): a node of radius ρ takes the closed form on waves when the third-order remainder
/// K₃ ρ³ / 6 (K₃ = WaterPatch::thirdDerivativeBound) is at most kExpansionTolerance · V / A. The remainder is what the
/// closed form misses per unit of projected area, so the volume it adds is ≲ that × the wetted area, ≲ tolerance × V.
/// (The earlier rule K ρ ≤ const on the curvature alone let nodes grow like 1/amplitude in low waves of the same
/// wavelengths, where the third-order term does not shrink as fast: 0.2 % of V on the 3,400-triangle boat at 0.3 of
/// the scaling sea's amplitudes.) Measured against clipping every triangle with the same patch: see
/// tests/integrals/TreeHydrostaticsTest.cpp; over the benchmark shapes at 0.1–1 of the scaling sea's amplitudes the tree's
/// own volume error is ≤ 1.7e-4 of V at 1e-3 (≤ 0.5e-4 at 2e-4, where it no longer pays on the scaling sea itself).
constexpr double kExpansionTolerance = 1e-3;

/// Packed symmetric index (xx, xy, xz, yy, yz, zz).
constexpr int kSym[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};

/// Add a node entirely under water (see the file comment). e, Hw (packed H_b, off-diagonals doubled) body frame.
/// Curved = false: flat water (H = 0; Hw is not read), the same sums without the curvature terms.
template <bool Curved>
inline void addWetNode(const MeshMomentNode& n, const Eigen::Vector3d& u, const Eigen::Vector3d& offset, double c0,
                       const Eigen::Vector3d& e, const double Hw[6], NodeSums& acc) {
    // μ2·u and μ1 u
    double m2u[6];
    for (int ij = 0; ij < 6; ++ij) m2u[ij] = n.m2[ij][0] * u.x() + n.m2[ij][1] * u.y() + n.m2[ij][2] * u.z();
    const Eigen::Vector3d m1u = n.m1 * u;
    const double m0u = n.m0.dot(u);
    // ∫ D n (body)
    Eigen::Vector3d F = c0 * n.m0 + n.m1.transpose() * e;
    if (Curved) {
        for (int ij = 0; ij < 6; ++ij) {
            const double h = 0.5 * Hw[ij];
            F.x() -= h * n.m2[ij][0];
            F.y() -= h * n.m2[ij][1];
            F.z() -= h * n.m2[ij][2];
        }
    }
    const double V = u.dot(F);
    // ∫ D s × n ≈ c0 ε:μ1 + Σ_i e_i ∫ s_i (s × n); (s × n)_a = s_{a+1} n_{a+2} − s_{a+2} n_{a+1}
    Eigen::Vector3d sxn(n.m1(1, 2) - n.m1(2, 1), n.m1(2, 0) - n.m1(0, 2), n.m1(0, 1) - n.m1(1, 0));
    sxn *= c0;
    for (int i = 0; i < 3; ++i) {
        const double ei = e[i];
        sxn.x() += ei * (n.m2[kSym[i][1]][2] - n.m2[kSym[i][2]][1]);
        sxn.y() += ei * (n.m2[kSym[i][2]][0] - n.m2[kSym[i][0]][2]);
        sxn.z() += ei * (n.m2[kSym[i][0]][1] - n.m2[kSym[i][1]][0]);
    }
    // ∫ s D n_y ≈ c0 μ1 u + Σ_j e_j ∫ s s_j n_y
    Eigen::Vector3d sDny = c0 * m1u;
    for (int i = 0; i < 3; ++i) sDny[i] += e.x() * m2u[kSym[i][0]] + e.y() * m2u[kSym[i][1]] + e.z() * m2u[kSym[i][2]];
    // ∫ D² n_y
    double eMe = 0, hM = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) eMe += e[i] * e[j] * m2u[kSym[i][j]];
    if (Curved)
        for (int ij = 0; ij < 6; ++ij) hM += Hw[ij] * m2u[ij];
    const double D2 = c0 * c0 * m0u + 2.0 * c0 * e.dot(m1u) + eMe - c0 * hM;

    acc.V += V;
    acc.F += F;
    acc.T += offset.cross(F) + sxn;
    acc.Q += offset * V + sDny;
    acc.D2 += D2;
    acc.Ay += m0u;
    acc.area += n.area;
}

}  // namespace

HydrostaticsResult treeHydrostatics(const MeshMomentTree& tree, const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                    const btWaterSurface& water, double time, double fluidDensity, double gravity,
                                    const Eigen::Vector3d& torqueReference, const WaterPatch* patch) {
    checkBodyFrameArguments("treeHydrostatics", fluidDensity, gravity, pose, torqueReference);
    double flatH = 0;
    const bool flat = water.isFlat(time, flatH);
    // Without a second-order water model over the nodes (a surface that is neither flat nor given by a patch): the
    // clip-all result through the per-vertex shares (VertexHydrostatics.cpp), one exact query per vertex.
    // The shares are also what pays on waves short enough to make the typical leaf too large for the closed form
    // (median leaf radius > the largest radius the expansion allows, below): the traversal would then visit almost
    // every node and clip the leaves with the patch's own heights.
    if (tree.nodes.empty())
        return clippedHydrostatics(mesh, pose, water, time, fluidDensity, gravity, torqueReference, patch);
    if (tree.shares.vertexCount() != mesh.vertices.size() || tree.shares.triangleCount() != mesh.triangles.size())
        throw std::invalid_argument("treeHydrostatics: the tree was built for another mesh");
    const double thickness = tree.nodes[0].area > 0 ? std::abs(tree.nodes[0].m1.trace()) / 3.0 / tree.nodes[0].area : 0.0;
    // Water bilinear over a lattice (a grid, an FFT ocean without choppiness): triangles cut along the lattice lines,
    // exact for that water, with the surface's own heights (CurvedHydrostatics.cpp).
    btWaterLattice lattice;
    if (!flat && water.bilinearLattice(time, lattice))
        return curvedHydrostatics(mesh, tree.edges, pose, water, time, fluidDensity, gravity, torqueReference, thickness,
                                  nullptr);
    // Smooth waves that declare their third-derivative scale (Gerstner): the water curved over each triangle
    // (CurvedHydrostatics.cpp). Other surfaces (a choppy FFT ocean, the interactive surface) keep the plane through
    // each triangle's corner heights (per-vertex shares).
    const bool curved = !flat && water.heightThirdDerivativeScale(time) > 0;
    if (!flat && !(patch && patch->finite()))
        return curved ? curvedHydrostatics(mesh, tree.edges, pose, water, time, fluidDensity, gravity, torqueReference,
                                           thickness, nullptr)
                      : vertexHydrostatics(tree.shares, pose, water, time, fluidDensity, gravity, torqueReference, nullptr);
    // Largest node radius for the closed form on waves (kExpansionTolerance): K₃ ρ³ / 6 ≤ tolerance · V / A.
    const double K3 = flat ? 0.0 : patch->thirdDerivativeBound();
    const double maxRadius = K3 > 0 ? std::cbrt(6.0 * kExpansionTolerance * thickness / K3)
                                    : std::numeric_limits<double>::infinity();
    // Measured (one evaluation, 24 poses × times in the scaling sea, the patch sized as the action sizes it; mean ratio of the
    // median leaf radius to the largest radius): the traversal pays while the median leaf is at most ≈ 0.35 of the
    // largest radius (duck-x4 0.19: 51 µs against 106 through the shares; torus-fine 0.23: 139 against 170; the sphere
    // 0.30: 22 against 28), the per-vertex shares beyond (the duck 0.38: 28 against 34; the 3,400-triangle boat 0.55,
    // the torus 0.62, the 850-triangle boat 1.1: within 5 %).
    // There, a mesh fine against the water's curvature keeps the plane through each triangle's corner heights: over a
    // triangle of size h that plane is off by at most K₂h²/8 (K₂ the patch's curvature), so its volume error over the
    // wet area is ≲ K₂h²/(8 T) of V (T the mean thickness V/A). Measured against the divergence-theorem reference in
    // the scaling sea (tests/bench/WaveMethodsTest.cpp, "fine meshes"): the 850-triangle boat, estimate 0.0051,
    // plane 0.100 % of V worst, curved 0.006 % at 7× the time; the 3,400-triangle boat, estimate 0.0013, plane 0.026 %,
    // curved 0.003 % at 15× the time. So the plane is kept while the estimate is ≤ kPlaneWaterTolerance, on meshes of
    // at least kPlaneWaterMinTriangles triangles: the median leaf does not stand for a low-poly mesh's long slivers
    // (a 16-sided cylinder's sides run its whole length), and a low-poly mesh's curved evaluation is cheap.
    if (!flat && tree.medianLeafRadius > 0.35 * maxRadius) {
        const double planeEstimate = patch->curvatureBound() * tree.medianLeafRadius * tree.medianLeafRadius /
                                     (8.0 * std::max(thickness, 1e-300));
        const bool planeSuffices =
            mesh.triangles.size() >= kPlaneWaterMinTriangles && planeEstimate <= kPlaneWaterTolerance;
        return curved && !planeSuffices
                   ? curvedHydrostatics(mesh, tree.edges, pose, water, time, fluidDensity, gravity, torqueReference,
                                        thickness, patch)
                   : vertexHydrostatics(tree.shares, pose, water, time, fluidDensity, gravity, torqueReference, patch);
    }
    if (tree.triangles.size() != mesh.triangles.size() || tree.bounds.size() != tree.nodes.size())
        throw std::invalid_argument("treeHydrostatics: the tree was built for another mesh");
    if (flat && !std::isfinite(flatH)) throw std::runtime_error("treeHydrostatics: the flat water height is not finite");

    thread_local std::vector<int> stack;  // traversal stack, reused (no allocation per call once grown)
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d t = pose.translation();
    const Eigen::Vector3d& r = torqueReference;
    const Eigen::Vector3d u = R.row(1).transpose();   // world up in the body frame
    const Eigen::Vector3d X = R.row(0).transpose(), Z = R.row(2).transpose();
    const Eigen::Vector3d qr = R.transpose() * (r - t);  // reference point, body frame
    const double flatOffset = t.y() - flatH;             // flat water: D(q) = u·q + t_y − level
    const double K = flat ? 0.0 : patch->curvatureBound();
    // Every value of the patch's interpolant lies within [waterLow, waterHigh]: the Catmull-Rom weights of a cell sum
    // to 1 and their negative part is at most 2 × 0.125 × 1.125 ≈ 0.28, so it overshoots the node range by at most
    // 0.28 × its spread (0.5 × used). Points outside the footprint are clamped to its border cells (WaterPatch.h).
    const double nodeSpread = flat ? 0.0 : patch->maxNode() - patch->minNode();
    const double waterLow = flat ? flatH : patch->minNode() - 0.5 * nodeSpread;
    const double waterHigh = flat ? flatH : patch->maxNode() + 0.5 * nodeSpread;

    NodeSums acc;  // wet nodes and the wetted parts of the straddling leaves' triangles, body frame
    stack.clear();
    stack.push_back(0);
    while (!stack.empty()) {
        const int index = stack.back();
        stack.pop_back();
        const MeshMomentBounds& b = tree.bounds[std::size_t(index)];
        const Eigen::Vector3d c(b.centre[0], b.centre[1], b.centre[2]);
        // World centre of the box (flat water needs only its height).
        const Eigen::Vector3d P = flat ? Eigen::Vector3d(0.0, u.dot(c) + t.y(), 0.0) : Eigen::Vector3d(R * c + t);
        const double rho = b.radius;
        const Eigen::Vector3d a0(b.axes[0], b.axes[1], b.axes[2]), a1(b.axes[3], b.axes[4], b.axes[5]);
        const Eigen::Vector3d a2 = a0.cross(a1);  // the box's third axis (not stored)
        if (!flat) {
            // Before the (costlier) expansion: the node's box against the range every patch height lies in. Wholly
            // above it: dry. Wholly below it and too large for the closed form: its children, whatever the water does.
            const double yHalf = std::abs(u.dot(a0)) * b.half[0] + std::abs(u.dot(a1)) * b.half[1] +
                                 std::abs(u.dot(a2)) * b.half[2];
            if (P.y() - yHalf > waterHigh) continue;
            if (P.y() + yHalf < waterLow && rho > maxRadius && b.right >= 0) {
                stack.push_back(index + 1);
                stack.push_back(b.right);
                continue;
            }
        }
        double f0 = flatH, fx = 0, fz = 0, fxx = 0, fxz = 0, fzz = 0;
        if (!flat) patch->taylor(P.x(), P.z(), f0, fx, fz, fxx, fxz, fzz);
        // D = y − f over the node: c0 + e·s − ½ sᵀH_b s (file comment). Its linear part ranges over the node's oriented
        // box by ± Σ_k |e·a_k| h_k (the box's extent across the local water slope, not just along the vertical); the
        // quadratic part by ± ½ K ρ².
        double c0 = P.y() - f0;
        Eigen::Vector3d e = u - fx * X - fz * Z;  // Rᵀ(ŷ − G), body frame
        const double spread = std::abs(e.dot(a0)) * b.half[0] + std::abs(e.dot(a1)) * b.half[1] +
                              std::abs(e.dot(a2)) * b.half[2] + 0.5 * K * rho * rho;
        if (c0 - spread >= 0) continue;  // entirely above the water
        // Entirely below: closed form, if the node is small enough for the expansion (ρ ≤ maxRadius: the neglected
        // third-order part of the water height over the node grows like ρ³; measured in
        // tests/integrals/TreeHydrostaticsTest.cpp: the tree adds ≤ 2e-4 of V to the patch's own error).
        // (Strictly below: a node touching the water from below is opened, so that the waterline along it reaches the
        // waterplane moments through its clipped triangles.)
        if (c0 + spread < 0 && rho <= maxRadius) {
            const MeshMomentNode& n = tree.nodes[std::size_t(index)];
            if (flat) {  // G = H = 0: D = u·q + t_y − level exactly, no expansion to move
                addWetNode<false>(n, u, n.centre - qr, u.dot(n.centre) + flatOffset, u, nullptr, acc);
                continue;
            }
            // The moments are about the double-precision centre: move the expansion there (δ = its world offset).
            const Eigen::Vector3d Pd = R * n.centre + t;
            const double dx = Pd.x() - P.x(), dz = Pd.z() - P.z();
            f0 += fx * dx + fz * dz + 0.5 * (fxx * dx * dx + 2.0 * fxz * dx * dz + fzz * dz * dz);
            fx += fxx * dx + fxz * dz;
            fz += fxz * dx + fzz * dz;
            c0 = Pd.y() - f0;
            e = u - fx * X - fz * Z;
            // H_b = f_xx X Xᵀ + f_xz (X Zᵀ + Z Xᵀ) + f_zz Z Zᵀ, packed, off-diagonals doubled.
            double Hw[6];
            for (int i = 0; i < 3; ++i)
                for (int j = i; j < 3; ++j) {
                    const double h = fxx * X[i] * X[j] + fxz * (X[i] * Z[j] + Z[i] * X[j]) + fzz * Z[i] * Z[j];
                    Hw[kSym[i][j]] = i == j ? h : 2.0 * h;
                }
            addWetNode<true>(n, u, n.centre - qr, c0, e, Hw, acc);
            continue;
        }
        if (b.right >= 0) {
            stack.push_back(index + 1);  // first child: next in depth-first order
            stack.push_back(b.right);
            continue;
        }
        // A straddling leaf: clip its triangles (corners read contiguously) in the body frame. D = y − f at each corner:
        // in flat water u·q + t_y − level; on waves the leaf's second-order expansion about its centre when the leaf is
        // small enough (same criterion as above), else the patch's interpolant at the corner's world (x, z) (a leaf of a
        // few large triangles spans much of the body).
        const bool expand = flat || rho <= maxRadius;
        const double P0 = P.y() - f0;  // D at the leaf centre c (its expansion, on waves)
        const Eigen::Vector3d eLeaf = u - fx * X - fz * Z;
        const Eigen::Vector3d* corner = tree.corners.data() + 3 * std::size_t(b.first);
        for (int k = 0; k < b.count; ++k, corner += 3) {
            BodyCorner in[3];
            for (int j = 0; j < 3; ++j) {
                const Eigen::Vector3d& q = corner[j];
                if (flat) {
                    in[j].D = u.dot(q) + flatOffset;
                } else if (expand) {
                    const Eigen::Vector3d sigma = q - c;
                    const double xs = X.dot(sigma), zs = Z.dot(sigma);
                    in[j].D = P0 + eLeaf.dot(sigma) - 0.5 * (fxx * xs * xs + 2.0 * fxz * xs * zs + fzz * zs * zs);
                } else {
                    in[j].D = u.dot(q) + t.y() - patch->height(X.dot(q) + t.x(), Z.dot(q) + t.z());
                }
            }
            if (in[0].D >= 0 && in[1].D >= 0 && in[2].D >= 0) continue;  // dry (or touching)
            for (int j = 0; j < 3; ++j) in[j].s = corner[j] - qr;
            addClippedBodyTriangle(in, u, X, Z, acc);
        }
    }

    const WetIntegrals I = toWetIntegrals(acc, R);  // world frame relative to r; result shared with the clip-all path
    return I.result(fluidDensity * gravity, r, "treeHydrostatics");
}

}  // namespace buoyancy
