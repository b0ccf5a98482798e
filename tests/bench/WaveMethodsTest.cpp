// The wave rows' comparison methods and shapes (bullet_examples/benchmark/PlaneClipMethods.h, BenchShapes.h), checked
// against closed forms: a box under flat water and under a tilted planar water surface.
#include "benchmark/BenchSeas.h"
#include "benchmark/BenchShapes.h"
#include "benchmark/PlaneClipMethods.h"
#include "oracles/PolyhedralOracle.h"
#include "oracles/WaveOracle.h"
#include "benchmark/Scaling.h"

#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <ctime>

namespace {

using buoyancy::bench::PlaneMethod;

/// Water that is the plane y = h0 + a x + b z (a tilted, still surface).
class TiltedPlaneWater : public btWaterSurface {
public:
    TiltedPlaneWater(double h0, double a, double b) : m_h0(h0), m_a(a), m_b(b) {}
    void heights(const double* x, const double* z, std::size_t n, double, double* out) const override {
        for (std::size_t i = 0; i < n; ++i) out[i] = m_h0 + m_a * x[i] + m_b * z[i];
    }
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double, double& lo, double& hi) const override {
        lo = 1e300;
        hi = -1e300;
        for (double x : {minX, maxX})
            for (double z : {minZ, maxZ}) {
                const double h = m_h0 + m_a * x + m_b * z;
                lo = std::min(lo, h);
                hi = std::max(hi, h);
            }
    }

private:
    double m_h0, m_a, m_b;
};

Eigen::AlignedBox3d boundsOf(const buoyancy::TriangleMesh& mesh) {
    Eigen::AlignedBox3d b;
    for (const auto& v : mesh.vertices) b.extend(v);
    return b;
}

}  // namespace

TEST_CASE("tangent-plane and fitted-plane in flat water are the exact clip: the box's closed-form volume", "[bench]") {
    const double a = 2.0, b = 0.6, c = 1.0;  // the benchmark's box
    const buoyancy::TriangleMesh box = buoyancy::makeBoxMesh(a, b, c);
    const Eigen::AlignedBox3d bounds = boundsOf(box);
    const double level = 0.3;
    const btFlatWaterSurface water(level);
    for (double yaw : {0.0, 0.7}) {
        for (double centreY : {0.05, 0.25, 0.45, 0.58}) {
            Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
            pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();  // keeps the box upright
            pose.translation() = Eigen::Vector3d(1.5, centreY, -0.4);
            // Closed form: the box centred at the origin in water at level − centreY.
            const double V = buoyancy_test::boxSubmergedVolume(a, b, c, level - centreY);
            const double cobY = centreY + buoyancy_test::boxCentreOfBuoyancyY(a, b, c, level - centreY);
            const Eigen::Vector3d com = pose.translation();
            for (PlaneMethod m : {PlaneMethod::Tangent, PlaneMethod::Fitted}) {
                INFO(buoyancy::bench::planeMethodName(m) << " yaw " << yaw << " centre y " << centreY);
                const buoyancy::HydrostaticsResult h =
                    buoyancy::bench::planeMethodHydrostatics(m, box, bounds, pose, water, 2.0, 1000.0, 9.81, com);
                CHECK(h.submerged_volume == Approx(V).epsilon(1e-12));
                CHECK(h.centre_of_buoyancy.y() == Approx(cobY).epsilon(1e-12));
                CHECK(h.centre_of_buoyancy.x() == Approx(com.x()).margin(1e-12));
                CHECK(h.centre_of_buoyancy.z() == Approx(com.z()).margin(1e-12));
                CHECK(h.force.y() == Approx(1000.0 * 9.81 * V).epsilon(1e-12));
                CHECK(h.torque.norm() < 1e-9 * 1000.0 * 9.81 * V);  // C_B straight under the COM
            }
        }
    }
    // Heeled: against the polyhedral oracle's clip of the same posed mesh (independent of the library).
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.3, 0.2, 0.1);
    const auto exact =
        buoyancy_test::oracleSubmergedMoments(buoyancy_test::oraclePose(box.vertices, pose), box.triangles, level);
    const buoyancy::HydrostaticsResult h = buoyancy::bench::planeMethodHydrostatics(
        PlaneMethod::Tangent, box, bounds, pose, water, 0.0, 1000.0, 9.81, pose.translation());
    CHECK(h.submerged_volume == Approx(exact.volume).epsilon(1e-12));
    CHECK((h.centre_of_buoyancy - exact.centroid).norm() < 1e-12);
}

