/// @file CapsuleHydrostatics.cpp
/// A capsule in flat water, sliced across its axis (design.md 2.5 "Capsules in flat water"). The slice at axial
/// coordinate s is a disc of radius ρ(s) (r on the cylinder, √(r² − u²) at distance u past a cap's centre); the water
/// crosses it along a chord at signed distance d(s) = e(s) / sin φ from its centre, where e(s) is the depth of the
/// slice's centre and φ the axis's angle from up. The wet part of the disc is the segment x < d:
///   W = ρ² (π − α) + d √(ρ² − d²), α = acos(d / ρ); its first moment along x is −⅔ (ρ² − d²)^{3/2};
///   the wet arc of the disc's rim is 2 (π − α) ρ, and the surface element of a capsule's side is r ds per radian
///   (cylinder and spheres alike), so the wetted area is ∫ 2 r (π − α) ds;
///   the chord has length 2 √(ρ² − d²) and consecutive chords lie ds / sin φ apart in the water plane, so the
///   waterline's area and moments are integrals over s of the chord's.
/// Slices wholly wet (d ≥ ρ) or dry (d ≤ −ρ) integrate in closed form. Across the band of slices the waterline cuts,
/// ρ² − d² is a quadratic in s vanishing at the band's ends (where they are not the cylinder's ends), so with
/// s = m − h cos θ the chord is h √k sin θ, a trigonometric polynomial, and every integrand is smooth in θ: an
/// N-point Gauss–Legendre rule in θ converges geometrically (to rounding at N = 16, tests/integrals).
/// When the axis is near vertical the band is thin (width ≈ 2 ρ tan φ): slices are then placed relative to where
/// the axis meets the water, so that no quantity is a difference of nearly equal ones.

#include <BulletBuoyancy/integrals/CapsuleHydrostatics.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace buoyancy {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kNodes = 20;

/// Gauss–Legendre rule on θ ∈ [0, π], with cos θ and sin θ × weight (the substitution's ds / dθ folded in).
struct AngleRule {
    std::array<double, kNodes> cosTheta{}, sinWeight{};
};

AngleRule makeRule() {
    AngleRule rule;
    for (int i = 0; i < kNodes; ++i) {
        // Newton on the Legendre polynomial P_N from Tricomi's initial guess.
        double x = std::cos(kPi * (i + 0.75) / (kNodes + 0.5)), dp = 1;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = x;
            for (int n = 2; n <= kNodes; ++n) {
                const double p2 = ((2.0 * n - 1) * x * p1 - (n - 1.0) * p0) / n;
                p0 = p1;
                p1 = p2;
            }
            dp = kNodes * (x * p1 - p0) / (x * x - 1);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        const double w = 2.0 / ((1 - x * x) * dp * dp);
        const double theta = 0.5 * kPi * (x + 1);
        rule.cosTheta[i] = std::cos(theta);
        rule.sinWeight[i] = std::sin(theta) * w * 0.5 * kPi;
    }
    return rule;
}

const AngleRule& angleRule() {
    static const AngleRule rule = makeRule();
    return rule;
}

/// The integrals over slices, accumulated piece by piece.
struct SliceSums {
    double volume = 0;     ///< ∫ W ds, m³
    double axial = 0;      ///< ∫ s W ds, m⁴
    double across = 0;     ///< ∫ (first moment of W along ŵ) ds, m⁴
    double wetted = 0;     ///< ∫ 2 r (π − α) ds, m²
    double area = 0, ax = 0, az = 0, axx = 0, axz = 0, azz = 0;  ///< waterline, about the reference (x', z')
};

/// The capsule, the water and the frame the slices are computed in.
struct Setup {
    double r = 0, h = 0;
    double cosPhi = 0, sinPhi = 0;   ///< axis against up (cos φ ≥ 0)
    bool nearVertical = false;       ///< slices measured from where the axis meets the water
    double sRef = 0;                 ///< axial coordinate slices are measured from (δ = s − sRef)
    double eRef = 0;                 ///< depth of the slice centre at sRef, m
    Eigen::Vector3d axis, across, chord;  ///< a; ŵ (in the slice, towards up); the chord's direction (horizontal)
    Eigen::Vector3d centreFromRef;        ///< capsule centre − torque reference
};

