// Exact-mesh hydrostatics through the per-vertex shares (plugin/BulletBuoyancy/integrals/VertexShares + VertexHydrostatics): the
// shares against their definition, flat water against the independent polyhedral oracle and Archimedes (water levels
// through vertices included: the corners with D = 0 exactly), and waves against clipping every triangle with the same
// corner heights (the same water model, written independently in ClippedHydrostatics.cpp).
#include "ArchimedesErrors.h"
#include "HydrostaticsTestCases.h"
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/VertexShares.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include "oracles/OracleMeshes.h"
#include "oracles/PolyhedralOracle.h"
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>

using namespace buoyancy;
using namespace buoyancy_test;

namespace {
constexpr double kRho = 1000, kG = 9.81;

/// Wetted area below y = h of a posed mesh: each triangle clipped against the plane (clipTriangleBelow, independent).
double wettedAreaBelow(const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& tris, double h) {
    double area = 0;
    for (const auto& t : tris) {
        Eigen::Vector3d poly[4];
        const int n = clipTriangleBelow(v[std::size_t(t[0])], v[std::size_t(t[1])], v[std::size_t(t[2])], h, poly);
        for (int k = 1; k + 1 < n; ++k) area += 0.5 * (poly[k] - poly[0]).cross(poly[k + 1] - poly[0]).norm();
    }
    return area;
}
}  // namespace

TEST_CASE("vertex shares: sums of the per-triangle terms they regroup", "[integrals][vertex]") {
    for (const auto& s : fiveOracleShapes()) {
        INFO(s.name);
        const TriangleMesh mesh = toTriangleMesh(s.mesh);
        const VertexShares sh = buildVertexShares(mesh);
        REQUIRE(sh.vertexCount() == mesh.vertices.size());
        REQUIRE(sh.triangleCount() == mesh.triangles.size());
        // Closed mesh: Σ_v B_v = Σ_t A_t = 0; Σ_v a_v = the surface area (oracle); Σ_v M_v = ∫ q nᵀ dA = V I
        // (divergence theorem: ∫ ∂q_i/∂q_j dV); Σ_v T_v = ∫ q × n dA = 0 (curl of q is 0).
        Eigen::Vector3d B = Eigen::Vector3d::Zero(), T = Eigen::Vector3d::Zero();
        Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
        double area = 0;
        for (std::size_t v = 0; v < sh.vertexCount(); ++v) {
            B += Eigen::Vector3d(sh.bx[v], sh.by[v], sh.bz[v]);
            T += Eigen::Vector3d(sh.tx[v], sh.ty[v], sh.tz[v]);
            for (int k = 0; k < 9; ++k) M(k / 3, k % 3) += sh.m[k][v];
            area += sh.area[v];
        }
        const double V = oracleDryMoments(s.mesh.verts, s.mesh.tris).volume;
        const double A = oracleSurfaceArea(s.mesh.verts, s.mesh.tris);
        CHECK(B.norm() < 1e-12 * A);
        CHECK(std::abs(area - A) < 1e-12 * A);
        CHECK((M - V * Eigen::Matrix3d::Identity()).norm() < 1e-12 * V);
        CHECK(T.norm() < 1e-12 * V);
    }
    TriangleMesh bad = toTriangleMesh(oracleBox(1, 1, 1));
    bad.triangles[3][1] = 99;
    CHECK_THROWS_AS(buildVertexShares(bad), std::invalid_argument);
    bad = toTriangleMesh(oracleBox(1, 1, 1));
    bad.vertices[2].x() = std::nan("");
    CHECK_THROWS_AS(buildVertexShares(bad), std::invalid_argument);
}

TEST_CASE("vertex hydrostatics in flat water: the oracle and Archimedes to rounding, levels through vertices included",
          "[integrals][vertex]") {
    std::mt19937 rng(23);
    ArchimedesErrors worst;
    for (const auto& s : fiveOracleShapes()) {
        const TriangleMesh mesh = toTriangleMesh(s.mesh);
        const VertexShares sh = buildVertexShares(mesh);
        const double Vfull = oracleDryMoments(s.mesh.verts, s.mesh.tris).volume;
        for (int p = 0; p < 10; ++p) {
            // Pose 0: the identity, so that levels through vertices hit whole faces of the box and the cylinder.
            const Eigen::Isometry3d pose = p == 0 ? Eigen::Isometry3d::Identity() : randomPose(rng, 3.0);
            const auto posed = oraclePose(s.mesh.verts, pose);
            const PosedBounds bounds = posedBounds(posed);
            const double lo = bounds.lo, hi = bounds.hi, diag = bounds.diag;
            const Eigen::Vector3d ref = pose.translation() + Eigen::Vector3d(0.07, -0.03, 0.02);
            std::vector<double> levels;
            for (int k = 0; k < 13; ++k) levels.push_back(lo - 0.05 * (hi - lo) + k * (1.1 * (hi - lo)) / 12.0);
            for (int k = 0; k < 4; ++k) levels.push_back(posed[std::size_t(k * 3) % posed.size()].y());  // through vertices
            levels.push_back(lo);
            levels.push_back(hi);
            for (double h : levels) {
                const btFlatWaterSurface water(h);
                const HydrostaticsResult r = vertexHydrostatics(sh, pose, water, 0.0, kRho, kG, ref);
                const OracleMoments o = oracleSubmergedMoments(posed, s.mesh.tris, h);
                INFO(s.name << " pose " << p << " h=" << h << " V=" << r.submerged_volume << " oracle " << o.volume);
                const ArchimedesErrors e = archimedesErrors(r, o, Vfull, diag, ref, kRho, kG);
                CHECK(e.volume < 1e-10);
                CHECK(e.force < 1e-10);
                CHECK(e.torque < 1e-10);
                CHECK(e.centre < 1e-9);
                worst.takeWorst(e);
                CHECK(std::abs(r.waterline_area - oracleCapArea(posed, s.mesh.tris, h)) < 1e-10 * diag * diag);
                CHECK(std::abs(r.wetted_area - wettedAreaBelow(posed, s.mesh.tris, h)) < 1e-10 * diag * diag);
            }
        }
    }
    std::printf("vertex shares, flat water, worst vs oracle: volume %.1e of V, CoB %.1e of diag, force %.1e, torque %.1e\n",
                worst.volume, worst.centre, worst.force, worst.torque);
}

