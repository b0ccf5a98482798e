// The interactive height field must not creep at fine resolution. Oracles: conservation (the grid's
// water volume Σ (η − h) A is zero at all times: the coupler only moves displaced water), the open-sea level
// far from the bodies (h, up to the displaced volume spread over the grid), and Archimedes for the floating
// boxes (draft s·c).
#include <catch2/catch.hpp>

#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>

#include <cmath>
#include <sstream>

namespace {

std::string sceneText(int resolution) {
    std::ostringstream s;
    s << R"({"duration": 20, "water": {"type": "interactive", "height": 0, "size": [20, 20], "resolution": )" << resolution
      << R"(, "wave_speed": 2, "damping": 0.1},
 "bodies": [{"name": "drop", "shape": {"type": "box", "size": [1, 0.5, 1]}, "density": 500, "position": [0, 1, 0]},
            {"name": "neighbour", "shape": {"type": "box", "size": [1, 0.5, 1]}, "density": 500, "position": [2.5, 0, 0]},
            {"name": "buoy", "shape": {"type": "sphere", "radius": 0.3, "resolution": 32}, "density": 400,
             "position": [-1.5, 0.05, 2]}]})";
    return s.str();
}

}  // namespace

TEST_CASE("interactive water at 256^2: the mean and far-field level stay put, boxes float at their drafts",
          "[water][interactive][slow]") {
    const int resolution = 256;
    const buoyancy::cli::Scene scene = buoyancy::cli::parseScene(sceneText(resolution), "level.json", ".");
    auto world = buoyancy::cli::buildSceneWorld(scene, 10.0);
    btInteractiveWaterSurface* water = world->interactiveWater;
    REQUIRE(water != nullptr);
    REQUIRE(water->cellsX() == resolution);
    const double cellArea = water->cellSize() * water->cellSize();
    const double gridArea = cellArea * water->cellsX() * water->cellsZ();
    double worstVolume = 0, worstFar = 0, lateBox = 0;
    int lateCount = 0;
    const int frames = int(std::lround(20.0 / (scene.dt * scene.substepsPerFrame)));
    for (int f = 1; f <= frames; ++f) {
        buoyancy::cli::stepSceneFrame(scene, *world);
        worstVolume = std::max(worstVolume, std::abs(water->waterVolume()));
        if (f % 60 == 0) {
            // Far field: the cells more than 4 m from the grid centre region holding the bodies (|x|, |z| > 6 m).
            double sum = 0;
            int n = 0;
            for (int j = 0; j < water->cellsZ(); ++j)
                for (int i = 0; i < water->cellsX(); ++i) {
                    const double x = -10 + (i + 0.5) * water->cellSize(), z = -10 + (j + 0.5) * water->cellSize();
                    if (std::abs(x) > 6 || std::abs(z) > 6) {
                        sum += water->cellHeight(i, j);
                        ++n;
                    }
                }
            worstFar = std::max(worstFar, std::abs(sum / n));
        }
        if (world->time() > 15) {
            for (int b = 0; b < 2; ++b) {  // the two boxes: COM y = h − c/2 + s·c = 0 (s = 0.5, c = 0.5)
                lateBox = std::max(lateBox, std::abs(double(world->bodies[std::size_t(b)]->getRigidBody()->getCenterOfMassPosition().y())));
            }
            ++lateCount;
        }
    }
    INFO("worst |grid water volume| " << worstVolume << " m^3, worst |far-field mean level| " << worstFar
                                     << " m, worst late |box COM y| " << lateBox << " m");
    CHECK(worstVolume < 1e-9);
    // Displaced water spread over the grid would raise the open sea by at most Σ V_sub / A_grid (0.56 m³ / 400 m²).
    CHECK(worstFar < 0.56 / gridArea + 2e-3);
    CHECK(lateCount > 0);
    CHECK(lateBox < 0.02);
}
