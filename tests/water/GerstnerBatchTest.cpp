// Batch Gerstner queries: heights, velocities and their warm-started forms against an independent
// evaluation written here in long double — the trochoid forward map x = x0 − Σ Q A k̂ sin θ, y = h + Σ A cos θ,
// inverted by plain fixed-point iteration (a contraction of factor Σ Q A k, no Newton), and the velocity as an
// 8th-order central finite difference in time of each wave's particle displacement (Airy decay below h).
// Required: 1e-12 of Σ A (heights, m) and of Σ A ω (velocities, m/s), for steep seas and far points.
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <catch2/catch.hpp>

#include <cfenv>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {
constexpr long double kPiL = 3.141592653589793238462643383279502884L;

/// The waves in long double, from the user-facing parameters (not from the class).
struct Oracle {
    struct W {
        long double a, k, om, dx, dz, qa, ph;
    };
    std::vector<W> w;
    long double h, ampSum = 0, velSum = 0, loop = 0;
    Oracle(const std::vector<btGerstnerWave>& ws, double height, double g) : h(height) {
        for (const auto& v : ws) {
            W o;
            o.a = v.amplitude;
            o.k = 2 * kPiL / v.wavelength;
            o.om = std::sqrt((long double)g * o.k);
            const long double n = std::hypot((long double)v.directionX, (long double)v.directionZ);
            o.dx = v.directionX / n;
            o.dz = v.directionZ / n;
            o.qa = (long double)v.steepness * v.amplitude;
            o.ph = v.phase;
            ampSum += o.a;
            velSum += o.a * o.om;
            loop += o.qa * o.k;
            w.push_back(o);
        }
    }
    long double phase(const W& v, long double x0, long double z0, long double t) const {
        return v.k * (v.dx * x0 + v.dz * z0) - v.om * t + v.ph;
    }
    /// Rest position of the particle at (x, z): x0 ← x + Σ Q A d sin θ(x0) until it stops moving.
    void invert(long double x, long double z, long double t, long double& x0, long double& z0) const {
        x0 = x;
        z0 = z;
        const long double floor = 8 * std::numeric_limits<long double>::epsilon() * (1 + std::fabs(x) + std::fabs(z));
        for (int it = 0; it < 200000; ++it) {
            long double nx = x, nz = z;
            for (const W& v : w) {
                const long double s = std::sin(phase(v, x0, z0, t));
                nx += v.qa * v.dx * s;
                nz += v.qa * v.dz * s;
            }
            const long double step = std::fabs(nx - x0) + std::fabs(nz - z0);
            x0 = nx;
            z0 = nz;
            if (step <= floor) break;
        }
    }
    /// Height of the particle at rest position (x0, z0).
    long double heightAt(long double x0, long double z0, long double t) const {
        long double y = h;
        for (const W& v : w) y += v.a * std::cos(phase(v, x0, z0, t));
        return y;
    }
    long double height(long double x, long double z, long double t) const {
        long double x0, z0;
        invert(x, z, t, x0, z0);
        return heightAt(x0, z0, t);
    }
    /// d/dt of each wave's displacement of the particle under (x, z), by finite differences in time, times
    /// e^{k min(0, y − h)}. Phases at t + τ are θ(t) − ω τ (θ(t) rounded once, so large phases cost nothing).
    void velocity(long double x, long double y, long double z, long double t, long double out[3]) const {
        long double x0, z0;
        invert(x, z, t, x0, z0);
        velocityAt(x0, z0, y, t, out);
    }
    void velocityAt(long double x0, long double z0, long double y, long double t, long double out[3]) const {
        const long double e = 1e-2L;  // s
        // 8th-order central first-derivative stencil at ±1..4 e
        const long double c[4] = {4.0L / 5, -1.0L / 5, 4.0L / 105, -1.0L / 280};
        out[0] = out[1] = out[2] = 0;
        const long double depth = std::min((long double)0, y - h);
        for (const W& v : w) {
            const long double th = phase(v, x0, z0, t), decay = std::exp(v.k * depth);
            long double d[3] = {0, 0, 0};
            for (int j = 1; j <= 4; ++j) {
                const long double ap = th - v.om * (j * e), am = th + v.om * (j * e);  // θ(t + je), θ(t − je)
                d[0] += c[j - 1] * (-v.qa * v.dx * std::sin(ap) + v.qa * v.dx * std::sin(am));
                d[1] += c[j - 1] * (v.a * std::cos(ap) - v.a * std::cos(am));
                d[2] += c[j - 1] * (-v.qa * v.dz * std::sin(ap) + v.qa * v.dz * std::sin(am));
            }
            for (int k = 0; k < 3; ++k) out[k] += decay * d[k] / e;
        }
    }
};

