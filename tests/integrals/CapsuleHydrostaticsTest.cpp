// capsuleHydrostatics against closed forms (a lying and a standing capsule, a capsule of no length is a sphere),
// against the symmetry of the capsule through its centre, and at arbitrary tilts against an independent integration
// written here: horizontal sections of the capsule, each integrated row by row, the row's extent being the union of
// the three exact intervals where the row is within r of the two end centres and of the axis between them.
#include <BulletBuoyancy/integrals/CapsuleHydrostatics.h>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>

using namespace buoyancy;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Capsule {
    Eigen::Vector3d centre, axis;
    double h, r;
    double volume() const { return kPi * r * r * (2 * h + 4.0 / 3.0 * r); }
    double surface() const { return 2 * kPi * r * 2 * h + 4 * kPi * r * r; }
};

/// The z-interval of the line (x, y, ·) within r of the capsule's segment; false when it misses.
bool rowExtent(const Capsule& k, double x, double y, double& z0, double& z1) {
    z0 = std::numeric_limits<double>::infinity();
    z1 = -z0;
    const auto ball = [&](const Eigen::Vector3d& b) {
        const double q = k.r * k.r - (x - b.x()) * (x - b.x()) - (y - b.y()) * (y - b.y());
        if (q < 0) return;
        z0 = std::min(z0, b.z() - std::sqrt(q));
        z1 = std::max(z1, b.z() + std::sqrt(q));
    };
    ball(k.centre + k.h * k.axis);
    ball(k.centre - k.h * k.axis);
    // Within r of the axis line: |q|² − (q·a)² ≤ r², q = p − c, a quadratic α z² + β z + γ ≤ 0.
    const Eigen::Vector3d q0(x - k.centre.x(), y - k.centre.y(), -k.centre.z());
    const Eigen::Vector3d ez(0, 0, 1);
    const double az = k.axis.z(), qa = q0.dot(k.axis);
    const double alpha = 1 - az * az, beta = 2 * (q0.z() - qa * az), gamma = q0.squaredNorm() - qa * qa - k.r * k.r;
    double lo, hi;
    if (alpha > 1e-14) {
        const double disc = beta * beta - 4 * alpha * gamma;
        if (disc < 0) return z1 >= z0;
        lo = (-beta - std::sqrt(disc)) / (2 * alpha);
        hi = (-beta + std::sqrt(disc)) / (2 * alpha);
    } else {  // the axis is along z: the row is within r of the line everywhere or nowhere
        if (gamma > 0) return z1 >= z0;
        lo = -1e300;
        hi = 1e300;
    }
    // ... and projecting onto the segment: −h ≤ qa + z az ≤ h.
    if (std::abs(az) > 1e-14) {
        double t0 = (-k.h - qa) / az, t1 = (k.h - qa) / az;
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
    } else if (std::abs(qa) > k.h) {
        return z1 >= z0;
    }
    if (hi > lo) {
        z0 = std::min(z0, lo);
        z1 = std::max(z1, hi);
    }
    return z1 >= z0;
}

/// Area, ∫x, ∫z, ∫x², ∫xz, ∫z² of the horizontal section at height y (about the origin).
struct Section {
    double area = 0, x = 0, z = 0, xx = 0, xz = 0, zz = 0;
};

Section section(const Capsule& k, double y, int rows) {
    Section s;
    const double reach = k.h * std::abs(k.axis.x()) + k.r;
    const double xm = k.centre.x(), xh = reach;
    // x = xm − xh cos θ, midpoint rule in θ: the rows crowd where the section's ends are.
    for (int i = 0; i < rows; ++i) {
        const double theta = kPi * (i + 0.5) / rows;
        const double x = xm - xh * std::cos(theta), dx = xh * std::sin(theta) * kPi / rows;
        double z0, z1;
        if (!rowExtent(k, x, y, z0, z1)) continue;
        const double len = z1 - z0, zm = 0.5 * (z0 + z1);
        s.area += len * dx;
        s.x += x * len * dx;
        s.z += zm * len * dx;
        s.xx += x * x * len * dx;
        s.xz += x * zm * len * dx;
        s.zz += (z1 * z1 * z1 - z0 * z0 * z0) / 3.0 * dx;
    }
    return s;
}

