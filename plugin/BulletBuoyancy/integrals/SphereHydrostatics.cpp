/// @file SphereHydrostatics.cpp
/// The spherical cap (design.md 2.5 "Spheres in flat water"). Volume of a cap of height h on a sphere of radius R:
/// V = π h² (3R − h)/3; its centroid from the sphere's centre: 3 (2R − h)² / (4 (3R − h)) (both by integrating
/// discs of radius² R² − z² over the cap). Flat water: the pressure force on the wetted surface is ρ g V straight up
/// through the cap's centroid (Archimedes, the surface closed by the waterline disc, on which the pressure is zero).

#include <BulletBuoyancy/integrals/SphereHydrostatics.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace buoyancy {

HydrostaticsResult sphereHydrostatics(const Eigen::Vector3d& centre, double radius, double waterHeight,
                                      double fluidDensity, double gravity, const Eigen::Vector3d& torqueReference) {
    constexpr double kPi = 3.14159265358979323846;
    HydrostaticsResult r;
    const double R = radius;
    const double s = waterHeight - centre.y();  // depth of the centre below the water (negative: above)
    const double h = std::clamp(R + s, 0.0, 2.0 * R);
    r.waterplane.valid = true;
    if (h <= 0.0) return r;  // dry
    r.submerged_volume = kPi * h * h * (3.0 * R - h) / 3.0;
    const double below = 3.0 * (2.0 * R - h) * (2.0 * R - h) / (4.0 * (3.0 * R - h));
    r.centre_of_buoyancy = centre - Eigen::Vector3d(0, below, 0);
    r.force = Eigen::Vector3d(0, fluidDensity * gravity * r.submerged_volume, 0);
    r.torque = (r.centre_of_buoyancy - torqueReference).cross(r.force);
    r.wetted_area = 2.0 * kPi * R * h;
    const double a2 = std::max(0.0, R * R - s * s);
    if (h < 2.0 * R && a2 > 0.0) {
        const double A = kPi * a2;
        const double dx = centre.x() - torqueReference.x(), dz = centre.z() - torqueReference.z();
        r.waterline_area = A;
        r.waterplane.x = A * dx;  // disc: ∫x' dA = A x̄', ∫x'² dA = A (x̄'² + a²/4), ∫x'z' dA = A x̄' z̄'
        r.waterplane.z = A * dz;
        r.waterplane.xx = A * (dx * dx + 0.25 * a2);
        r.waterplane.xz = A * dx * dz;
        r.waterplane.zz = A * (dz * dz + 0.25 * a2);
    }
    return r;
}

}  // namespace buoyancy