/// The benchmark's scaling sea (bullet_examples/benchmark/Scaling.cpp p3Sea), Σ Q A k ≈ 0.22.
std::vector<btGerstnerWave> p3Sea() {
    return {{1.0, 60.0, 1.0, 0.0, 0.5, 0.0},
            {0.6, 35.0, 0.8, 0.6, 0.5, 1.3},
            {0.35, 20.0, -0.3, 1.0, 0.5, 2.1},
            {0.2, 10.0, 0.6, -0.8, 0.5, 0.4}};
}

/// Waves scaled to Σ Q A k = loop (steep for loop → 1), short ones included.
std::vector<btGerstnerWave> steepSea(double loop, int count) {
    std::vector<btGerstnerWave> ws;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    double s = 0;
    for (int i = 0; i < count; ++i) {
        const double lambda = 4.0 + 50.0 * u(rng), a = 0.04 * lambda * (0.3 + 0.7 * u(rng)), ang = 6.283 * u(rng);
        ws.push_back({a, lambda, std::cos(ang), std::sin(ang), 1.0, 6.283 * u(rng)});
        s += a * 6.283185307179586 / lambda;
    }
    for (auto& w : ws) w.steepness = loop / s;
    return ws;
}

struct Errors {
    double h = 0, v = 0;
};

/// Worst height and velocity errors of the batch queries at the given points, relative to Σ A and Σ A ω.
Errors checkBatch(const btGerstnerWaterSurface& s, const Oracle& o, const std::vector<double>& x,
                  const std::vector<double>& y, const std::vector<double>& z, double t) {
    const std::size_t n = x.size();
    std::vector<double> h(n), vx(n), vy(n), vz(n);
    s.heights(x.data(), z.data(), n, t, h.data());
    s.velocities(x.data(), y.data(), z.data(), n, t, vx.data(), vy.data(), vz.data());
    Errors e;
    for (std::size_t i = 0; i < n; ++i) {
        long double x0, z0, v[3];
        o.invert(x[i], z[i], t, x0, z0);
        e.h = std::max(e.h, double(std::fabs(h[i] - o.heightAt(x0, z0, t)) / o.ampSum));
        o.velocityAt(x0, z0, y[i], t, v);
        e.v = std::max({e.v, double(std::fabs(vx[i] - v[0]) / o.velSum), double(std::fabs(vy[i] - v[1]) / o.velSum),
                        double(std::fabs(vz[i] - v[2]) / o.velSum)});
    }
    return e;
}
}  // namespace

TEST_CASE("gerstner batch: the finite-difference oracle reproduces Airy's |u| = A ω e^{k y}", "[water][gerstner]") {
    // The test's own oracle against the textbook: one wave of steepness 1 has a circular orbit of radius A.
    const btGerstnerWave w{0.3, 25.0, 1.0, 0.0, 1.0, 0.7};
    const Oracle o({w}, 0.0, 9.81);
    const long double k = 2 * kPiL / 25.0L, om = std::sqrt(9.81L * k);
    long double v[3];
    o.velocity(3.1L, -2.0L, 1.7L, 4.2L, v);
    CHECK(double(std::hypot(v[0], v[1]) / (0.3L * om * std::exp(-2.0L * k))) == Approx(1.0).epsilon(1e-13));
}