/// A piece of the capsule along its axis: the cylinder (sphere = false) or a cap's half ball centred at sCentre.
struct Piece {
    bool sphere;
    bool top;        ///< a half ball: the one at +halfHeight (its tip at sCentre + r), else at sCentre − r
    double sCentre;
    double d0, d1;  ///< the piece, δ = s − sRef
};

double radiusSquared(const Setup& c, const Piece& p, double delta) {
    if (!p.sphere) return c.r * c.r;
    const double u = delta + (c.sRef - p.sCentre);
    return c.r * c.r - u * u;
}

/// Slices [δ0, δ1] of the piece wholly under water.
void addWet(const Setup& c, const Piece& p, double d0, double d1, SliceSums& sum) {
    const double s0 = c.sRef + d0, s1 = c.sRef + d1;
    if (!p.sphere) {
        const double disc = kPi * c.r * c.r;
        sum.volume += disc * (d1 - d0);
        sum.axial += disc * 0.5 * (s1 - s0) * (s1 + s0);
    } else {
        const double r2 = c.r * c.r, u0 = s0 - p.sCentre, u1 = s1 - p.sCentre;
        const auto vol = [r2](double u) { return r2 * u - u * u * u / 3.0; };
        const auto mom = [r2](double u) { return 0.5 * r2 * u * u - 0.25 * u * u * u * u; };
        sum.volume += kPi * (vol(u1) - vol(u0));
        sum.axial += kPi * (p.sCentre * (vol(u1) - vol(u0)) + mom(u1) - mom(u0));
    }
    sum.wetted += 2.0 * kPi * c.r * (d1 - d0);
}

/// Slices [δ0, δ1] of the piece that the waterline cuts: the Gauss–Legendre rule in θ.
void addCut(const Setup& c, const Piece& p, double d0, double d1, SliceSums& sum) {
    const AngleRule& rule = angleRule();
    const double mid = 0.5 * (d0 + d1), half = 0.5 * (d1 - d0);
    const double invSin = 1.0 / c.sinPhi;
    for (int k = 0; k < kNodes; ++k) {
        const double delta = mid - half * rule.cosTheta[k];
        const double ds = half * rule.sinWeight[k];
        const double rho2 = radiusSquared(c, p, delta);
        if (!(rho2 > 0)) continue;
        const double rho = std::sqrt(rho2);
        const double d = (c.eRef - delta * c.cosPhi) * invSin;
        const double t = std::clamp(d / rho, -1.0, 1.0);
        const double wetAngle = kPi - std::acos(t);                          // π − α
        const double q = std::sqrt(std::max(0.0, (rho - d) * (rho + d)));    // half chord
        const double W = rho2 * wetAngle + d * q;
        const double s = c.sRef + delta;
        sum.volume += W * ds;
        sum.axial += s * W * ds;
        sum.across += (-2.0 / 3.0) * q * q * q * ds;
        sum.wetted += 2.0 * c.r * wetAngle * ds;
        if (q > 0) {
            const double L = 2.0 * q, w = ds * invSin;
            const Eigen::Vector3d m = c.centreFromRef + s * c.axis + d * c.across;  // chord's midpoint
            const double ux = c.chord.x(), uz = c.chord.z(), L3 = L * L * L / 12.0;
            sum.area += L * w;
            sum.ax += L * m.x() * w;
            sum.az += L * m.z() * w;
            sum.axx += (L * m.x() * m.x() + ux * ux * L3) * w;
            sum.axz += (L * m.x() * m.z() + ux * uz * L3) * w;
            sum.azz += (L * m.z() * m.z() + uz * uz * L3) * w;
        }
    }
}

