// The river (btRiverSurface): a flat surface whose current follows a polyline channel. The field against its closed
// form (the speed u_max on the centreline along the tangent, 0 at the banks, 3/4 u_max at d = w/4, the blended
// direction across a bend: the bisector at the corner, continuous along the way), flat heights, the settings refused
// with their names; and in a Bullet world a crate released at rest drifting up to the current (the drag law's
// terminal state: the relative velocity goes to 0) while one beside the channel stays put. The thread-safety rule is
// checked with every other surface in ConcurrentQueriesTest.cpp.
#include "oracles/BulletTestWorld.h"

#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btRiverSurface.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

using Catch::Matchers::Contains;

namespace {

/// A river 8 m wide at level 0.25 m along +x through the origin, turning 60° towards +z at (20, 0).
btRiverSettings bendRiver(double width = 8.0, double speed = 1.5) {
    btRiverSettings s;
    s.height = 0.25;
    s.width = width;
    s.surfaceSpeed = speed;
    const double turn = 60.0 * M_PI / 180.0;
    s.centreline = {{-20.0, 0.0}, {20.0, 0.0}, {20.0 + 30.0 * std::cos(turn), 30.0 * std::sin(turn)}};
    return s;
}

struct Velocity {
    double x = 0, y = 0, z = 0;
};

Velocity velocityAt(const btWaterSurface& water, double x, double z, double y = -0.5) {
    Velocity v;
    water.velocities(&x, &y, &z, 1, 0.0, &v.x, &v.y, &v.z);
    return v;
}

}  // namespace

TEST_CASE("river: on the centreline the current is the surface speed along the tangent", "[water][river]") {
    const btRiverSurface river(bendRiver());
    for (double x : {-15.0, -3.0, 0.0, 7.5, 12.0}) {  // the first segment, away from the bend (b = w/2 = 4 m)
        const Velocity v = velocityAt(river, x, 0.0);
        CHECK(v.x == Approx(1.5).epsilon(1e-12));
        CHECK(v.y == 0.0);
        CHECK(v.z == Approx(0.0).margin(1e-12));
    }
    // The second segment, direction (cos 60°, sin 60°), away from the bend.
    const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);
    const Velocity v = velocityAt(river, 20.0 + 15.0 * c, 15.0 * s);
    CHECK(v.x == Approx(1.5 * c).epsilon(1e-12));
    CHECK(v.z == Approx(1.5 * s).epsilon(1e-12));
    // The same at every depth and time: the current is steady and uniform over depth.
    double x = 0, y = -3.0, z = 0, u = 0, w = 0, vy = 1;
    river.velocities(&x, &y, &z, 1, 42.0, &u, &vy, &w);
    CHECK(u == Approx(1.5).epsilon(1e-12));
    CHECK(vy == 0.0);
}

TEST_CASE("river: the cross-channel profile is the parabola u_max (1 - (2d/w)^2) with 0 at and beyond the banks",
          "[water][river]") {
    const double width = 8.0, umax = 1.5;
    const btRiverSurface river(bendRiver(width, umax));
    // d = w/4: 3/4 of the surface speed, on either side.
    CHECK(velocityAt(river, 0.0, width / 4).x == Approx(0.75 * umax).epsilon(1e-12));
    CHECK(velocityAt(river, 0.0, -width / 4).x == Approx(0.75 * umax).epsilon(1e-12));
    // Other distances against the closed form.
    for (double d : {0.3, 1.1, 2.5, 3.9}) {
        INFO("d = " << d);
        const double expected = umax * (1.0 - (2.0 * d / width) * (2.0 * d / width));
        CHECK(velocityAt(river, -5.0, d).x == Approx(expected).epsilon(1e-12));
        CHECK(river.speedAtDistance(d) == Approx(expected).epsilon(1e-12));
        CHECK(river.distanceToCentreline(-5.0, -d) == Approx(d).epsilon(1e-12));
    }
    // At the banks and outside the channel: still water.
    for (double d : {width / 2, width / 2 + 1e-9, 5.0, 50.0}) {
        INFO("d = " << d);
        const Velocity v = velocityAt(river, -5.0, d);
        CHECK(v.x == 0.0);
        CHECK(v.z == 0.0);
        CHECK(velocityAt(river, -5.0, -d).x == 0.0);
    }
    // The end segments continue straight: far upstream of the first point the channel is still there.
    CHECK(velocityAt(river, -100.0, 0.0).x == Approx(umax).epsilon(1e-12));
    CHECK(velocityAt(river, -100.0, width).x == 0.0);
}

