// The waterplane's area moments (HydrostaticsResult::waterplane, summed from the waterline's segments by Green's
// theorem in WetTriangleIntegrals.h / BodyFrameSums.h) against two independent oracles: a box's rectangle section in
// closed form, and, for any closed mesh in flat water, the divergence theorem on the wetted surface,
// ∫_waterplane f dA = −∫_wet f n_y dA for f = 1, x', z', x'², x'z', z'² (the fields (0, f, 0) are divergence-free),
// the wetted pieces clipped and integrated here. All three exact-mesh paths (clip-all, moment tree, vertex shares).
#include "HydrostaticsTestCases.h"
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/integrals/VertexShares.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include "oracles/OracleMeshes.h"
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>
#include <array>
#include <cmath>
#include <random>

using namespace buoyancy;
using namespace buoyancy_test;

namespace {
constexpr double kRho = 1000, kG = 9.81;

/// {A, ∫x', ∫z', ∫x'², ∫x'z', ∫z'²} of the waterplane of a posed mesh below flat water y = 0, about r: the wetted
/// pieces (each triangle clipped against y ≤ 0) summed as −∫ f n_y dA, exact per flat triangle
/// (∫ x dA = A x̄, ∫ x² dA = A/6 Σ_{i≤j} x_i x_j, ∫ x z dA = A/12 (Σ x_i z_i + Σx Σz)).
std::array<double, 6> divergenceOracle(const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& tris,
                                       const Eigen::Vector3d& r) {
    std::array<double, 6> m{};
    for (const auto& t : tris) {
        Eigen::Vector3d poly[4];
        const int n = clipTriangleBelow(v[std::size_t(t[0])], v[std::size_t(t[1])], v[std::size_t(t[2])], 0.0, poly);
        for (int k = 1; k + 1 < n; ++k) {
            const Eigen::Vector3d p[3] = {poly[0] - r, poly[k] - r, poly[k + 1] - r};
            const double ay = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).y();  // ∫ n_y dA over the piece
            const double sx = p[0].x() + p[1].x() + p[2].x(), sz = p[0].z() + p[1].z() + p[2].z();
            double xx = 0, zz = 0, xz = 0;
            for (int i = 0; i < 3; ++i) {
                xz += p[i].x() * p[i].z();
                for (int j = i; j < 3; ++j) {
                    xx += p[i].x() * p[j].x();
                    zz += p[i].z() * p[j].z();
                }
            }
            m[0] -= ay;
            m[1] -= ay * sx / 3;
            m[2] -= ay * sz / 3;
            m[3] -= ay * xx / 6;
            m[4] -= ay * (xz + sx * sz) / 12;
            m[5] -= ay * zz / 6;
        }
    }
    return m;
}

std::array<double, 6> fromResult(const HydrostaticsResult& h) {
    return {h.waterline_area, h.waterplane.x, h.waterplane.z, h.waterplane.xx, h.waterplane.xz, h.waterplane.zz};
}

/// Largest difference over the six moments, each against its own scale (A, A·L, A·L² with L the mesh size).
double momentError(const std::array<double, 6>& a, const std::array<double, 6>& b, double area, double size) {
    const double scale[6] = {area, area * size, area * size, area * size * size, area * size * size, area * size * size};
    double e = 0;
    for (int i = 0; i < 6; ++i) e = std::max(e, std::abs(a[std::size_t(i)] - b[std::size_t(i)]) / scale[i]);
    return e;
}
}  // namespace

TEST_CASE("waterplane moments: a yawed box's rectangle section in closed form", "[integrals][waterplane]") {
    // Box a × h × c (x, y, z), yawed by ψ about y, centre at (tx, ty, tz) with |ty| < h/2: the section by y = 0 is
    // the a × c rectangle about (tx, tz), its axes U = (cos ψ, −sin ψ), W = (sin ψ, cos ψ) in (x, z). About r:
    // ∫x'² = A X² + U_x² a³c/12 + W_x² ac³/12, ∫x'z' = A X Z + U_x U_z a³c/12 + W_x W_z ac³/12, … (X = tx − r_x).
    const double a = 2.0, h = 0.6, c = 1.0;
    const TriangleMesh mesh = toTriangleMesh(oracleBox(a, h, c));
    const MeshMomentTree tree = buildMeshMomentTree(mesh);
    const VertexShares shares = buildVertexShares(mesh);
    const btFlatWaterSurface flat(0.0);
    for (double psi : {0.0, 0.3, 1.1, 2.5}) {
        for (double ty : {-0.2, 0.1, 0.25}) {
            INFO("psi " << psi << " ty " << ty);
            Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
            pose.linear() = Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitY()).toRotationMatrix();
            pose.translation() = Eigen::Vector3d(0.7, ty, -1.3);
            const Eigen::Vector3d r(0.2, 0.5, -0.9);
            const Eigen::Vector3d U = pose.linear() * Eigen::Vector3d::UnitX(), W = pose.linear() * Eigen::Vector3d::UnitZ();
            const double A = a * c, Iu = a * a * a * c / 12, Iw = a * c * c * c / 12;
            const double X = 0.7 - r.x(), Z = -1.3 - r.z();
            const std::array<double, 6> exact = {A,
                                                 A * X,
                                                 A * Z,
                                                 A * X * X + U.x() * U.x() * Iu + W.x() * W.x() * Iw,
                                                 A * X * Z + U.x() * U.z() * Iu + W.x() * W.z() * Iw,
                                                 A * Z * Z + U.z() * U.z() * Iu + W.z() * W.z() * Iw};
            const HydrostaticsResult paths[3] = {clippedHydrostatics(mesh, pose, flat, 0.0, kRho, kG, r),
                                                 treeHydrostatics(tree, mesh, pose, flat, 0.0, kRho, kG, r),
                                                 vertexHydrostatics(shares, pose, flat, 0.0, kRho, kG, r)};
            for (int p = 0; p < 3; ++p) {
                const HydrostaticsResult& res = paths[p];
                INFO("path " << p << " (clip-all, tree, shares): waterline area " << res.waterline_area);
                CHECK(res.waterplane.valid);
                CHECK(momentError(fromResult(res), exact, A, a) < 1e-12);
            }
        }
    }
}