/// The band of slices of the piece that the waterline cuts, δ: empty (lo ≥ hi) when none.
void cutBand(const Setup& c, const Piece& p, double& lo, double& hi) {
    lo = hi = 0;
    if (c.sinPhi == 0) return;  // slices parallel to the water: none is cut
    if (!p.sphere) {
        // |e(s)| < r sin φ with e(s) = eRef − δ cos φ.
        if (c.cosPhi == 0) {
            if (std::abs(c.eRef) < c.r * c.sinPhi) {
                lo = -std::numeric_limits<double>::infinity();
                hi = std::numeric_limits<double>::infinity();
            }
            return;
        }
        lo = (c.eRef - c.r * c.sinPhi) / c.cosPhi;
        hi = (c.eRef + c.r * c.sinPhi) / c.cosPhi;
        return;
    }
    // e(s)² < (r² − u²) sin² φ, u = s − sCentre: with e1 the depth of the ball's centre, u = e1 cos φ ± sin φ √(r² − e1²).
    const double o = c.sRef - p.sCentre;   // u at δ = 0
    const double e1 = c.eRef + o * c.cosPhi;
    const double disc = c.r * c.r - e1 * e1;
    if (!(disc > 0)) return;
    // δ = u − o; near vertical (sRef where the axis meets the water) e1 cos φ − o = −o sin² φ, without cancellation.
    const double base = c.nearVertical ? -o * c.sinPhi * c.sinPhi : e1 * c.cosPhi - o;
    const double spread = c.sinPhi * std::sqrt(disc);
    lo = base - spread;
    hi = base + spread;
}

/// Slices [a, b] cut by the waterline whose integrands have a singular point (a root of ρ² − d² that a piece's end
/// clipped off, or the cap's tip where ρ = 0) at gapA before a or gapB past b (∞: none near). The rule converges
/// slowly when such a point is close to the interval; the interval is then graded towards it, each step integrating
/// the far three quarters and keeping the near quarter, until the point is a quarter of the interval's length away
/// (at most 12 steps: what is left then holds a share of the volume under rounding).
void addBand(const Setup& c, const Piece& p, double a, double b, double gapA, double gapB, SliceSums& sum) {
    const auto gradeTowardsA = [&](double lo, double hi) {
        for (int level = 0; level < 12 && (hi - lo) > 4.0 * gapA; ++level) {
            const double split = lo + 0.25 * (hi - lo);
            addCut(c, p, split, hi, sum);
            hi = split;
        }
        addCut(c, p, lo, hi, sum);
    };
    for (int level = 0; level < 12 && (b - a) > 4.0 * gapB; ++level) {
        const double split = b - 0.25 * (b - a);
        gradeTowardsA(a, split);
        a = split;
        gapA = std::numeric_limits<double>::infinity();  // a is now inside the band
    }
    gradeTowardsA(a, b);
}

void addPiece(const Setup& c, const Piece& p, SliceSums& sum) {
    constexpr double kNone = std::numeric_limits<double>::infinity();
    double rawLo, rawHi;
    cutBand(c, p, rawLo, rawHi);
    const double lo = std::clamp(rawLo, p.d0, p.d1), hi = std::clamp(rawHi, p.d0, p.d1);
    // Without a band in the piece, lo = hi split it where the band would be (at the water itself when the slices are
    // parallel to it); each side is then wholly wet or dry.
    const auto side = [&](double a, double b) {
        if (!(b > a)) return;
        const double m = 0.5 * (a + b);
        if (c.eRef - m * c.cosPhi > 0) addWet(c, p, a, b, sum);  // the slices' centres are under water
    };
    side(p.d0, lo);
    if (hi > lo) {
        double gapLo = lo > rawLo ? lo - rawLo : kNone;  // a root clipped off by the piece's end
        double gapHi = hi < rawHi ? rawHi - hi : kNone;
        if (p.sphere) {  // the cap's tip, where the disc shrinks to a point
            if (p.top)
                gapHi = std::min(gapHi, (p.sCentre + c.r - c.sRef) - hi);
            else
                gapLo = std::min(gapLo, lo - (p.sCentre - c.r - c.sRef));
        }
        addBand(c, p, lo, hi, gapLo, gapHi, sum);
    }
    side(hi, p.d1);
}

}  // namespace

