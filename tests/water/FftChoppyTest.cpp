// The choppy FFT ocean's inversion against the forward parametric surface. The forward map is
// rebuilt here from the documented convention (btFftOceanSurface.h): the point at rest x₀ moves to
// x = x₀ − λ D(x₀), y = h + η(x₀), where D is the Riesz transform of the elevation, D = Σ (−i k/|k|) η̂(k) e^{ik·x}
// (zero and Nyquist modes excluded). D is computed here by a direct DFT of the elevation field (no FFT, no
// library code), so the height the library inverts at x must equal the elevation at the rest point.
#include <catch2/catch.hpp>

#include <BulletBuoyancy/water/btFftOceanSurface.h>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Riesz transform of an N×N periodic field (index j·N + i at (i·L/N, j·L/N)) by direct DFT.
void rieszByDft(const std::vector<double>& eta, int N, std::vector<double>& dx, std::vector<double>& dz) {
    using C = std::complex<double>;
    std::vector<C> hat(std::size_t(N) * N);
    for (int n = 0; n < N; ++n)
        for (int m = 0; m < N; ++m) {
            C s = 0;
            for (int j = 0; j < N; ++j)
                for (int i = 0; i < N; ++i) s += eta[std::size_t(j) * N + i] * std::polar(1.0, -2 * kPi * (double(m) * i + double(n) * j) / N);
            hat[std::size_t(n) * N + m] = s / double(N * N);
        }
    dx.assign(std::size_t(N) * N, 0.0);
    dz.assign(std::size_t(N) * N, 0.0);
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            C sx = 0, sz = 0;
            for (int n = 0; n < N; ++n)
                for (int m = 0; m < N; ++m) {
                    const int km = m < N / 2 ? m : m - N, kn = n < N / 2 ? n : n - N;  // signed mode numbers
                    if ((km == 0 && kn == 0) || km == -N / 2 || kn == -N / 2) continue;
                    const double len = std::hypot(double(km), double(kn));
                    const C e = hat[std::size_t(n) * N + m] * std::polar(1.0, 2 * kPi * (double(m) * i + double(n) * j) / N);
                    sx += C(0, -km / len) * e;
                    sz += C(0, -kn / len) * e;
                }
            dx[std::size_t(j) * N + i] = sx.real();
            dz[std::size_t(j) * N + i] = sz.real();
        }
}

/// Bilinear periodic lookup of an N×N field of spacing h at (x, z) (the documented interpolation).
double bilinear(const std::vector<double>& f, int N, double h, double x, double z) {
    const double u = x / h, v = z / h;
    const double fu = std::floor(u), fv = std::floor(v), a = u - fu, b = v - fv;
    auto w = [&](double i) { return int(((long long)i % N + N) % N); };
    const int i0 = w(fu), i1 = w(fu + 1), j0 = w(fv), j1 = w(fv + 1);
    return (1 - b) * ((1 - a) * f[std::size_t(j0) * N + i0] + a * f[std::size_t(j0) * N + i1]) +
           b * ((1 - a) * f[std::size_t(j1) * N + i0] + a * f[std::size_t(j1) * N + i1]);
}

}  // namespace

TEST_CASE("fft ocean: choppy inversion agrees with the forward parametric surface, choppiness 0 is plain", "[water][fft]") {
    btFftOceanSettings s;
    s.resolution = 32;
    s.patchSize = 64;
    s.windSpeed = 8;
    s.windDirectionX = 0.8;
    s.windDirectionZ = 0.6;
    s.height = 0.7;
    s.seed = 5;
    const double t = 3.3, L = s.patchSize, h = L / s.resolution;
    const int N = s.resolution;
    btFftOceanSettings plainSettings = s;
    plainSettings.choppiness = 0;
    const btFftOceanSurface plain(plainSettings);
    s.choppiness = 0.8;
    const btFftOceanSurface choppy(s);

    // Choppiness moves points sideways; it does not change the elevation at the rest points.
    const std::vector<double> eta = plain.elevationField(t);
    const std::vector<double> etaChoppy = choppy.elevationField(t);
    REQUIRE(eta.size() == std::size_t(N) * N);
    for (std::size_t i = 0; i < eta.size(); ++i) CHECK(etaChoppy[i] == Approx(eta[i]).margin(1e-12));

    std::vector<double> Dx, Dz;
    rieszByDft(eta, N, Dx, Dz);
    // Precondition: the forward map is one-to-one (Jacobian of x₀ − λ D positive at every node: no loops).
    double minJ = 1e9;
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) {
            auto at = [&](const std::vector<double>& f, int a, int b) { return f[std::size_t((b + N) % N) * N + (a + N) % N]; };
            const double dxdx = (at(Dx, i + 1, j) - at(Dx, i - 1, j)) / (2 * h), dxdz = (at(Dx, i, j + 1) - at(Dx, i, j - 1)) / (2 * h);
            const double dzdx = (at(Dz, i + 1, j) - at(Dz, i - 1, j)) / (2 * h), dzdz = (at(Dz, i, j + 1) - at(Dz, i, j - 1)) / (2 * h);
            minJ = std::min(minJ, (1 - s.choppiness * dxdx) * (1 - s.choppiness * dzdz) - s.choppiness * s.choppiness * dxdz * dzdx);
        }
    INFO("min Jacobian of the forward map " << minJ);
    REQUIRE(minJ > 0.2);

    // 1) Rest points on the grid nodes: the forward point's inverted height is the node's elevation.
    double worstNode = 0, maxShift = 0;
    for (int j = 0; j < N; j += 3)
        for (int i = 0; i < N; i += 3) {
            const std::size_t id = std::size_t(j) * N + i;
            const double x = i * h - s.choppiness * Dx[id], z = j * h - s.choppiness * Dz[id];
            maxShift = std::max(maxShift, std::hypot(x - i * h, z - j * h));
            worstNode = std::max(worstNode, std::abs(choppy.height(x, z, t) - (s.height + eta[id])));
        }
    // 2) Rest points anywhere: the forward surface of the (bilinear) fields.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, L);
    double worstAny = 0, worstPlain = 0;
    for (int k = 0; k < 200; ++k) {
        const double x0 = u(rng), z0 = u(rng);
        const double x = x0 - s.choppiness * bilinear(Dx, N, h, x0, z0), z = z0 - s.choppiness * bilinear(Dz, N, h, x0, z0);
        const double y = s.height + bilinear(eta, N, h, x0, z0);
        worstAny = std::max(worstAny, std::abs(choppy.height(x, z, t) - y));
        // Choppiness 0 is the plain height field: the height at (x0, z0) is the elevation there.
        worstPlain = std::max(worstPlain, std::abs(plain.height(x0, z0, t) - y));
    }
    INFO("largest horizontal shift " << maxShift << " m; worst residual at nodes " << worstNode << " m, anywhere "
                                     << worstAny << " m; plain " << worstPlain << " m");
    CHECK(maxShift > 0.05);  // the choppy surface really moved sideways
    CHECK(worstNode < 1e-6);
    CHECK(worstAny < 1e-6);
    CHECK(worstPlain < 1e-12);
}