TEST_CASE("the fitted and the tangent plane of a tilted planar water surface reproduce it: closed-form box volume", "[bench]") {
    // Water y = h0 + sx x + sz z; the box [x0, x1] × [y0, y1] × [z0, z1] (axis-aligned) with a wet bottom and a dry top
    // everywhere, so V = ∫∫ (h − y0) dx dz = Lx Lz (h(c) − y0) and the centroid follows from the same integrals.
    const double h0 = 0.1, sx = 0.08, sz = -0.05;
    const TiltedPlaneWater water(h0, sx, sz);
    const double Lx = 2.0, Ly = 0.6, Lz = 1.0;
    const buoyancy::TriangleMesh box = buoyancy::makeBoxMesh(Lx, Ly, Lz);
    const Eigen::AlignedBox3d bounds = boundsOf(box);
    const Eigen::Vector3d centre(0.7, 0.05, -1.2);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = centre;
    const double y0 = centre.y() - 0.5 * Ly, H = h0 + sx * centre.x() + sz * centre.z();
    REQUIRE(H - 0.5 * (std::abs(sx) * Lx + std::abs(sz) * Lz) > y0);          // bottom wet everywhere
    REQUIRE(H + 0.5 * (std::abs(sx) * Lx + std::abs(sz) * Lz) < y0 + Ly);     // top dry everywhere
    const double V = Lx * Lz * (H - y0);
    const double cx = centre.x() + sx * Lz * Lx * Lx * Lx / 12.0 / V;
    const double cz = centre.z() + sz * Lx * Lz * Lz * Lz / 12.0 / V;
    const double cy = (Lx * Lz * (H * H - y0 * y0) / 2.0 + (sx * sx * Lz * Lx * Lx * Lx + sz * sz * Lx * Lz * Lz * Lz) / 24.0) / V;

    // The fitted plane over a rectangle is the surface itself.
    const buoyancy::bench::WaterPlane fitted = buoyancy::bench::fittedWaterPlane(water, -1.0, -2.0, 3.0, 0.5, 0.0);
    const Eigen::Vector3d n = Eigen::Vector3d(-sx, 1.0, -sz).normalized();
    CHECK((fitted.normal - n).norm() < 1e-12);
    CHECK(fitted.point.y() == Approx(h0 + sx * fitted.point.x() + sz * fitted.point.z()).margin(1e-12));
    const buoyancy::bench::WaterPlane tangent = buoyancy::bench::tangentWaterPlane(water, 0.3, 0.4, 0.0);
    CHECK((tangent.normal - n).norm() < 1e-9);

    for (PlaneMethod m : {PlaneMethod::Fitted, PlaneMethod::Tangent}) {
        INFO(buoyancy::bench::planeMethodName(m));
        const buoyancy::HydrostaticsResult h =
            buoyancy::bench::planeMethodHydrostatics(m, box, bounds, pose, water, 0.0, 1000.0, 9.81, centre);
        CHECK(h.submerged_volume == Approx(V).epsilon(1e-9));
        CHECK(h.centre_of_buoyancy.x() == Approx(cx).epsilon(1e-9));
        CHECK(h.centre_of_buoyancy.y() == Approx(cy).epsilon(1e-9));
        CHECK(h.centre_of_buoyancy.z() == Approx(cz).epsilon(1e-9));
        // Jolt's force: ρ g V straight up at the centre of buoyancy.
        CHECK(h.force.y() == Approx(1000.0 * 9.81 * V).epsilon(1e-9));
        CHECK(h.force.x() == 0);
        CHECK(h.force.z() == 0);
        const Eigen::Vector3d torque = (h.centre_of_buoyancy - centre).cross(h.force);
        CHECK((h.torque - torque).norm() <= 1e-9 * torque.norm());
    }
}