TEST_CASE("waterplane moments: closed meshes at random poses against the divergence theorem",
          "[integrals][waterplane]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    const btFlatWaterSurface flat(0.0);
    for (const NamedMesh& s : fiveOracleShapes()) {
        const TriangleMesh mesh = toTriangleMesh(s.mesh);
        const MeshMomentTree tree = buildMeshMomentTree(mesh);
        const VertexShares shares = buildVertexShares(mesh);
        double lo = 1e300, hi = -1e300, size = 0;
        for (const auto& p : s.mesh.verts) {
            lo = std::min(lo, p.y());
            hi = std::max(hi, p.y());
            size = std::max(size, p.norm());
        }
        for (int k = 0; k < 12; ++k) {
            Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
            pose.linear() = Eigen::AngleAxisd(3.0 * U(rng), Eigen::Vector3d(U(rng), U(rng), U(rng)).normalized())
                                .toRotationMatrix();
            pose.translation() = Eigen::Vector3d(U(rng), 0.4 * size * U(rng), U(rng));
            const Eigen::Vector3d r(U(rng), U(rng), U(rng));
            std::vector<Eigen::Vector3d> posed;
            for (const auto& p : s.mesh.verts) posed.push_back(pose * p);
            const std::array<double, 6> oracle = divergenceOracle(posed, s.mesh.tris, r);
            if (!(oracle[0] > 1e-6 * size * size)) continue;  // dry or under water: no waterplane
            INFO(s.name << " pose " << k);
            const HydrostaticsResult paths[3] = {clippedHydrostatics(mesh, pose, flat, 0.0, kRho, kG, r),
                                                 treeHydrostatics(tree, mesh, pose, flat, 0.0, kRho, kG, r),
                                                 vertexHydrostatics(shares, pose, flat, 0.0, kRho, kG, r)};
            for (const HydrostaticsResult& res : paths) {
                CHECK(res.waterplane.valid);
                CHECK(momentError(fromResult(res), oracle, oracle[0], size) < 1e-9);
            }
        }
    }
}

TEST_CASE("waterplane moments: the three paths agree on waves, and a body under water has none",
          "[integrals][waterplane]") {
    // On waves each path cuts a triangle against the plane through its corners' heights (the same water model), so
    // the waterline — and the moments — are the same polygon.
    std::vector<btGerstnerWave> waves(2);
    waves[0] = {0.3, 8.0, 1.0, 0.3, 0.5, 0.0};
    waves[1] = {0.1, 3.0, -0.2, 1.0, 0.5, 1.0};
    const btGerstnerWaterSurface sea(waves);
    const TriangleMesh mesh = toTriangleMesh(oracleSphere(0.8, 32, 16));
    const MeshMomentTree tree = buildMeshMomentTree(mesh);
    const VertexShares shares = buildVertexShares(mesh);
    for (double t : {0.0, 0.7, 1.9}) {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = Eigen::Vector3d(0.3, sea.height(0.3, 0.4, t) + 0.1, 0.4);
        const Eigen::Vector3d r = pose.translation();
        const HydrostaticsResult clip = clippedHydrostatics(mesh, pose, sea, t, kRho, kG, r);
        const HydrostaticsResult shared = vertexHydrostatics(shares, pose, sea, t, kRho, kG, r);
        REQUIRE(clip.waterplane.valid);
        REQUIRE(shared.waterplane.valid);
        CHECK(momentError(fromResult(shared), fromResult(clip), clip.waterline_area, 0.8) < 1e-10);
        CHECK(clip.waterline_area == Approx(M_PI * 0.8 * 0.8).epsilon(0.1));  // a cap near the equator
    }
    Eigen::Isometry3d deep = Eigen::Isometry3d::Identity();
    deep.translation() = Eigen::Vector3d(0, -5, 0);
    const HydrostaticsResult under = treeHydrostatics(tree, mesh, deep, sea, 0.0, kRho, kG, deep.translation());
    CHECK(under.waterplane.valid);
    CHECK(under.waterline_area == Approx(0).margin(1e-12));
    CHECK(under.waterplane.xx == Approx(0).margin(1e-12));
}
