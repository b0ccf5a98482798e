// Grid and FFT ocean surfaces: bilinear exactness, wrap/clamp, bounds; FFT mean level, variance
// against the spectrum's integral (Parseval, spectrum written here independently), time derivative,
// determinism with a seed, choppy inversion.
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST_CASE("grid: bilinear reproduces a plane, periodic wraps, clamped holds the edge", "[water][grid]") {
    const int nx = 7, nz = 5;
    const double sp = 0.5, ox = -1.0, oz = 2.0;
    std::vector<double> hs(nx * nz);
    auto plane = [](double x, double z) { return 0.3 * x - 0.2 * z + 1.0; };
    for (int j = 0; j < nz; ++j)
        for (int i = 0; i < nx; ++i) hs[j * nx + i] = plane(ox + i * sp, oz + j * sp);
    btGridWaterSurface clamped(nx, nz, sp, ox, oz, hs, false);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> ux(ox, ox + (nx - 1) * sp), uz(oz, oz + (nz - 1) * sp);
    for (int k = 0; k < 100; ++k) {
        const double x = ux(rng), z = uz(rng);
        CHECK(clamped.height(x, z, 0) == Approx(plane(x, z)).margin(1e-12));
    }
    // Outside: the nearest edge value.
    CHECK(clamped.height(ox - 10, oz + 1.0, 0) == Approx(plane(ox, oz + 1.0)).margin(1e-12));
    CHECK(clamped.height(ox + 100, oz + 100, 0) == Approx(plane(ox + (nx - 1) * sp, oz + (nz - 1) * sp)).margin(1e-12));
    // Periodic: period nx·sp, nz·sp.
    btGridWaterSurface periodic(nx, nz, sp, ox, oz, hs, true);
    for (int k = 0; k < 50; ++k) {
        const double x = ux(rng), z = uz(rng);
        CHECK(periodic.height(x + 3 * nx * sp, z - 2 * nz * sp, 0) == Approx(periodic.height(x, z, 0)).margin(1e-12));
    }
    // Between the last sample and the wrapped first one: linear between them.
    const double xl = ox + (nx - 1) * sp + 0.25 * sp;
    CHECK(periodic.height(xl, oz, 0) == Approx(0.75 * hs[nx - 1] + 0.25 * hs[0]).margin(1e-12));
    // Bounds contain every bilinear value in the region.
    double lo, hi;
    periodic.heightBounds(0.0, 2.5, 1.0, 3.0, 0, lo, hi);
    for (int k = 0; k < 100; ++k) {
        const double x = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const double z = std::uniform_real_distribution<double>(2.5, 3.0)(rng);
        const double h = periodic.height(x, z, 0);
        CHECK(h >= lo - 1e-12);
        CHECK(h <= hi + 1e-12);
    }
    // Updating every frame; bad sizes rejected.
    std::vector<double> flat(nx * nz, 4.0);
    periodic.setHeights(flat);
    CHECK(periodic.height(0.3, 2.7, 0) == 4.0);
    CHECK_THROWS_WITH(periodic.setHeights(std::vector<double>(3, 0.0)), Catch::Contains("heights"));
    CHECK_THROWS_WITH(btGridWaterSurface(1, 5, sp, 0, 0, std::vector<double>(5, 0.0), true), Catch::Contains("2x2"));
    CHECK_THROWS_WITH(btGridWaterSurface(2, 2, -1, 0, 0, std::vector<double>(4, 0.0), true), Catch::Contains("spacing"));
}

namespace {
/// Phillips directional density as documented in btFftOceanSurface.h, written here independently.
double phillips(double kx, double kz, double U, double g, double alpha, double wx, double wz) {
    const double k = std::hypot(kx, kz);
    if (k == 0) return 0;
    const double c = (kx * wx + kz * wz) / k;
    if (c <= 0) return 0;
    const double L = U * U / g;
    return 0.5 * alpha * std::exp(-1 / (k * L * k * L)) / (k * k * k) * (2 / kPi) * c * c / k;
}

double meanAndVariance(const std::vector<double>& f, double& var) {
    double m = 0;
    for (double v : f) m += v;
    m /= double(f.size());
    var = 0;
    for (double v : f) var += (v - m) * (v - m);
    var /= double(f.size());
    return m;
}
}  // namespace