TEST_CASE("the wave rows' shapes: the low-poly hull is closed, outward and at most 100 triangles", "[bench]") {
    const std::string path = std::string(BUOYANCY_SOURCE_DIR) + "/bullet_examples/models/hull_lowpoly.obj";
    buoyancy::TriangleMesh hull = buoyancy::importMeshFile(path);
    const std::size_t imported = hull.triangleCount();
    const buoyancy::MeshReport report = buoyancy::prepareMesh(hull, path);
    CHECK(report.warnings.empty());
    CHECK(report.flipped_components == 0);
    CHECK(report.degenerate_removed == 0);
    CHECK(report.components == 1);
    CHECK(hull.triangleCount() == imported);
    CHECK(hull.triangleCount() <= 100);
    const auto dry = buoyancy_test::oracleDryMoments(hull.vertices, hull.triangles);
    CHECK(dry.volume > 0);  // outward
    const Eigen::AlignedBox3d b = boundsOf(hull);
    CHECK(b.sizes().maxCoeff() >= 4.0);
    CHECK(b.sizes().maxCoeff() <= 6.0);

    std::vector<std::string> warnings;
    const auto shapes = buoyancy::bench::waveBenchShapes(warnings);
    CHECK(warnings.empty());
    REQUIRE(shapes.size() == 3);
    CHECK(shapes[0].name == "box");
    CHECK(shapes[0].mesh.triangleCount() == 12);
    CHECK(shapes[1].name == "cylinder");
    CHECK(buoyancy_test::oracleDryMoments(shapes[1].mesh.vertices, shapes[1].mesh.triangles).volume > 0);
    CHECK(shapes[2].name == "hull");
}

TEST_CASE("the wave rows' seas: swell is the scaling sea, chop is short and steep", "[bench]") {
    const auto seas = buoyancy::bench::benchSeas();
    REQUIRE(seas.size() == 2);
    CHECK(seas[0].name == "swell");
    CHECK(seas[1].name == "chop");
    REQUIRE(seas[0].waves.size() == 4);
    CHECK(seas[0].waves[0].wavelength == 60.0);
    const btGerstnerWaterSurface chop(seas[1].waves);
    CHECK(chop.loopFactor() == Approx(0.5).margin(0.02));  // Σ Q A k
    for (const auto& w : seas[1].waves) {
        CHECK(w.wavelength >= 4.0);
        CHECK(w.wavelength <= 10.0);
    }
}

TEST_CASE("wave poses put the body's centre at the local water height at their time", "[bench]") {
    const btGerstnerWaterSurface water(buoyancy::bench::chopSea());
    const buoyancy::TriangleMesh box = buoyancy::makeBoxMesh(2.0, 0.6, 1.0);
    const auto poses = buoyancy::bench::waveBenchPoses(box, water, {0.8, 3.2}, {-0.25, 0.0, 0.25}, {0, 15, 30});
    REQUIRE(poses.size() == 6);
    CHECK(poses[0].id == "t0.80_dy-0.25_heel0");
    CHECK(poses[4].id == "t3.20_dy0.00_heel30");
    for (const auto& p : poses) {
        const Eigen::Vector3d c = p.pose.translation();  // the box's centre is its mesh origin
        const double height = 0.6 * std::cos(p.heelDegrees * M_PI / 180) + 1.0 * std::sin(p.heelDegrees * M_PI / 180);
        CHECK(c.x() == Approx(0).margin(1e-12));
        CHECK(c.z() == Approx(0).margin(1e-12));
        CHECK(c.y() == Approx(water.height(0, 0, p.time) + p.offsetFraction * height).margin(1e-12));
    }
}