TEST_CASE("gerstner batch: cold heights and velocities equal the independent evaluation to 1e-12", "[water][gerstner]") {
    struct Sea {
        const char* name;
        std::vector<btGerstnerWave> waves;
    };
    const std::vector<Sea> seas = {{"scaling sea", p3Sea()},
                                   {"steep, 4 waves, sum QAk = 0.95", steepSea(0.95, 4)},
                                   {"moderate, 20 waves (heap scratch)", steepSea(0.5, 20)},
                                   {"one wave, sum QAk = 0.97", steepSea(0.97, 1)}};
    for (const Sea& sea : seas) {
        const double h = 0.4, g = 9.81;
        const btGerstnerWaterSurface s(sea.waves, h, g);
        const Oracle o(sea.waves, h, g);
        std::mt19937 rng(5);
        for (double range : {60.0, 1e4}) {  // near the origin, and far (phases up to ~1e4 rad: range reduction)
            std::uniform_real_distribution<double> u(-range, range), uy(-3.0, 1.0), ut(0, 100);
            std::vector<double> x(51), y(51), z(51);  // odd: the last point runs alone in its SIMD pair
            for (std::size_t i = 0; i < x.size(); ++i) {
                x[i] = u(rng);
                z[i] = u(rng);
                y[i] = h + uy(rng);  // above and below the mean level (decay 1 and < 1)
            }
            const double t = ut(rng);
            const Errors e = checkBatch(s, o, x, y, z, t);
            // Conditioning of double inputs: the phase θ = k d·x₀ − ω t + φ is only known to ~ulp(θ), and near the
            // crest of a sea that almost loops the inversion amplifies a phase error by 1/(1 − Σ Q A k). Any double
            // evaluation then errs by about ulp(θ_max) / (1 − Σ Q A k) of the amplitude: 1e-12 holds unless that is
            // larger (here only the single wave with Σ Q A k = 0.97 at |x| ~ 1e4, where it is ~1e-10).
            double thetaMax = 0;
            for (const auto& v : o.w) thetaMax = std::max(thetaMax, double(v.k * 2 * range + v.om * t + std::fabs(v.ph)));
            const double conditioning = std::numeric_limits<double>::epsilon() * thetaMax / double(1 - o.loop);
            const double tol = std::max(1e-12, conditioning);
            INFO(sea.name << ", |x| up to " << range << ": height error " << e.h << " of sum A, velocity error "
                          << e.v << " of sum A omega (tolerance " << tol << ")");
            CHECK(e.h <= tol);
            CHECK(e.v <= tol);
        }
    }
}

TEST_CASE("gerstner batch: warm-started queries over substeps equal the independent evaluation", "[water][gerstner]") {
    // A body-like query pattern at 240 substeps/s: 8×8 height nodes on a fixed world lattice that shifts by one
    // cell now and then (WaterPatch), and 32 drag probes moving with a drifting, turning body. The clock jumps
    // back 1 s at substep 100 (a reset) and forward 0.5 s at 150 (a pause): the warm start's extrapolation in
    // time must then be ignored, never trusted.
    for (double loop : {0.22, 0.9}) {
        const auto ws = loop < 0.5 ? p3Sea() : steepSea(loop, 4);
        const double h = -0.3, g = 9.81;
        const btGerstnerWaterSurface s(ws, h, g);
        const Oracle o(ws, h, g);
        btWaterQueryCache nodeCache, probeCache;
        std::vector<double> nx(64), nz(64), nh(64), px(32), py(32), pz(32), vx(32), vy(32), vz(32);
        double worstH = 0, worstV = 0;
        for (int step = 0; step < 240; ++step) {
            const double jump = step >= 150 ? 0.5 : (step >= 100 ? -1.0 : 0.0);
            const double t = 7.0 + step / 240.0 + jump, cx = 1.5 * t + 5000.0, cz = -0.7 * t, a = 0.3 * t, cell = 0.8;
            const double ox = (std::floor(cx / cell) - 4) * cell, oz = (std::floor(cz / cell) - 4) * cell;
            for (int k = 0; k < 64; ++k) {
                nx[k] = ox + cell * (k % 8);
                nz[k] = oz + cell * (k / 8);
            }
            for (int k = 0; k < 32; ++k) {
                const double bx = -2.0 + 0.5 * (k % 8), bz = -1.0 + 0.6 * (k / 8);
                px[k] = cx + std::cos(a) * bx - std::sin(a) * bz;
                pz[k] = cz + std::sin(a) * bx + std::cos(a) * bz;
                py[k] = h - 0.05 * k;
            }
            s.heightsCached(nx.data(), nz.data(), 64, t, nh.data(), nodeCache);
            s.velocitiesCached(px.data(), py.data(), pz.data(), 32, t, vx.data(), vy.data(), vz.data(), probeCache);
            // The oracle is slow: every 8th substep, and the substeps right after the jumps.
            if (step % 8 != 0 && step != 239 && step != 101 && step != 151) continue;
            for (int k = 0; k < 64; ++k)
                worstH = std::max(worstH, double(std::fabs(nh[k] - o.height(nx[k], nz[k], t)) / o.ampSum));
            for (int k = 0; k < 32; ++k) {
                long double v[3];
                o.velocity(px[k], py[k], pz[k], t, v);
                worstV = std::max({worstV, double(std::fabs(vx[k] - v[0]) / o.velSum),
                                   double(std::fabs(vy[k] - v[1]) / o.velSum), double(std::fabs(vz[k] - v[2]) / o.velSum)});
            }
        }
        INFO("sum QAk = " << loop << ": worst height error " << worstH << " of sum A, velocity " << worstV
                          << " of sum A omega");
        CHECK(worstH <= 1e-12);
        CHECK(worstV <= 1e-12);
    }
}