TEST_CASE("fft ocean: mean level h and variance = integral of the spectrum (Parseval)", "[water][fft]") {
    btFftOceanSettings s;
    s.resolution = 64;
    s.patchSize = 50.0;
    s.windSpeed = 5.0;
    s.windDirectionX = 0.6;
    s.windDirectionZ = 0.8;
    s.height = 1.5;
    // The expected variance: Σ over the patch's wavevectors (zero mode and Nyquist row/column excluded)
    // of Ψ(k) Δk², the discrete form of ∫Ψ d²k.
    const double dk = 2 * kPi / s.patchSize;
    double expected = 0;
    for (int m = -s.resolution / 2 + 1; m < s.resolution / 2; ++m)
        for (int n = -s.resolution / 2 + 1; n < s.resolution / 2; ++n)
            expected += phillips(m * dk, n * dk, s.windSpeed, s.gravity, s.phillipsAlpha, 0.6, 0.8) * dk * dk;
    // ... which is close to the continuous integral α L_w²/4 when the patch resolves the spectrum.
    const double Lw = s.windSpeed * s.windSpeed / s.gravity;
    CHECK(expected == Approx(s.phillipsAlpha * Lw * Lw / 4).epsilon(0.1));
    double varSum = 0;
    const int seeds = 12;
    for (int seed = 1; seed <= seeds; ++seed) {
        s.seed = seed;
        btFftOceanSurface ocean(s);
        const std::vector<double> eta = ocean.elevationField(2.0 + seed);
        double var;
        CHECK(meanAndVariance(eta, var) == Approx(0.0).margin(1e-12));
        varSum += var;
        // The queried heights carry the mean level h exactly on the grid nodes.
        CHECK(ocean.height(0.0, 0.0, 2.0 + seed) == Approx(s.height + eta[0]).margin(1e-12));
        CHECK(ocean.spectrumDensity(0.3, 0.4) == Approx(phillips(0.3, 0.4, s.windSpeed, s.gravity, s.phillipsAlpha, 0.6, 0.8)));
    }
    INFO("mean variance " << varSum / seeds << " m^2, spectrum integral " << expected << " m^2");
    CHECK(varSum / seeds == Approx(expected).epsilon(0.1));
}

TEST_CASE("fft ocean: deterministic with a seed, evolves in time, velocity = d(eta)/dt", "[water][fft]") {
    btFftOceanSettings s;
    s.resolution = 32;
    s.patchSize = 40.0;
    s.windSpeed = 6.0;
    s.seed = 42;
    btFftOceanSurface a(s), b(s);
    const std::vector<double> x{0.3, 5.1, -12.7}, z{1.9, -3.3, 30.2};
    std::vector<double> ha(3), hb(3), hc(3);
    a.heights(x.data(), z.data(), 3, 1.25, ha.data());
    b.heights(x.data(), z.data(), 3, 1.25, hb.data());
    for (int i = 0; i < 3; ++i) CHECK(ha[i] == hb[i]);
    s.seed = 43;
    btFftOceanSurface c(s);
    c.heights(x.data(), z.data(), 3, 1.25, hc.data());
    CHECK(hc[0] != ha[0]);
    // Periodic with the patch.
    CHECK(a.height(0.3 + 40.0, 1.9 - 80.0, 1.25) == Approx(ha[0]).margin(1e-9));
    // Changes in time; the cache gives the same value when t comes back.
    CHECK(a.height(0.3, 1.9, 2.0) != ha[0]);
    CHECK(a.height(0.3, 1.9, 1.25) == ha[0]);
    // Vertical surface velocity at a grid node = central difference of the elevation in time.
    const double t = 3.0, e = 1e-4, xn = 5 * 40.0 / 32, zn = 7 * 40.0 / 32, y = 0.0;
    double vx, vy, vz;
    a.velocities(&xn, &y, &zn, 1, t, &vx, &vy, &vz);
    const double d = (a.height(xn, zn, t + e) - a.height(xn, zn, t - e)) / (2 * e);
    CHECK(vy == Approx(d).margin(1e-6));
    // Choppy: the height at the displaced position of a node equals that node's elevation (inversion).
    s.choppiness = 0.8;
    btFftOceanSurface ch(s);
    // The inverted height stays within the (unchoppy) field range given by the bounds.
    double lo, hi;
    ch.heightBounds(0, 0, 1, 1, t, lo, hi);
    for (int k = 0; k < 50; ++k) {
        const double hx = ch.height(0.37 * k, 0.91 * k, t);
        CHECK(hx >= lo - 1e-12);
        CHECK(hx <= hi + 1e-12);
    }
    CHECK_THROWS_WITH(btFftOceanSurface([] { btFftOceanSettings p; p.resolution = 7; return p; }()),
                      Catch::Contains("resolution"));
    CHECK_THROWS_WITH(btFftOceanSurface([] { btFftOceanSettings p; p.windSpeed = 0; return p; }()),
                      Catch::Contains("wind_speed"));
}