TEST_CASE("vertex hydrostatics on Gerstner waves: clipping every triangle with the same corner heights, to rounding",
          "[integrals][vertex]") {
    const std::vector<btGerstnerWave> p3 = p3SeaWaves();
    const std::vector<btGerstnerWave> shortSea = {{0.25, 3.0, 1.0, 0.2, 0.7, 0.0}, {0.15, 2.0, 0.3, 1.0, 0.6, 1.0}};
    std::mt19937 rng(29);
    double worst = 0;
    int straddling = 0;
    for (const auto* waves : {&p3, &shortSea}) {
        const btGerstnerWaterSurface sea(*waves);
        for (const auto& s : fiveOracleShapes()) {
            const TriangleMesh mesh = toTriangleMesh(s.mesh);
            const VertexShares sh = buildVertexShares(mesh);
            const double Vfull = oracleDryMoments(s.mesh.verts, s.mesh.tris).volume;
            const MeshBall ball = meshBall(mesh);
            const double radius = ball.radius, diag = 2 * radius;
            for (int p = 0; p < 12; ++p) {
                const double t = 0.41 * p;
                const Eigen::Isometry3d pose = poseAcrossWaterline(rng, sea, t, ball, 20.0, 0.7);
                const Eigen::Vector3d bc = pose * ball.centre;
                WaterPatch patch;
                btWaterQueryCache cache;
                patch.build(sea, bc.x(), bc.z(), radius, t, 8, cache);
                const Eigen::Vector3d ref = bc + Eigen::Vector3d(0.05, -0.02, 0.03);
                for (const WaterPatch* pp : {static_cast<const WaterPatch*>(&patch), static_cast<const WaterPatch*>(nullptr)}) {
                    const HydrostaticsResult r = vertexHydrostatics(sh, pose, sea, t, kRho, kG, ref, pp);
                    const HydrostaticsResult e = clippedHydrostatics(mesh, pose, sea, t, kRho, kG, ref, pp);
                    INFO(s.name << " pose " << p << (pp ? " patch" : " exact queries") << " V " << r.submerged_volume
                                << " clip-all " << e.submerged_volume);
                    if (e.submerged_volume > 1e-3 * Vfull && e.submerged_volume < 0.999 * Vfull) ++straddling;
                    const double d = std::max({std::abs(r.submerged_volume - e.submerged_volume) / Vfull,
                                               (r.force - e.force).norm() / (kRho * kG * Vfull),
                                               (r.torque - e.torque).norm() / (kRho * kG * Vfull * diag),
                                               std::abs(r.waterline_area - e.waterline_area) / (diag * diag),
                                               std::abs(r.wetted_area - e.wetted_area) / (diag * diag)});
                    CHECK(d < 1e-11);
                    if (e.submerged_volume > 1e-6 * Vfull)
                        CHECK((r.centre_of_buoyancy - e.centre_of_buoyancy).norm() / diag < 1e-9);
                    worst = std::max(worst, d);
                }
            }
        }
    }
    CHECK(straddling > 100);  // the cases cross the waterline (not all dry or all wet)
    std::printf("vertex shares on waves vs clipping every triangle: worst relative difference %.1e (%d cases across "
                "the waterline)\n",
                worst, straddling);
}

TEST_CASE("vertex hydrostatics: bad input", "[integrals][vertex]") {
    const TriangleMesh box = toTriangleMesh(oracleBox(1, 1, 1));
    const VertexShares sh = buildVertexShares(box);
    const btFlatWaterSurface water(0.0);
    Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
    bad.translation().x() = std::nan("");
    CHECK_THROWS_AS(vertexHydrostatics(sh, bad, water, 0, kRho, kG, Eigen::Vector3d::Zero()), std::invalid_argument);
    CHECK_THROWS_AS(vertexHydrostatics(sh, Eigen::Isometry3d::Identity(), water, 0, -1, kG, Eigen::Vector3d::Zero()),
                    std::invalid_argument);
    CHECK_THROWS_AS(vertexHydrostatics(sh, Eigen::Isometry3d::Identity(), water, 0, kRho, std::nan(""),
                                       Eigen::Vector3d::Zero()),
                    std::invalid_argument);
    const btFlatWaterSurface nanWater(std::nan(""));
    CHECK_THROWS_AS(vertexHydrostatics(sh, Eigen::Isometry3d::Identity(), nanWater, 0, kRho, kG, Eigen::Vector3d::Zero()),
                    std::runtime_error);
    // An empty mesh: nothing under water.
    const VertexShares none = buildVertexShares(TriangleMesh{});
    CHECK(vertexHydrostatics(none, Eigen::Isometry3d::Identity(), water, 0, kRho, kG, Eigen::Vector3d::Zero())
              .submerged_volume == 0);
}