/// Submerged volume and its first moment by stacking the sections from the capsule's bottom to the water.
void stackSections(const Capsule& k, double water, int levels, int rows, double& volume, Eigen::Vector3d& moment) {
    const double bottom = k.centre.y() - k.h * std::abs(k.axis.y()) - k.r;
    const double top = std::min(water, k.centre.y() + k.h * std::abs(k.axis.y()) + k.r);
    volume = 0;
    moment.setZero();
    if (top <= bottom) return;
    const double ym = 0.5 * (bottom + top), yh = 0.5 * (top - bottom);
    for (int j = 0; j < levels; ++j) {
        const double theta = kPi * (j + 0.5) / levels;
        const double y = ym - yh * std::cos(theta), dy = yh * std::sin(theta) * kPi / levels;
        const Section s = section(k, y, rows);
        volume += s.area * dy;
        moment += Eigen::Vector3d(s.x, y * s.area, s.z) * dy;
    }
}

HydrostaticsResult evaluate(const Capsule& k, double water, const Eigen::Vector3d& reference = Eigen::Vector3d::Zero()) {
    return capsuleHydrostatics(k.centre, k.axis, k.h, k.r, water, 1000.0, 9.81, reference);
}

}  // namespace

TEST_CASE("capsule hydrostatics: a lying capsule is a circular segment along its length and a spherical cap",
          "[integrals]") {
    const double r = 0.3, h = 0.5;
    for (double e : {-0.29, -0.17, -0.05, 0.0, 0.013, 0.11, 0.23, 0.299}) {  // depth of the axis below the water
        const Capsule k{Eigen::Vector3d(0.4, -e, -0.7), Eigen::Vector3d(0, 0, 1), h, r};
        const HydrostaticsResult res = evaluate(k, 0.0, k.centre);
        const double capHeight = r + e;
        const double cap = kPi * capHeight * capHeight * (3 * r - capHeight) / 3;
        const double segment = r * r * (kPi - std::acos(e / r)) + e * std::sqrt(r * r - e * e);
        const double volume = cap + 2 * h * segment;
        INFO("depth of the axis " << e);
        CHECK(res.submerged_volume == Approx(volume).epsilon(1e-13));
        // Below the axis by: the segment's centroid ⅔ (r² − e²)^{3/2} / segment, the cap's 3 (2r − c)² / (4 (3r − c)).
        const double below = (2 * h * (2.0 / 3.0) * std::pow(r * r - e * e, 1.5) +
                              cap * 3 * (2 * r - capHeight) * (2 * r - capHeight) / (4 * (3 * r - capHeight))) /
                             volume;
        CHECK(res.centre_of_buoyancy.y() == Approx(k.centre.y() - below).epsilon(1e-12));
        CHECK(std::abs(res.centre_of_buoyancy.x() - k.centre.x()) < 1e-14);
        CHECK(std::abs(res.centre_of_buoyancy.z() - k.centre.z()) < 1e-14);
        const double chord = 2 * std::sqrt(r * r - e * e);
        CHECK(res.waterline_area == Approx(chord * 2 * h + kPi * (r * r - e * e)).epsilon(1e-13));
        // About the centre: a rectangle 2h long (along z) and chord = 2a wide, and a half disc of radius a on each end
        // (∫w over a half disc 2a³/3, ∫w² πa⁴/8, w from its straight side).
        const double a2 = r * r - e * e, a = std::sqrt(a2);
        CHECK(res.waterplane.xx == Approx(2 * h * chord * chord * chord / 12 + kPi * a2 * a2 / 4).epsilon(1e-12));
        CHECK(res.waterplane.zz == Approx(chord * std::pow(2 * h, 3) / 12 + kPi * a2 * h * h + 8.0 / 3.0 * h * a * a2 +
                                          kPi * a2 * a2 / 4)
                                       .epsilon(1e-12));
        CHECK(std::abs(res.waterplane.xz) < 1e-14);
        CHECK(res.wetted_area == Approx(2 * r * (kPi - std::acos(e / r)) * 2 * h + 2 * kPi * r * capHeight).epsilon(1e-13));
    }
}