TEST_CASE("river: across a bend the direction turns continuously from one tangent to the next", "[water][river]") {
    const btRiverSurface river(bendRiver());
    const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);
    // At the corner itself both segments are equally near: the bisector of the two tangents, at full speed.
    const Velocity corner = velocityAt(river, 20.0, 0.0);
    const double bx = 1.0 + c, bz = s, bn = std::hypot(bx, bz);
    CHECK(corner.x == Approx(1.5 * bx / bn).epsilon(1e-12));
    CHECK(corner.z == Approx(1.5 * bz / bn).epsilon(1e-12));
    // Walking along the centreline through the corner: the angle of the current rises monotonically from 0 to 60°,
    // with no jump (the weights are continuous in position: a step of 1 cm turns it by far less than a degree).
    double previous = 0.0, largestStep = 0.0;
    const double ds = 0.01;
    for (double t = -10.0; t <= 10.0; t += ds) {  // arc length from the corner, m
        const double x = t < 0 ? 20.0 + t : 20.0 + t * c, z = t < 0 ? 0.0 : t * s;
        double dx = 0, dz = 0;
        river.flowDirection(x, z, dx, dz);
        CHECK(std::hypot(dx, dz) == Approx(1.0).epsilon(1e-12));
        const double angle = std::atan2(dz, dx) * 180.0 / M_PI;
        CHECK(angle >= previous - 1e-9);
        largestStep = std::max(largestStep, angle - previous);
        previous = angle;
    }
    CHECK(previous == Approx(60.0).epsilon(1e-9));
    std::printf("river bend: largest turn of the current per 1 cm along the centreline %.3f degrees\n", largestStep);
    CHECK(largestStep < 0.5);
    // Across the inner bisector (the points equally near both segments, off the centreline) the direction is
    // continuous too: just either side of it, the same to 1e-6.
    // The inner side of the bend is +z here (the river turns left): the inner bisector leaves the corner along
    // the direction between −t₀ and t₁, i.e. (−1 + c, s) normalised.
    const double ux = (-1.0 + c), uz = s, un = std::hypot(ux, uz);
    const double px = 20.0 + 2.0 * ux / un, pz = 2.0 * uz / un;  // 2 m along the inner bisector
    const double nx = (1.0 + c) / bn, nz = s / bn;                // across it
    double ax = 0, az = 0, cx = 0, cz = 0;
    river.flowDirection(px - 1e-7 * nx, pz - 1e-7 * nz, ax, az);
    river.flowDirection(px + 1e-7 * nx, pz + 1e-7 * nz, cx, cz);
    CHECK(std::hypot(ax - cx, az - cz) < 1e-6);
}

TEST_CASE("river: the surface is flat at its level", "[water][river]") {
    const btRiverSurface river(bendRiver());
    std::vector<double> x, z;
    for (int i = 0; i < 50; ++i) {
        x.push_back(-30.0 + 1.3 * i);
        z.push_back(-10.0 + 0.7 * i);
    }
    std::vector<double> h(x.size(), -1.0);
    river.heights(x.data(), z.data(), x.size(), 3.0, h.data());
    for (double v : h) CHECK(v == 0.25);
    double lo = 0, hi = 0, level = 0;
    river.heightBounds(-5, -5, 5, 5, 0.0, lo, hi);
    CHECK(lo == 0.25);
    CHECK(hi == 0.25);
    CHECK(river.isFlat(0.0, level));
    CHECK(level == 0.25);
    CHECK_FALSE(river.isTimeVarying());
    CHECK_FALSE(river.prefersHeightPatch());
}

