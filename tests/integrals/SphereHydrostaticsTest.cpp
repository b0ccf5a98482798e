// sphereHydrostatics against integrals computed here by quadrature (discs stacked along y for the volume and its
// moment, a polar grid over the waterline disc for the waterplane moments) and against the half and full sphere.
#include <BulletBuoyancy/bullet/btCollisionShapeMesh.h>
#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/integrals/SphereHydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <ctime>

using namespace buoyancy;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST_CASE("sphere hydrostatics: half, full and dry spheres", "[integrals]") {
    const Eigen::Vector3d c(0.3, -0.2, 1.1);
    const double R = 0.7, rho = 1025, g = 9.81;
    const HydrostaticsResult half = sphereHydrostatics(c, R, c.y(), rho, g, c);
    CHECK(half.submerged_volume == Approx(2.0 / 3.0 * kPi * R * R * R).epsilon(1e-14));
    CHECK(half.centre_of_buoyancy.y() == Approx(c.y() - 3.0 * R / 8.0).epsilon(1e-14));  // a hemisphere's centroid
    CHECK(half.force.y() == Approx(rho * g * half.submerged_volume).epsilon(1e-14));
    CHECK(half.torque.norm() < 1e-9);  // the force passes through the centre
    CHECK(half.waterline_area == Approx(kPi * R * R).epsilon(1e-14));
    CHECK(half.wetted_area == Approx(2 * kPi * R * R).epsilon(1e-14));
    const HydrostaticsResult full = sphereHydrostatics(c, R, c.y() + 5, rho, g, Eigen::Vector3d::Zero());
    CHECK(full.submerged_volume == Approx(4.0 / 3.0 * kPi * R * R * R).epsilon(1e-14));
    CHECK((full.centre_of_buoyancy - c).norm() < 1e-12);
    CHECK(full.waterline_area == 0);
    CHECK(full.wetted_area == Approx(4 * kPi * R * R).epsilon(1e-14));
    const HydrostaticsResult dry = sphereHydrostatics(c, R, c.y() - 5, rho, g, Eigen::Vector3d::Zero());
    CHECK(dry.submerged_volume == 0);
    CHECK(dry.force.norm() == 0);
}

TEST_CASE("sphere hydrostatics: caps at any depth against quadrature", "[integrals]") {
    const Eigen::Vector3d c(-1.0, 0.4, 2.0), ref(0.5, 0.0, -0.3);
    const double R = 1.3, rho = 1000, g = 9.81;
    for (double s : {-1.2, -0.6, -0.1, 0.25, 0.9, 1.25}) {
        INFO("centre " << s << " m below the water");
        const double H = c.y() + s;
        // Discs stacked from the bottom of the sphere up to the water (midpoint rule, 20,000 slices).
        const int n = 20000;
        const double top = std::min(H, c.y() + R), bottom = c.y() - R;
        double V = 0, My = 0;
        for (int i = 0; i < n; ++i) {
            const double y = bottom + (i + 0.5) * (top - bottom) / n;
            const double area = kPi * std::max(0.0, R * R - (y - c.y()) * (y - c.y()));
            V += area * (top - bottom) / n;
            My += y * area * (top - bottom) / n;
        }
        const HydrostaticsResult r = sphereHydrostatics(c, R, H, rho, g, ref);
        CHECK(r.submerged_volume == Approx(V).epsilon(1e-6));
        CHECK(r.centre_of_buoyancy.y() == Approx(My / V).epsilon(1e-6));
        CHECK(r.centre_of_buoyancy.x() == c.x());
        const Eigen::Vector3d F(0, rho * g * V, 0);
        CHECK((r.torque - (r.centre_of_buoyancy - ref).cross(F)).norm() < 1e-6 * F.norm());
        // Waterplane: a polar grid over the disc of radius a about (c.x, c.z).
        const double a = std::sqrt(R * R - s * s);
        double A = 0, Ix = 0, Ixx = 0, Ixz = 0;
        const int nr = 400, nt = 400;
        for (int i = 0; i < nr; ++i)
            for (int j = 0; j < nt; ++j) {
                const double rr = (i + 0.5) * a / nr, t = (j + 0.5) * 2 * kPi / nt;
                const double dA = rr * (a / nr) * (2 * kPi / nt);
                const double x = c.x() + rr * std::cos(t) - ref.x(), z = c.z() + rr * std::sin(t) - ref.z();
                A += dA;
                Ix += x * dA;
                Ixx += x * x * dA;
                Ixz += x * z * dA;
            }
        CHECK(r.waterline_area == Approx(A).epsilon(1e-5));
        CHECK(r.waterplane.x == Approx(Ix).epsilon(1e-5));
        CHECK(r.waterplane.xx == Approx(Ixx).epsilon(1e-5));
        CHECK(r.waterplane.xz == Approx(Ixz).epsilon(1e-5));
        CHECK(r.wetted_area == Approx(2 * kPi * R * (std::min(H, c.y() + R) - bottom)).epsilon(1e-12));
    }
}

TEST_CASE("sphere hydrostatics: timing against the tessellated sphere and the 12-triangle box (manual)", "[.timing]") {
    // What a btSphereShape body costs in flat water, closed form against the mesh it used to float with (the default
    // curvedShapeTolerance's 17,160 triangles), and a btBoxShape's 12 triangles for scale. Thread CPU time.
    auto cpu = [] {
        timespec ts{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
        return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
    };
    const btSphereShape sphere{btScalar(0.5)};
    const TriangleMesh sphereMesh = btCollisionShapeToMesh(sphere, 1e-3);
    const MeshMomentTree sphereTree = buildMeshMomentTree(sphereMesh);
    const TriangleMesh box = makeBoxMesh(1.0, 0.4, 0.8);
    const MeshMomentTree boxTree = buildMeshMomentTree(box);
    const btFlatWaterSurface water(0.0);
    auto pose = [](int i) {
        Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
        p.linear() = Eigen::AngleAxisd(0.3 + 1e-3 * i, Eigen::Vector3d(1, 0, 0.2).normalized()).toRotationMatrix();
        p.translation() = Eigen::Vector3d(0.1, -0.1 + 1e-4 * i, 0.2);
        return p;
    };
    double sink = 0;
    const int n = 200000, nMesh = 200;
    double t0 = cpu();
    for (int i = 0; i < n; ++i) sink += sphereHydrostatics(pose(i).translation(), 0.5, 0.0, 1000, 9.81, pose(i).translation()).submerged_volume;
    const double closed = (cpu() - t0) * 1e9 / n;
    t0 = cpu();
    for (int i = 0; i < nMesh; ++i)
        sink += treeHydrostatics(sphereTree, sphereMesh, pose(i), water, 0, 1000, 9.81, pose(i).translation(), nullptr).submerged_volume;
    const double mesh = (cpu() - t0) * 1e9 / nMesh;
    t0 = cpu();
    for (int i = 0; i < n / 10; ++i)
        sink += treeHydrostatics(boxTree, box, pose(i), water, 0, 1000, 9.81, pose(i).translation(), nullptr).submerged_volume;
    const double boxNs = (cpu() - t0) * 1e9 / (n / 10);
    std::printf("  flat water, one evaluation: sphere closed form %.0f ns, sphere mesh (%zu triangles) %.0f ns, "
                "12-triangle box %.0f ns %g\n",
                closed, sphereMesh.triangles.size(), mesh, boxNs, sink * 0);
}