TEST_CASE("capsule hydrostatics: a standing capsule is discs stacked to the water", "[integrals]") {
    const double r = 0.3, h = 0.5;
    // Volume below axial coordinate s (from the centre, up): a half ball, the cylinder, the upper half ball.
    const auto below = [&](double s, double& volume, double& moment) {
        volume = moment = 0;
        const auto ball = [&](double centre, double u0, double u1) {
            volume += kPi * ((r * r * u1 - u1 * u1 * u1 / 3) - (r * r * u0 - u0 * u0 * u0 / 3));
            moment += kPi * (centre * ((r * r * u1 - u1 * u1 * u1 / 3) - (r * r * u0 - u0 * u0 * u0 / 3)) +
                             (r * r * u1 * u1 / 2 - u1 * u1 * u1 * u1 / 4) - (r * r * u0 * u0 / 2 - u0 * u0 * u0 * u0 / 4));
        };
        if (s > -h - r) ball(-h, -r, std::min(s + h, 0.0));
        if (s > -h) {
            const double top = std::min(s, h);
            volume += kPi * r * r * (top + h);
            moment += kPi * r * r * (top * top - h * h) / 2;
        }
        if (s > h) ball(h, 0.0, std::min(s - h, r));
    };
    for (double s : {-0.9, -0.7, -0.5, -0.2, 0.0, 0.37, 0.5, 0.61, 0.79, 0.9}) {
        for (double sign : {1.0, -1.0}) {  // either way up
            const Capsule k{Eigen::Vector3d(0.2, 1.0, 0.1), Eigen::Vector3d(0, sign, 0), h, r};
            const HydrostaticsResult res = evaluate(k, 1.0 + s, k.centre);
            double volume, moment;
            below(s, volume, moment);
            INFO("water at axial coordinate " << s);
            if (volume == 0) {
                CHECK(res.submerged_volume == 0);
                continue;
            }
            CHECK(res.submerged_volume == Approx(volume).epsilon(1e-13));
            CHECK(res.centre_of_buoyancy.y() == Approx(1.0 + moment / volume).epsilon(1e-13));
            CHECK(std::abs(res.centre_of_buoyancy.x() - 0.2) < 1e-14);
            CHECK(res.torque.norm() < 1e-9);
            const double wetLength = std::clamp(s + h + r, 0.0, 2 * (h + r));
            CHECK(res.wetted_area == Approx(2 * kPi * r * wetLength).epsilon(1e-13));
            const double u = std::max(0.0, std::abs(s) - h), a2 = std::max(0.0, r * r - u * u);
            CHECK(res.waterline_area == Approx(kPi * a2).margin(1e-15));
            CHECK(res.waterplane.xx == Approx(kPi * a2 * a2 / 4).margin(1e-15));
        }
    }
}

TEST_CASE("capsule hydrostatics: a capsule of no length is a sphere's cap at any tilt", "[integrals]") {
    const double R = 0.45;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 200; ++i) {
        const Capsule k{Eigen::Vector3d(u(rng), u(rng), u(rng)), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized(),
                        0.0, R};
        const double water = k.centre.y() + 1.1 * R * u(rng);
        const HydrostaticsResult res = evaluate(k, water, k.centre);
        const double c = std::clamp(R + water - k.centre.y(), 0.0, 2 * R);  // cap height
        const double volume = kPi * c * c * (3 * R - c) / 3;
        CHECK(res.submerged_volume == Approx(volume).margin(1e-14 * R * R * R));
        if (volume > 1e-6) {
            const double below = 3 * (2 * R - c) * (2 * R - c) / (4 * (3 * R - c));
            CHECK((res.centre_of_buoyancy - (k.centre - Eigen::Vector3d(0, below, 0))).norm() < 1e-12 * R);
        }
        CHECK(res.wetted_area == Approx(2 * kPi * R * c).margin(1e-14 * R * R));
    }
}