TEST_CASE("river: bad settings are refused naming the setting", "[water][river]") {
    btRiverSettings s = bendRiver();
    s.centreline.resize(1);
    CHECK_THROWS_WITH(btRiverSurface(s), Contains("centreline") && Contains("at least 2"));
    s = bendRiver();
    s.centreline[2] = s.centreline[1];
    CHECK_THROWS_WITH(btRiverSurface(s), Contains("centreline[2]: repeats centreline[1]"));
    s = bendRiver();
    s.centreline[0].x = NAN;
    CHECK_THROWS_WITH(btRiverSurface(s), Contains("centreline[0]"));
    for (double w : {0.0, -1.0, double(NAN), double(INFINITY)}) {
        s = bendRiver();
        s.width = w;
        CHECK_THROWS_WITH(btRiverSurface(s), Contains("width"));
    }
    for (double u : {-0.1, double(NAN), double(INFINITY)}) {
        s = bendRiver();
        s.surfaceSpeed = u;
        CHECK_THROWS_WITH(btRiverSurface(s), Contains("surfaceSpeed"));
    }
    s = bendRiver();
    s.height = NAN;
    CHECK_THROWS_WITH(btRiverSurface(s), Contains("height"));
    s = bendRiver();
    s.surfaceSpeed = 0.0;  // a still channel is allowed
    CHECK_NOTHROW(btRiverSurface(s));
}

