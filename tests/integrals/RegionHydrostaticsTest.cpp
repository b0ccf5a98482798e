// regionHydrostatics: a body straddling two bounded waters takes each part of its surface from its own water.
// Oracle: a 2 × 1 × 1 m box across the vertical boundary x = 0 of two flat waters at different levels and densities,
// integrated by hand: each region's part is a prism (volume = area × depth), the pressure on a vertical face of depth
// D is ρ g D²/2 per metre of width acting D/3 above the bottom, on a horizontal face ρ g D × its area.
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>

namespace {

/// The box [minX, maxX] × [minY, ∞) × [minZ, maxZ] as a region (no top face), world = water frame.
buoyancy::WaterRegion openTopBox(const btWaterSurface& water, double density, double minX, double maxX, double minY,
                                 double minZ, double maxZ) {
    buoyancy::WaterRegion r;
    r.water = &water;
    r.fluidDensity = density;
    const Eigen::Vector3d n[5] = {-Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY(),
                                  -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};
    const double d[5] = {-minX, maxX, -minY, -minZ, maxZ};
    for (int k = 0; k < 5; ++k) {
        r.normal[k] = n[k];
        r.offset[k] = d[k];
    }
    r.planeCount = 5;
    return r;
}

}  // namespace

TEST_CASE("regionHydrostatics: a box across two flat waters of different levels, against the hand integral",
          "[integrals][waters]") {
    const double g = 9.81;
    const double h1 = 0.2, rho1 = 1000.0;   // left water (x < 0)
    const double h2 = -0.1, rho2 = 1025.0;  // right water (x > 0)
    const btFlatWaterSurface left(h1), right(h2);
    const buoyancy::WaterRegion regions[2] = {openTopBox(left, rho1, -10, 0, -5, -5, 5),
                                              openTopBox(right, rho2, 0, 10, -5, -5, 5)};
    // Box 2 × 1 × 1 centred at the origin: x in [-1, 1], bottom y = -0.5, z in [-0.5, 0.5].
    const buoyancy::TriangleMesh box = buoyancy::makeBoxMesh(2.0, 1.0, 1.0);
    const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d ref = Eigen::Vector3d::Zero();
    const auto h = buoyancy::regionHydrostatics(box, pose, regions, 2, 0.0, g, ref);

    const double D1 = h1 + 0.5, D2 = h2 + 0.5;  // depths of the bottom in each water
    const double V1 = 1.0 * 1.0 * D1, V2 = 1.0 * 1.0 * D2;
    CHECK(h.submerged_volume == Approx(V1 + V2).epsilon(1e-12));
    // Centre of buoyancy: the prisms' centroids (-0.5, -0.5 + D1/2, 0) and (0.5, -0.5 + D2/2, 0), volume-weighted.
    CHECK(h.centre_of_buoyancy.x() == Approx((V1 * -0.5 + V2 * 0.5) / (V1 + V2)).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.y() == Approx((V1 * (-0.5 + D1 / 2) + V2 * (-0.5 + D2 / 2)) / (V1 + V2)).epsilon(1e-12));
    CHECK(h.centre_of_buoyancy.z() == Approx(0.0).margin(1e-12));
    // Vertical: each part of the bottom pressed by its own water, ρ g D × 1 m².
    const double Fy1 = rho1 * g * D1, Fy2 = rho2 * g * D2;
    CHECK(h.force.y() == Approx(Fy1 + Fy2).epsilon(1e-12));
    // Horizontal: the left end face (x = -1) pushed to +x by the left water, the right end to −x by the right water.
    const double FxL = rho1 * g * D1 * D1 / 2, FxR = -rho2 * g * D2 * D2 / 2;
    CHECK(h.force.x() == Approx(FxL + FxR).epsilon(1e-12));
    CHECK(h.force.z() == Approx(0.0).margin(1e-9));
    // Torque about the origin, τ_z = x F_y − y F_x: the bottom forces at x = ∓0.5, the end forces D/3 above the bottom.
    const double yL = -0.5 + D1 / 3, yR = -0.5 + D2 / 3;
    const double tauZ = -0.5 * Fy1 + 0.5 * Fy2 - yL * FxL - yR * FxR;
    CHECK(h.torque.z() == Approx(tauZ).epsilon(1e-12));
    CHECK(h.torque.x() == Approx(0.0).margin(1e-9));
    CHECK(h.torque.y() == Approx(0.0).margin(1e-9));
    // Wetted area: bottom 2 m², end faces D1 and D2, side faces 2 × (D1 + D2) × 1 m.
    CHECK(h.wetted_area == Approx(2.0 + D1 + D2 + 2 * (D1 + D2)).epsilon(1e-12));
    CHECK(h.waterline_area == Approx(2.0).epsilon(1e-12));
}

TEST_CASE("regionHydrostatics: a body inside one region matches clippedHydrostatics, and outside every region it is dry",
          "[integrals][waters]") {
    const btFlatWaterSurface water(0.1);
    const buoyancy::WaterRegion inside = openTopBox(water, 1000.0, -10, 10, -5, -10, 10);
    const buoyancy::TriangleMesh mesh = buoyancy::makeSphereMesh(0.5, 24, 13);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(0.3, -0.05, 0.2)).rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
    const Eigen::Vector3d ref(0.3, -0.1, 0.2);
    const auto a = buoyancy::regionHydrostatics(mesh, pose, &inside, 1, 0.0, 9.81, ref);
    const auto b = buoyancy::clippedHydrostatics(mesh, pose, water, 0.0, 1000.0, 9.81, ref);
    CHECK(a.submerged_volume == Approx(b.submerged_volume).epsilon(1e-12));
    CHECK((a.force - b.force).norm() <= 1e-9 * b.force.norm());
    CHECK((a.torque - b.torque).norm() <= 1e-9 * b.force.norm());
    CHECK(a.waterplane.valid);
    const buoyancy::WaterRegion away = openTopBox(water, 1000.0, 5, 10, -5, -10, 10);
    const auto dry = buoyancy::regionHydrostatics(mesh, pose, &away, 1, 0.0, 9.81, ref);
    CHECK(dry.submerged_volume == 0.0);
    CHECK(dry.force.norm() == 0.0);
}