HydrostaticsResult capsuleHydrostatics(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double halfHeight,
                                       double radius, double waterHeight, double fluidDensity, double gravity,
                                       const Eigen::Vector3d& torqueReference) {
    HydrostaticsResult result;
    result.waterplane.valid = true;
    Setup c;
    c.r = radius;
    c.h = halfHeight;
    c.axis = axis.normalized();
    if (c.axis.y() < 0) c.axis = -c.axis;  // the capsule is symmetric: let the axis point up
    c.cosPhi = c.axis.y();
    c.sinPhi = std::hypot(c.axis.x(), c.axis.z());
    // Within 1e-12 rad of vertical or horizontal the axis is taken as exactly so (an error of that order, relative).
    constexpr double kAlmost = 1e-12;
    Eigen::Vector3d horizontal(1, 0, 0);  // the axis's horizontal direction
    if (c.sinPhi < kAlmost) {
        c.sinPhi = 0;
        c.cosPhi = 1;
    } else {
        horizontal = Eigen::Vector3d(c.axis.x(), 0, c.axis.z()) / c.sinPhi;
        if (c.cosPhi < kAlmost) c.cosPhi = 0;
    }
    c.across = -c.cosPhi * horizontal + Eigen::Vector3d(0, c.sinPhi, 0);
    c.chord = Eigen::Vector3d(-horizontal.z(), 0, horizontal.x());
    c.centreFromRef = centre - torqueReference;
    const double e0 = waterHeight - centre.y();  // depth of the capsule's centre
    if (c.cosPhi > c.sinPhi) {
        c.nearVertical = true;
        c.sRef = e0 / c.cosPhi;  // where the axis meets the water
        c.eRef = 0;
    } else {
        c.sRef = 0;
        c.eRef = e0;
    }
    const double end = halfHeight + radius;
    const Piece pieces[3] = {{true, false, -halfHeight, -end - c.sRef, -halfHeight - c.sRef},
                             {false, false, 0.0, -halfHeight - c.sRef, halfHeight - c.sRef},
                             {true, true, halfHeight, halfHeight - c.sRef, end - c.sRef}};
    SliceSums sum;
    for (const Piece& p : pieces) addPiece(c, p, sum);

    if (c.sinPhi == 0 && std::abs(c.sRef) < end) {
        // Vertical axis: the waterline is the disc of the slice at the water.
        const double s = c.sRef;
        const double u = std::max(0.0, std::abs(s) - halfHeight);
        const double a2 = radius * radius - u * u;
        if (a2 > 0) {
            const Eigen::Vector3d m = c.centreFromRef + s * c.axis;
            const double A = kPi * a2;
            sum.area = A;
            sum.ax = A * m.x();
            sum.az = A * m.z();
            sum.axx = A * (m.x() * m.x() + 0.25 * a2);
            sum.axz = A * m.x() * m.z();
            sum.azz = A * (m.z() * m.z() + 0.25 * a2);
        }
    }
    if (!(sum.volume > 0)) return result;  // dry
    result.submerged_volume = sum.volume;
    result.centre_of_buoyancy = centre + (sum.axial * c.axis + sum.across * c.across) / sum.volume;
    result.force = Eigen::Vector3d(0, fluidDensity * gravity * sum.volume, 0);
    result.torque = (result.centre_of_buoyancy - torqueReference).cross(result.force);
    result.wetted_area = sum.wetted;
    result.waterline_area = sum.area;
    result.waterplane.x = sum.ax;
    result.waterplane.z = sum.az;
    result.waterplane.xx = sum.axx;
    result.waterplane.xz = sum.axz;
    result.waterplane.zz = sum.azz;
    return result;
}

}  // namespace buoyancy
