#include "scene/SceneWater.h"

#include "scene/SceneErrors.h"

#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>
#include <BulletBuoyancy/water/btRiverSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <stdexcept>

namespace buoyancy::cli {

namespace {

/// The surface of water object `w` at level `height`, m; `g`: the waves' dispersion, m/s².
SceneWaterSurface makeSurface(const SceneWater& w, double height, double g) {
    SceneWaterSurface out;
    try {
        if (w.type == "gerstner") {
            out.surface = std::make_unique<btGerstnerWaterSurface>(w.waves, height, g);
        } else if (w.type == "grid") {
            out.surface = std::make_unique<btGridWaterSurface>(w.gridNx, w.gridNz, w.gridSpacing, w.gridOrigin.x(),
                                                               w.gridOrigin.y(), w.gridHeights, w.gridPeriodic);
        } else if (w.type == "fft") {
            out.surface = std::make_unique<btFftOceanSurface>(w.fft);
        } else if (w.type == "interactive") {
            auto s = std::make_unique<btInteractiveWaterSurface>(w.size.x(), w.size.y(), w.resolution, w.waveSpeed,
                                                                 w.damping, height, w.centre.x(),
                                                                 w.centre.y());
            out.interactive = s.get();
            out.surface = std::move(s);
        } else if (w.type == "river") {
            btRiverSettings river = w.river;
            river.height = height;
            out.surface = std::make_unique<btRiverSurface>(river);
        } else {
            out.surface = std::make_unique<btFlatWaterSurface>(height, w.current.x(), w.current.y());
        }
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string(e.what()));
    }
    return out;
}

/// g for the waves' dispersion: the scene's, 9.81 m/s² in a scene without gravity.
double dispersionGravity(const Scene& scene) { return scene.gravity.norm() > 0 ? scene.gravity.norm() : 9.81; }

}  // namespace

SceneWaterSurface makeSceneWater(const Scene& scene) {
    try {
        return makeSurface(scene.water, scene.waterHeight, dispersionGravity(scene));
    } catch (const UsageError& e) {
        throw UsageError("water: " + std::string(e.what()));
    }
}

std::unique_ptr<btWaterSurface> makeSceneWaterBody(const Scene& scene, std::size_t index) {
    const SceneWaterBody& body = scene.waters.at(index);
    try {
        return makeSurface(body.water, body.height, dispersionGravity(scene)).surface;
    } catch (const UsageError& e) {
        throw UsageError("waters[" + std::to_string(index) + "]: " + std::string(e.what()));
    }
}

}  // namespace buoyancy::cli
