// The water's acceleration Du/Dt (btWaterSurface::accelerations, design.md 2.7 "The water's acceleration"): the
// default central difference, flat water's zero, Gerstner's particle acceleration against the second difference of
// the forward parametric surface written here from its formula, the FFT ocean's fields against a difference in time.
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {
constexpr double kPi = 3.14159265358979323846;

/// A surface with only the default accelerations(): flat at 0 with the velocity field
/// u = (U sin(ω t + x), V cos(ω t) y, 0), whose ∂u/∂t is (U ω cos(ω t + x), −V ω sin(ω t) y, 0).
class OscillatingCurrent : public btWaterSurface {
public:
    static constexpr double U = 0.7, V = 0.3, Omega = 1.9;
    void heights(const double*, const double*, std::size_t n, double, double* out) const override {
        std::fill(out, out + n, 0.0);
    }
    void velocities(const double* x, const double* y, const double*, std::size_t n, double t, double* vx, double* vy,
                    double* vz) const override {
        for (std::size_t i = 0; i < n; ++i) {
            vx[i] = U * std::sin(Omega * t + x[i]);
            vy[i] = V * std::cos(Omega * t) * y[i];
            vz[i] = 0.0;
        }
    }
    void heightBounds(double, double, double, double, double, double& lo, double& hi) const override { lo = hi = 0; }
    bool isTimeVarying() const override { return true; }
};

/// The trochoidal wave's particle at rest position (x0, z0) and rest height y0 at time t, from the formula
/// (independent of the class): each wave's orbit radius decays as e^{k min(0, y0 − h)}.
void forward(const std::vector<btGerstnerWave>& ws, double h, double g, double x0, double y0, double z0, double t,
             double& x, double& y, double& z) {
    x = x0;
    z = z0;
    y = y0;
    for (const auto& w : ws) {
        const double k = 2 * kPi / w.wavelength, om = std::sqrt(g * k), e = std::exp(k * std::min(0.0, y0 - h));
        const double n = std::hypot(w.directionX, w.directionZ), dx = w.directionX / n, dz = w.directionZ / n;
        const double th = k * (dx * x0 + dz * z0) - om * t + w.phase;
        x -= w.steepness * w.amplitude * e * dx * std::sin(th);
        z -= w.steepness * w.amplitude * e * dz * std::sin(th);
        y += w.amplitude * e * std::cos(th);
    }
}
}  // namespace

TEST_CASE("water acceleration: the default is the central difference of the velocities in time", "[water]") {
    OscillatingCurrent s;
    // More points than the default's stack chunk (32), to cross a chunk boundary.
    const std::size_t n = 70;
    std::vector<double> x(n), y(n), z(n, 0.0), ax(n), ay(n), az(n);
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = 0.1 * double(i);
        y[i] = -0.05 * double(i);
    }
    const double t = 2.3;
    s.accelerations(x.data(), y.data(), z.data(), n, t, ax.data(), ay.data(), az.data());
    const double w = OscillatingCurrent::Omega;
    for (std::size_t i = 0; i < n; ++i) {
        // Truncation error of the central difference: h² ω² / 6 of the amplitude (6e-7 here).
        CHECK(ax[i] == Approx(OscillatingCurrent::U * w * std::cos(w * t + x[i])).margin(1e-6));
        CHECK(ay[i] == Approx(-OscillatingCurrent::V * w * std::sin(w * t) * y[i]).margin(1e-6));
        CHECK(az[i] == 0.0);
    }
}

TEST_CASE("water acceleration: flat water with a current has none", "[water]") {
    btFlatWaterSurface flat(0.5, 1.2, -0.4);
    const double x[2] = {1, 2}, y[2] = {-1, -3}, z[2] = {0, 5};
    double ax[2] = {9, 9}, ay[2] = {9, 9}, az[2] = {9, 9};
    flat.accelerations(x, y, z, 2, 3.0, ax, ay, az);
    for (int i = 0; i < 2; ++i) {
        CHECK(ax[i] == 0.0);
        CHECK(ay[i] == 0.0);
        CHECK(az[i] == 0.0);
    }
}

