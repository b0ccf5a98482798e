// boxHydrostatics against the polyhedral oracle (an independent clip of the box's 12 triangles, written in the test
// tree), the rectangle's closed-form waterplane moments, and a grid quadrature over the waterline of tilted boxes.
#include <BulletBuoyancy/integrals/BoxHydrostatics.h>

#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

using namespace buoyancy;
using namespace buoyancy_test;

namespace {

// The box's corners and its 12 outward triangles, written here (not the library's makeBoxMesh).
void boxTriangles(const Eigen::Vector3d& h, std::vector<Eigen::Vector3d>& v, std::vector<Eigen::Vector3i>& t) {
    v.clear();
    for (int k = 0; k < 8; ++k)
        v.emplace_back((k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(), (k & 4) ? h.z() : -h.z());
    t = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
         {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
}

// Waterplane integrals of the tilted box's cut by y = H, by the midpoint rule on an n × n grid over a square that
// holds it: a point is inside when its box coordinates are within the half extents.
struct GridMoments {
    double area = 0, x = 0, z = 0, xx = 0, xz = 0, zz = 0;
};
GridMoments gridWaterplane(const Eigen::Isometry3d& pose, const Eigen::Vector3d& h, double H,
                           const Eigen::Vector3d& ref, int n) {
    GridMoments m;
    const double half = h.norm();
    const double step = 2 * half / n, dA = step * step;
    const Eigen::Isometry3d inv = pose.inverse();
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Eigen::Vector3d p(pose.translation().x() - half + (i + 0.5) * step, H,
                                    pose.translation().z() - half + (j + 0.5) * step);
            const Eigen::Vector3d q = inv * p;
            if (std::abs(q.x()) > h.x() || std::abs(q.y()) > h.y() || std::abs(q.z()) > h.z()) continue;
            const double x = p.x() - ref.x(), z = p.z() - ref.z();
            m.area += dA;
            m.x += x * dA;
            m.z += z * dA;
            m.xx += x * x * dA;
            m.xz += x * z * dA;
            m.zz += z * z * dA;
        }
    return m;
}

}  // namespace

TEST_CASE("box hydrostatics: an upright box against the rectangle's closed forms", "[integrals]") {
    const Eigen::Vector3d h(0.6, 0.25, 0.4);  // a 1.2 × 0.5 × 0.8 m box
    const double rho = 1025, g = 9.81;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(1.5, 0.1, -2.0);
    const Eigen::Vector3d ref(1.0, 0.0, -1.0);
    for (double draft : {0.05, 0.25, 0.4999}) {
        INFO("draft " << draft << " m");
        const double H = 0.1 - 0.25 + draft;
        const HydrostaticsResult r = boxHydrostatics(pose, h, H, rho, g, ref);
        CHECK(r.submerged_volume == Approx(1.2 * 0.8 * draft).epsilon(1e-13));
        CHECK(r.centre_of_buoyancy.x() == Approx(1.5).epsilon(1e-13));
        CHECK(r.centre_of_buoyancy.y() == Approx(0.1 - 0.25 + draft / 2).epsilon(1e-12));
        CHECK(r.centre_of_buoyancy.z() == Approx(-2.0).epsilon(1e-13));
        CHECK(r.force.y() == Approx(rho * g * 1.2 * 0.8 * draft).epsilon(1e-13));
        CHECK(r.wetted_area == Approx(1.2 * 0.8 + 2 * (1.2 + 0.8) * draft).epsilon(1e-13));
        // The waterline, a 1.2 × 0.8 rectangle centred 0.5 m along x and −1 m along z from the reference.
        const double A = 1.2 * 0.8, dx = 0.5, dz = -1.0;
        CHECK(r.waterline_area == Approx(A).epsilon(1e-13));
        CHECK(r.waterplane.valid);
        CHECK(r.waterplane.x == Approx(A * dx).epsilon(1e-12));
        CHECK(r.waterplane.z == Approx(A * dz).epsilon(1e-12));
        CHECK(r.waterplane.xx == Approx(A * (dx * dx + 1.2 * 1.2 / 12)).epsilon(1e-12));
        CHECK(r.waterplane.zz == Approx(A * (dz * dz + 0.8 * 0.8 / 12)).epsilon(1e-12));
        CHECK(r.waterplane.xz == Approx(A * dx * dz).epsilon(1e-12));
    }
    const HydrostaticsResult dry = boxHydrostatics(pose, h, -1.0, rho, g, ref);
    CHECK(dry.submerged_volume == 0);
    CHECK(dry.force.norm() == 0);
    const HydrostaticsResult under = boxHydrostatics(pose, h, 3.0, rho, g, ref);
    CHECK(under.submerged_volume == Approx(1.2 * 0.5 * 0.8).epsilon(1e-14));
    CHECK((under.centre_of_buoyancy - pose.translation()).norm() < 1e-14);
    CHECK(under.waterline_area == 0);
    CHECK(under.wetted_area == Approx(2 * (1.2 * 0.5 + 1.2 * 0.8 + 0.5 * 0.8)).epsilon(1e-13));
}

// Edges within rounding of level, lying at the water: where a crossing on them is ill-conditioned (the height changes
// by far less along the edge than the rounding of the heights), the cut must still stay on the face. Upright boxes
// tilted by tiny angles, the water at their bottom, their top and in between: the upright closed form holds to the
// tilt's first-order effect (the volume changes by at most the footprint's area × the tilt × the box's diagonal).
TEST_CASE("box hydrostatics: nearly level edges at the water stay exact", "[integrals]") {
    const Eigen::Vector3d h(0.6, 0.25, 0.4);
    const double A = 1.2 * 0.8, V = 1.2 * 0.5 * 0.8, L = 2 * h.norm();
    for (double tilt : {1e-19, 1e-17, 1e-15, 1e-12, 1e-9})
        for (int axis = 0; axis < 3; axis += 2)
            for (double draft : {0.0, 1e-17, 1e-9, 0.25, 0.5 - 1e-12, 0.5}) {
                INFO("tilt " << tilt << " rad about axis " << axis << ", draft " << draft << " m");
                Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
                pose.linear() = Eigen::AngleAxisd(tilt, axis == 0 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ())
                                    .toRotationMatrix();
                pose.translation() = Eigen::Vector3d(0.3, 0.7, -0.2);
                const double H = 0.7 - 0.25 + draft;
                const HydrostaticsResult r = boxHydrostatics(pose, h, H, 1000, 9.81, pose.translation());
                const double slack = A * tilt * L + 1e-14;
                CHECK(std::abs(r.submerged_volume - A * draft) <= slack);
                CHECK(r.submerged_volume >= 0);
                CHECK(r.submerged_volume <= V * (1 + 1e-14));
                if (r.submerged_volume > 1e-6) {
                    CHECK(std::abs(r.centre_of_buoyancy.x() - 0.3) <= 1e-9 + tilt * L);
                    CHECK(std::abs(r.centre_of_buoyancy.y() - (0.7 - 0.25 + draft / 2)) <= 1e-9 + tilt * L);
                    // The whole footprint, unless the water lies within the tilt's reach of the bottom or the top
                    // (there the plane cuts a tilted face, and the waterline is a part of the footprint).
                    if (std::min(draft, 0.5 - draft) > tilt * L)
                        CHECK(std::abs(r.waterline_area - A) <= 1e-12);
                    CHECK(r.waterline_area <= A * (1 + 1e-12));
                }
                CHECK(r.wetted_area <= 2 * (1.2 * 0.5 + 1.2 * 0.8 + 0.5 * 0.8) * (1 + 1e-14));
            }
}

TEST_CASE("box hydrostatics: a cube on its edge holds half its volume when cut through its centre", "[integrals]") {
    const Eigen::Vector3d h(0.5, 0.5, 0.5);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const HydrostaticsResult r = boxHydrostatics(pose, h, 0.0, 1000, 9.81, Eigen::Vector3d::Zero());
    CHECK(r.submerged_volume == Approx(0.5).epsilon(1e-14));
    // The lower half is a triangular prism with its apex 1/√2 below the centre: centroid a third of the way up.
    CHECK(r.centre_of_buoyancy.y() == Approx(-std::sqrt(0.5) / 3).epsilon(1e-13));
    CHECK(r.waterline_area == Approx(std::sqrt(2.0)).epsilon(1e-13));  // √2 × 1 rectangle
    CHECK(r.wetted_area == Approx(2 + 2 * 0.5).epsilon(1e-13));         // two whole faces and two half faces
}

TEST_CASE("box hydrostatics: random attitudes and depths against the polyhedral oracle", "[integrals]") {
    std::mt19937 rng(20261128);
    std::uniform_real_distribution<double> u(-1, 1), size(0.05, 2.0);
    std::vector<Eigen::Vector3d> v;
    std::vector<Eigen::Vector3i> t;
    for (int trial = 0; trial < 300; ++trial) {
        const Eigen::Vector3d h(size(rng), size(rng), size(rng));
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
        pose.translation() = Eigen::Vector3d(3 * u(rng), u(rng), 3 * u(rng));
        const double H = pose.translation().y() + 1.1 * h.norm() * u(rng);
        const Eigen::Vector3d ref(u(rng), u(rng), u(rng));
        boxTriangles(h, v, t);
        const std::vector<Eigen::Vector3d> posed = oraclePose(v, pose);
        const OracleMoments o = oracleSubmergedMoments(posed, t, H);
        const HydrostaticsResult r = boxHydrostatics(pose, h, H, 1000, 9.81, ref);
        INFO("trial " << trial << " half extents " << h.transpose() << " water " << H);
        const double scale = h.norm(), V = 8 * h.prod();
        CHECK(std::abs(r.submerged_volume - o.volume) <= 1e-12 * V);
        if (o.volume > 1e-6 * V) {
            CHECK((r.centre_of_buoyancy - o.centroid).norm() <= 1e-10 * scale);
            CHECK((r.torque - (o.centroid - ref).cross(Eigen::Vector3d(0, 9810 * o.volume, 0))).norm() <=
                  1e-9 * 9810 * V * (scale + ref.norm() + pose.translation().norm()));
        }
        CHECK(std::abs(r.waterline_area - oracleCapArea(posed, t, H)) <= 1e-12 * scale * scale);
    }
}

TEST_CASE("box hydrostatics: waterplane moments of tilted boxes against a grid over the waterline", "[integrals]") {
    const Eigen::Vector3d h(0.7, 0.3, 0.45);
    const Eigen::Vector3d ref(0.2, 0.0, -0.4);
    const int n = 1200;
    for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 0.5, 0.3), Eigen::Vector3d(0.2, 1, -0.7)}) {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = Eigen::AngleAxisd(0.6, axis.normalized()).toRotationMatrix();
        pose.translation() = Eigen::Vector3d(0.5, 0.05, 0.1);
        const HydrostaticsResult r = boxHydrostatics(pose, h, 0.0, 1000, 9.81, ref);
        const GridMoments m = gridWaterplane(pose, h, 0.0, ref, n);
        INFO("axis " << axis.transpose());
        // The grid's error lies along the rim: about one cell's width times the perimeter.
        const double cell = 2 * h.norm() / n, tol = cell * 2 * (2 * h.x() + 2 * h.z() + 2 * h.y());
        CHECK(r.waterline_area == Approx(m.area).margin(tol));
        CHECK(r.waterplane.x == Approx(m.x).margin(2 * tol));
        CHECK(r.waterplane.z == Approx(m.z).margin(2 * tol));
        CHECK(r.waterplane.xx == Approx(m.xx).margin(4 * tol));
        CHECK(r.waterplane.xz == Approx(m.xz).margin(4 * tol));
        CHECK(r.waterplane.zz == Approx(m.zz).margin(4 * tol));
        CHECK(std::abs(m.xz) > 10 * tol);
    }
}
