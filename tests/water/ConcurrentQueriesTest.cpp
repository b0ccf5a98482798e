// The thread-safety rule of btWaterSurface (water/btWaterSurface.h: thread-safe for concurrent const calls, warm-start
// memory per caller in btWaterQueryCache): for every surface, several threads querying at once, each with its own
// caches, get exactly the answers of the same queries made one after the other. Run under ThreadSanitizer by
// scripts/ci-extra.sh.
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>
#include <BulletBuoyancy/water/btRiverSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace {

/// What one caller (a body) asks over a few substeps: heights, velocities and bounds at points that move a little
/// each substep, through its own caches (the warm start of an iterative surface).
std::vector<double> callerQueries(const btWaterSurface& water, int caller, int substeps) {
    const std::size_t n = 96;
    std::vector<double> x(n), y(n), z(n), h(n), u(n), v(n), w(n), out;
    btWaterQueryCache heightCache, velocityCache;
    for (int s = 0; s < substeps; ++s) {
        const double t = 0.5 + s / 240.0;
        for (std::size_t i = 0; i < n; ++i) {
            x[i] = 3.0 * caller + 0.13 * double(i % 12) + 0.01 * s;
            z[i] = -2.0 * caller + 0.17 * double(i / 12) - 0.005 * s;
            y[i] = -0.3 - 0.01 * double(i % 5);
        }
        water.heightsCached(x.data(), z.data(), n, t, h.data(), heightCache);
        water.velocitiesCached(x.data(), y.data(), z.data(), n, t, u.data(), v.data(), w.data(), velocityCache);
        water.heights(x.data(), z.data(), n, t, h.data() + 0);  // the uncached query too
        double lo = 0, hi = 0;
        water.heightBounds(x[0] - 1.0, z[0] - 1.0, x[0] + 1.0, z[0] + 1.0, t, lo, hi);
        out.insert(out.end(), h.begin(), h.end());
        out.insert(out.end(), u.begin(), u.end());
        out.insert(out.end(), v.begin(), v.end());
        out.insert(out.end(), w.begin(), w.end());
        out.push_back(lo);
        out.push_back(hi);
    }
    return out;
}

std::vector<std::pair<std::string, std::unique_ptr<btWaterSurface>>> everySurface() {
    std::vector<std::pair<std::string, std::unique_ptr<btWaterSurface>>> s;
    s.emplace_back("flat", std::make_unique<btFlatWaterSurface>(0.2, 0.3, -0.1));
    std::vector<btGerstnerWave> waves(3);
    waves[0] = {0.5, 30.0, 1.0, 0.0, 0.7, 0.0};
    waves[1] = {0.3, 17.0, 0.8, 0.6, 0.6, 1.3};
    waves[2] = {0.15, 9.0, -0.3, 1.0, 0.5, 2.1};
    s.emplace_back("gerstner", std::make_unique<btGerstnerWaterSurface>(waves));
    std::vector<double> grid(32 * 32);
    for (std::size_t i = 0; i < grid.size(); ++i) grid[i] = 0.2 * std::sin(0.3 * double(i % 32)) * std::cos(0.2 * double(i / 32));
    s.emplace_back("grid", std::make_unique<btGridWaterSurface>(32, 32, 0.5, -8.0, -8.0, grid, true));
    btFftOceanSettings fft;
    fft.resolution = 32;
    fft.patchSize = 32.0;
    fft.choppiness = 0.8;
    s.emplace_back("fft", std::make_unique<btFftOceanSurface>(fft));
    auto interactive = std::make_unique<btInteractiveWaterSurface>(16.0, 16.0, 64, 2.0, 0.1);
    interactive->addVolumeChange(1.0, 0.5, 1.5, 0.3);
    interactive->step(1.0 / 60);
    s.emplace_back("interactive", std::move(interactive));
    btRiverSettings river;  // a bend through the callers' points: in the channel, near the corner and on the banks
    river.centreline = {{-5.0, -3.0}, {4.0, 0.0}, {12.0, -5.0}};
    river.width = 6.0;
    river.surfaceSpeed = 1.2;
    s.emplace_back("river", std::make_unique<btRiverSurface>(river));
    return s;
}

}  // namespace

TEST_CASE("water surfaces: concurrent queries with per-caller caches give the one-after-the-other answers",
          "[water][threads]") {
    const int callers = 4, substeps = 12;
    for (const auto& entry : everySurface()) {
        INFO(entry.first);
        const btWaterSurface* water = entry.second.get();
        std::vector<std::vector<double>> sequential(callers), concurrent(callers);
        for (int c = 0; c < callers; ++c) sequential[std::size_t(c)] = callerQueries(*water, c, substeps);
        std::vector<std::thread> threads;
        for (int c = 0; c < callers; ++c)
            threads.emplace_back([&, c] { concurrent[std::size_t(c)] = callerQueries(*water, c, substeps); });
        for (auto& t : threads) t.join();
        for (int c = 0; c < callers; ++c) {
            INFO("caller " << c);
            REQUIRE(sequential[std::size_t(c)].size() == concurrent[std::size_t(c)].size());
            CHECK(sequential[std::size_t(c)] == concurrent[std::size_t(c)]);
        }
    }
}