TEST_CASE("gerstner batch: a point's result does not depend on the batch around it", "[water][gerstner]") {
    // SIMD lanes are independent: each point alone equals the same point inside a batch, bit for bit, also
    // next to a point that is not finite (which gives NaN, not a crash or a hang), and at every SIMD width the
    // CPU offers (2: SSE2, 4: AVX2, 8: AVX-512), cold and warm-started. Under the CI's floating-point traps
    // (tests/test_main.cpp) a NaN input stops at its first comparison, as everywhere: no NaN point then.
    btGerstnerWaterSurface s(steepSea(0.9, 5), 0.0, 9.81);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-80, 80);
    const std::size_t n = 19;
    std::vector<double> x(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = u(rng);
        z[i] = u(rng);
        y[i] = -0.1 * double(i);
    }
    bool traps = false;
#if defined(__GLIBC__)
    traps = (fegetexcept() & FE_INVALID) != 0;
#endif
    const std::size_t bad = traps ? n : 4;  // the NaN point
    if (bad < n) x[bad] = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> ref[4];  // width 2: height, velocity x, y, z
    for (int lanes : {2, 4, 8}) {
        s.setSimdLanes(lanes);
        INFO("SIMD lanes " << s.simdLanes() << " (asked " << lanes << ")");
        std::vector<double> hb(n), vb[3];
        for (auto& v : vb) v.resize(n);
        s.heights(x.data(), z.data(), n, 3.3, hb.data());
        s.velocities(x.data(), y.data(), z.data(), n, 3.3, vb[0].data(), vb[1].data(), vb[2].data());
        for (std::size_t i = 0; i < n; ++i) {
            double h1, v1[3];
            s.heights(&x[i], &z[i], 1, 3.3, &h1);
            s.velocities(&x[i], &y[i], &z[i], 1, 3.3, &v1[0], &v1[1], &v1[2]);
            if (i == bad) {
                CHECK(std::isnan(hb[i]));
                CHECK(std::isnan(h1));
                continue;
            }
            CHECK(hb[i] == h1);
            for (int k = 0; k < 3; ++k) CHECK(vb[k][i] == v1[k]);
        }
        // Warm-started over a few substeps of drifting points.
        btWaterQueryCache cache;
        std::vector<double> xs = x, hw(n), vw[3];
        for (auto& v : vw) v.resize(n);
        for (int step = 0; step < 5; ++step) {
            for (auto& v : xs) v += 0.004;
            s.heightsCached(xs.data(), z.data(), n, 3.3 + step / 240.0, hw.data(), cache);
            s.velocitiesCached(xs.data(), y.data(), z.data(), n, 3.3 + step / 240.0, vw[0].data(), vw[1].data(),
                               vw[2].data(), cache);
        }
        if (lanes == 2) {
            ref[0] = hb;
            ref[0].insert(ref[0].end(), hw.begin(), hw.end());
            for (int k = 0; k < 3; ++k) {
                ref[k + 1] = vb[k];
                ref[k + 1].insert(ref[k + 1].end(), vw[k].begin(), vw[k].end());
            }
            continue;
        }
        for (std::size_t i = 0; i < n; ++i) {
            if (i == bad) continue;
            CHECK(hb[i] == ref[0][i]);
            CHECK(hw[i] == ref[0][n + i]);
            for (int k = 0; k < 3; ++k) {
                CHECK(vb[k][i] == ref[k + 1][i]);
                CHECK(vw[k][i] == ref[k + 1][n + i]);
            }
        }
    }
}