TEST_CASE("water acceleration: gerstner gives the acceleration of the particle there at the surface and below",
          "[water][gerstner]") {
    const double g = 9.81, h = 0.4;
    std::vector<btGerstnerWave> ws(3);
    ws[0] = {0.8, 40.0, 1.0, 0.0, 0.8, 0.3};
    ws[1] = {0.3, 13.0, 0.6, 0.8, 0.8, 1.7};
    ws[2] = {0.1, 5.0, -0.2, 1.0, 0.8, -2.0};
    btGerstnerWaterSurface s(ws, h, g);
    REQUIRE(s.loopFactor() > 0.1);
    double scale = 0;  // Σ A ω², m/s²
    for (const auto& w : ws) scale += w.amplitude * g * 2 * kPi / w.wavelength;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-30, 30), ut(0, 20), ud(-6, 0);
    double worstSurface = 0, worstBelow = 0;
    for (int i = 0; i < 400; ++i) {
        // Half the particles on the surface (rest height h), half below it.
        const double x0 = u(rng), z0 = u(rng), t = ut(rng), e = 1e-3, y0 = i % 2 ? h : h + ud(rng);
        double x, y, z, xa, ya, za, xb, yb, zb;
        forward(ws, h, g, x0, y0, z0, t, x, y, z);
        forward(ws, h, g, x0, y0, z0, t + e, xa, ya, za);
        forward(ws, h, g, x0, y0, z0, t - e, xb, yb, zb);
        double ax, ay, az;
        s.accelerations(&x, &y, &z, 1, t, &ax, &ay, &az);
        // The particle's acceleration: the second difference of its path.
        const double err = std::max({std::abs(ax - (xa - 2 * x + xb) / (e * e)), std::abs(ay - (ya - 2 * y + yb) / (e * e)),
                                     std::abs(az - (za - 2 * z + zb) / (e * e))});
        (i % 2 ? worstSurface : worstBelow) = std::max(i % 2 ? worstSurface : worstBelow, err);
    }
    CHECK(worstSurface < 1e-5 * scale);
    CHECK(worstBelow < 1e-5 * scale);
    // One wave of steepness 1: the particle of rest height y0 moves on a circle of radius A e^{k y0} at ω, so its
    // acceleration is A ω² e^{k y0} (Airy), wherever it is on the circle.
    const btGerstnerWave w{0.2, 20.0, 1.0, 0.0, 1.0, 0.5};
    btGerstnerWaterSurface one({w}, 0.0, g);
    const double k = 2 * kPi / 20.0, om = std::sqrt(g * k), y0 = -3.0;
    for (double t : {0.0, 0.7, 1.9}) {
        double px, py, pz, ax, ay, az;
        forward({w}, 0.0, g, 1.3, y0, 0.4, t, px, py, pz);
        one.accelerations(&px, &py, &pz, 1, t, &ax, &ay, &az);
        CHECK(std::hypot(ax, ay) == Approx(0.2 * om * om * std::exp(k * y0)).epsilon(1e-9));
        CHECK(az == Approx(0.0).margin(1e-15));
    }
}

TEST_CASE("water acceleration: the fft ocean's fields are the time derivative of its velocity fields",
          "[water][fft]") {
    btFftOceanSettings settings;
    settings.resolution = 32;
    settings.patchSize = 40.0;
    settings.windSpeed = 8.0;
    settings.choppiness = 0.0;  // rest position = query position: the velocity at a fixed point is the field's
    btFftOceanSurface s(settings);
    const double t = 5.0, e = 1e-4;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-50, 50), ud(-2, 0.5);
    double worst = 0, largest = 0;
    for (int i = 0; i < 100; ++i) {
        const double x = u(rng), y = ud(rng), z = u(rng);
        double ax, ay, az, pvx, pvy, pvz, mvx, mvy, mvz;
        s.accelerations(&x, &y, &z, 1, t, &ax, &ay, &az);
        s.velocities(&x, &y, &z, 1, t + e, &pvx, &pvy, &pvz);
        s.velocities(&x, &y, &z, 1, t - e, &mvx, &mvy, &mvz);
        const double dx = (pvx - mvx) / (2 * e), dy = (pvy - mvy) / (2 * e), dz = (pvz - mvz) / (2 * e);
        worst = std::max({worst, std::abs(ax - dx), std::abs(ay - dy), std::abs(az - dz)});
        largest = std::max({largest, std::abs(dx), std::abs(dy), std::abs(dz)});
    }
    REQUIRE(largest > 0.05);
    CHECK(worst < 1e-5 * largest);
}