TEST_CASE("capsule hydrostatics: what is wet at one level is what is dry at the level mirrored through the centre",
          "[integrals]") {
    // The capsule is symmetric through its centre: the wet part at water height H is the mirror image of the dry
    // part at 2 c_y − H. So V(H) + V(H') = V, their moments about c cancel, and the wetted areas add to the surface.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    double worstVolume = 0, worstMoment = 0, worstArea = 0;
    for (int i = 0; i < 3000; ++i) {
        Eigen::Vector3d axis(u(rng), u(rng), u(rng));
        if (i % 5 == 0) axis.y() *= 1e-6;                      // nearly lying
        if (i % 7 == 0) axis.x() *= 1e-6, axis.z() *= 1e-6;    // nearly standing
        const Capsule k{Eigen::Vector3d(u(rng), u(rng), u(rng)), axis.normalized(), 0.6 * (u(rng) + 1), 0.3};
        const double water = k.centre.y() + (k.h + k.r) * u(rng);
        const HydrostaticsResult a = evaluate(k, water), b = evaluate(k, 2 * k.centre.y() - water);
        const double L = k.h + k.r;
        worstVolume = std::max(worstVolume, std::abs(a.submerged_volume + b.submerged_volume - k.volume()) / k.volume());
        const Eigen::Vector3d ma = a.submerged_volume * (a.centre_of_buoyancy - k.centre);
        const Eigen::Vector3d mb = b.submerged_volume * (b.centre_of_buoyancy - k.centre);
        worstMoment = std::max(worstMoment, (ma - mb).norm() / (k.volume() * L));
        worstArea = std::max(worstArea, std::abs(a.wetted_area + b.wetted_area - k.surface()) / k.surface());
    }
    INFO("worst relative: volume " << worstVolume << ", moment " << worstMoment << ", wetted area " << worstArea);
    CHECK(worstVolume < 1e-13);
    CHECK(worstMoment < 1e-13);
    CHECK(worstArea < 1e-13);
}

TEST_CASE("capsule hydrostatics: tilted capsules against horizontal sections integrated row by row", "[integrals]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 5; ++i) {
        const Capsule k{Eigen::Vector3d(0.3 * u(rng), 0.2 * u(rng), 0.3 * u(rng)),
                        Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized(), 0.5, 0.3};
        const double water = 0.5 * u(rng);
        const Eigen::Vector3d reference(0.1, 0.0, -0.2);
        const HydrostaticsResult res = evaluate(k, water, reference);
        double volume;
        Eigen::Vector3d moment;
        stackSections(k, water, 1200, 1200, volume, moment);
        INFO("pose " << i << ": volume " << res.submerged_volume << " against " << volume);
        CHECK(res.submerged_volume == Approx(volume).epsilon(2e-6));
        CHECK((res.centre_of_buoyancy - moment / volume).norm() < 2e-6 * (k.h + k.r));
        const Section s = section(k, water, 20000);
        const double x0 = reference.x(), z0 = reference.z(), scale = (k.h + k.r) * (k.h + k.r);
        CHECK(res.waterline_area == Approx(s.area).epsilon(1e-6));
        CHECK(res.waterplane.x == Approx(s.x - x0 * s.area).margin(1e-6 * scale));
        CHECK(res.waterplane.z == Approx(s.z - z0 * s.area).margin(1e-6 * scale));
        CHECK(res.waterplane.xx == Approx(s.xx - 2 * x0 * s.x + x0 * x0 * s.area).margin(1e-6 * scale));
        CHECK(res.waterplane.xz == Approx(s.xz - x0 * s.z - z0 * s.x + x0 * z0 * s.area).margin(1e-6 * scale));
        CHECK(res.waterplane.zz == Approx(s.zz - 2 * z0 * s.z + z0 * z0 * s.area).margin(1e-6 * scale));
        CHECK(res.force.y() == Approx(1000.0 * 9.81 * res.submerged_volume).epsilon(1e-14));
        CHECK((res.torque - (res.centre_of_buoyancy - reference).cross(res.force)).norm() < 1e-9 * res.force.norm());
    }
}