// Fine meshes in the scaling sea: the plane through each triangle's corner heights against the curved-water model,
// error against the divergence-theorem reference and CPU time, with the estimate treeHydrostatics decides by.
TEST_CASE("waves: fine meshes, plane against curved water (manual)", "[.timing]") {
    const btGerstnerWaterSurface water(buoyancy::bench::p3Sea());
    const buoyancy::TriangleMesh boat = buoyancy::bench::loadBoatHull();
    const std::pair<const char*, buoyancy::TriangleMesh> meshes[] = {{"boat-850", boat},
                                                                     {"boat-x4", buoyancy::bench::subdivideMesh(boat)}};
    for (const auto& m : meshes) {
        const buoyancy::MeshMomentTree tree = buoyancy::buildMeshMomentTree(m.second);
        const double thickness = std::abs(tree.nodes[0].m1.trace()) / 3.0 / tree.nodes[0].area;
        std::vector<Eigen::Vector3d> verts(m.second.vertices.begin(), m.second.vertices.end());
        std::vector<Eigen::Vector3i> tris(m.second.triangles.begin(), m.second.triangles.end());
        const buoyancy_test::OracleMoments dry = buoyancy_test::oracleDryMoments(verts, tris);
        double worstPlane = 0, worstCurved = 0, estimate = 0, usPlane = 0, usCurved = 0;
        buoyancy::WaterPatch patch;
        btWaterQueryCache cache;
        const btBuoyancySettings settings;
        double lo = 1e300, hi = -1e300, radius = 0;
        for (const auto& v : verts) radius = std::max(radius, (v - dry.centroid).norm());
        for (int i = 0; i < 8; ++i) {
            const double t = 5.0 + 3.7 * i, x = 2.0 * i, z = -1.0 * i;
            Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
            pose.linear() = Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d(1, 0, 0.3).normalized()).toRotationMatrix();
            pose.translation() = Eigen::Vector3d(x, water.height(x, z, t), z) - pose.linear() * dry.centroid;
            const int nodes = btBuoyancyWaterPatchNodes(settings, radius, water.shortestWavelength());
            patch.build(water, x, z, radius, t, nodes, cache);
            estimate = std::max(estimate, patch.curvatureBound() * tree.medianLeafRadius * tree.medianLeafRadius /
                                              (8.0 * thickness));
            const Eigen::Vector3d com = pose * dry.centroid;
            buoyancy_test::WaveOracleOptions o;
            o.maxEdge = water.shortestWavelength() / 40.0;
            o.forceAndTorque = false;
            std::vector<Eigen::Vector3d> posed(verts.size());
            for (std::size_t k = 0; k < verts.size(); ++k) posed[k] = pose * verts[k];
            const auto ref = buoyancy_test::waveOracle(posed, tris, [&](double qx, double qz) { return water.height(qx, qz, t); },
                                                       com, o);
            const auto t0 = std::clock();
            const auto plane = buoyancy::vertexHydrostatics(tree.shares, pose, water, t, 1000, 9.81, com, &patch);
            const auto t1 = std::clock();
            const auto curved = buoyancy::curvedHydrostatics(m.second, tree.edges, pose, water, t, 1000, 9.81, com,
                                                             thickness, &patch);
            const auto t2 = std::clock();
            usPlane += 1e6 * double(t1 - t0) / CLOCKS_PER_SEC / 8;
            usCurved += 1e6 * double(t2 - t1) / CLOCKS_PER_SEC / 8;
            worstPlane = std::max(worstPlane, 100 * std::abs(plane.submerged_volume - ref.volume) / dry.volume);
            worstCurved = std::max(worstCurved, 100 * std::abs(curved.submerged_volume - ref.volume) / dry.volume);
        }
        std::printf("  %-9s leaf %.3f m  thickness %.3f m  estimate %.4f  plane %.4f %% (%.0f us)  curved %.4f %% (%.0f us)\n",
                    m.first, tree.medianLeafRadius, thickness, estimate, worstPlane, usPlane, worstCurved, usCurved);
    }
}

// A few scaling rows through the public API (the full set is `buoyancy bench --parts scaling`, ~45 min): boat-x4 at
// the default settings and with the plane water model, 1,000 boats, 1 and 2 threads.
TEST_CASE("scaling: 1,000 boats through the public API (manual)", "[.timing]") {
    const buoyancy::TriangleMesh boat4 = buoyancy::bench::subdivideMesh(buoyancy::bench::loadBoatHull());
    for (bool plane : {false, true}) {
        buoyancy::bench::ScalingOptions o;
        o.bodies = {1000};
        o.threads = {1, 2};
        o.windows = 3;
        o.planeWater = plane;
        o.variant = plane ? "plane-water" : "";
        std::ostringstream log;
        for (const auto& r : buoyancy::bench::runScaling(boat4, "boat-x4", o, log))
            std::printf("  %-12s bodies %d threads %d  realtime %.2f (%.2f–%.2f)  %.1f us per body-substep (buoyancy %.1f)\n",
                        plane ? "plane-water" : "default", r.bodies, r.threads, r.realtimeFactor, r.realtimeFactorMin,
                        r.realtimeFactorMax, 1e-3 * r.nsPerBodySubstepTotal, 1e-3 * r.nsPerBodySubstepBuoyancy);
    }
}