TEST_CASE("river: a crate released at rest drifts up to the current and one beside the channel stays put",
          "[water][river][bullet]") {
    // A straight river along +x, 8 m wide, 1.5 m/s on the centreline; level 0.
    btRiverSettings s;
    s.width = 8.0;
    s.surfaceSpeed = 1.5;
    s.centreline = {{-100.0, 0.0}, {100.0, 0.0}};
    const btRiverSurface river(s);
    buoyancy_test::BulletTestWorld w(&river);
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.5, 1.0));
    btBuoyantBodySettings crate;
    crate.density = 500.0;  // draft 0.25 m: the centre at the water line
    const std::size_t inStream = w.add(shape, crate, buoyancy_test::makePose(btVector3(0, 0, 0)));
    const std::size_t midway = w.add(shape, crate, buoyancy_test::makePose(btVector3(0, 0, 2.0)));  // d = 2 m = w/4
    const std::size_t ashore = w.add(shape, crate, buoyancy_test::makePose(btVector3(0, 0, 10.0)));  // outside
    // The current the crate meets, averaged over its wetted footprint (|d| ≤ 0.5 m about its centre line d₀):
    // u_max (1 − (4/w²)(d₀² + 1/12)).
    const auto footprintCurrent = [&](double d0) { return 1.5 * (1.0 - 4.0 / 64.0 * (d0 * d0 + 1.0 / 12.0)); };
    std::vector<double> relative;  // along-stream relative speed of the centre crate every 5 s
    double worstV2 = 0, minSpin = 1e9, maxSpin = -1e9;  // the crate at d = w/4 over the last 10 s
    for (int k = 0; k < 60; ++k) {
        w.run(0.5);
        if (k % 10 == 9) relative.push_back(footprintCurrent(0.0) - double(w.rigid(inStream)->getLinearVelocity().x()));
        if (k >= 40) {
            // Its along-stream speed against the current over its footprint where it is now (it drifts a few cm).
            const double v = double(w.rigid(midway)->getLinearVelocity().x());
            const double d = double(w.rigid(midway)->getCenterOfMassPosition().z());
            const double spin = double(w.rigid(midway)->getAngularVelocity().y());
            worstV2 = std::max(worstV2, std::abs(v / footprintCurrent(d) - 1.0));
            minSpin = std::min(minSpin, spin);
            maxSpin = std::max(maxSpin, spin);
        }
    }
    const double v0 = double(w.rigid(inStream)->getLinearVelocity().x());
    // Half the water's vorticity at d = 2 m: ω_y = ½ ∂u_x/∂z = ½ · (−8 u_max z / w²) = −0.1875 rad/s.
    const double halfVorticity = 0.5 * (-8.0 * 1.5 * 2.0 / 64.0);
    std::printf("river: crate on the centreline %.4f m/s (current over its footprint %.4f); relative speed every 5 s:",
                v0, footprintCurrent(0.0));
    for (double r : relative) std::printf(" %.4f", r);
    std::printf("\nriver: crate at d = w/4 over the last 10 s: speed off the current over its footprint by at most "
                "%.2f %%, spin %.4f..%.4f rad/s (half the vorticity %.4f), ends at z = %.4f\n",
                100.0 * worstV2, minSpin, maxSpin, halfVorticity, double(w.rigid(midway)->getCenterOfMassPosition().z()));
    // The relative velocity decays towards 0 (the radiation damping and the quadratic drag act on it only): 1 % of
    // the current after 5 s, a hundredth of that after 10 s.
    CHECK(relative.front() > 0);
    CHECK(relative.front() < 0.02 * footprintCurrent(0.0));
    for (std::size_t k = 1; k < relative.size(); ++k) CHECK(std::abs(relative[k]) < 0.001 * footprintCurrent(0.0));
    // Off the centreline the shear turns the crate: a free body in a shear flow spins at half the water's vorticity
    // (a sphere exactly; the square crate's rate varies a little with its angle: measured within 1 %). It drifts at
    // the current over its footprint (measured within 0.6 %; a spinning box presents its faces at every angle).
    CHECK(minSpin == Approx(halfVorticity).epsilon(0.03));
    CHECK(maxSpin == Approx(halfVorticity).epsilon(0.03));
    CHECK(worstV2 < 0.015);
    // Nothing pushed the crates across the channel (the centre one by symmetry; the other by less than a few cm).
    CHECK(std::abs(double(w.rigid(inStream)->getCenterOfMassPosition().z())) < 0.01);
    // Outside the channel the water is still: that crate has not moved.
    const btVector3 p = w.rigid(ashore)->getCenterOfMassPosition();
    CHECK(std::abs(double(p.x())) < 1e-3);
    CHECK(double(p.z()) == Approx(10.0).margin(1e-3));
    CHECK(double(w.rigid(ashore)->getLinearVelocity().length()) < 1e-3);
}

TEST_CASE("river: the world's water query reports the local current", "[water][river][bullet]") {
    btRiverSettings s;
    s.height = 0.5;
    s.width = 8.0;
    s.surfaceSpeed = 1.5;
    s.centreline = {{-50.0, 0.0}, {50.0, 0.0}};
    const btRiverSurface river(s);
    buoyancy_test::BulletTestWorld w(&river);
    const btWaterQueryResult inChannel = w.water().queryWater(btVector3(3, 0, 2));  // d = w/4, 0.5 m deep
    CHECK(inChannel.inWater);
    CHECK(double(inChannel.depth) == Approx(0.5).margin(1e-6));
    CHECK(double(inChannel.velocity.x()) == Approx(0.75 * 1.5).epsilon(1e-6));
    CHECK(double(inChannel.velocity.y()) == 0.0);
    CHECK(double(inChannel.velocity.z()) == Approx(0.0).margin(1e-6));
    const btWaterQueryResult onBank = w.water().queryWater(btVector3(3, 0, 6));  // beside the channel: still
    CHECK(onBank.inWater);
    CHECK(onBank.velocity.length() == 0);
}
