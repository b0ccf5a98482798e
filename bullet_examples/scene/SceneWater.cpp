#include "scene/SceneWater.h"

#include "scene/SceneErrors.h"

#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <stdexcept>

namespace buoyancy::cli {

SceneWaterSurface makeSceneWater(const Scene& scene) {
    const SceneWater& w = scene.water;
    const double g = scene.gravity.norm() > 0 ? scene.gravity.norm() : 9.81;  // the waves' dispersion
    SceneWaterSurface out;
    try {
        if (w.type == "gerstner") {
            out.surface = std::make_unique<btGerstnerWaterSurface>(w.waves, scene.waterHeight, g);
        } else if (w.type == "grid") {
            out.surface = std::make_unique<btGridWaterSurface>(w.gridNx, w.gridNz, w.gridSpacing, w.gridOrigin.x(),
                                                               w.gridOrigin.y(), w.gridHeights, w.gridPeriodic);
        } else if (w.type == "fft") {
            out.surface = std::make_unique<btFftOceanSurface>(w.fft);
        } else if (w.type == "interactive") {
            auto s = std::make_unique<btInteractiveWaterSurface>(w.size.x(), w.size.y(), w.resolution, w.waveSpeed,
                                                                 w.damping, scene.waterHeight, w.centre.x(),
                                                                 w.centre.y());
            out.interactive = s.get();
            out.surface = std::move(s);
        } else {
            out.surface = std::make_unique<btFlatWaterSurface>(scene.waterHeight, w.current.x(), w.current.y());
        }
    } catch (const std::invalid_argument& e) {
        throw UsageError("water: " + std::string(e.what()));
    }
    return out;
}

}  // namespace buoyancy::cli
