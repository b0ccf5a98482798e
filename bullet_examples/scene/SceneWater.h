#pragma once
/// @file SceneWater.h
/// Build the water surface a scene's "water" block describes (docs/scene-format.md).

#include "scene/SceneFile.h"

#include <memory>

class btWaterSurface;
class btInteractiveWaterSurface;

namespace buoyancy::cli {

/// The surface of a scene. `interactive` is set (pointing into `surface`) for "interactive" water, which the
/// runner must couple to its bodies with a btInteractiveWaterCoupler added after their actions.
struct SceneWaterSurface {
    std::unique_ptr<btWaterSurface> surface;
    btInteractiveWaterSurface* interactive = nullptr;
};

/// @throws UsageError naming the "water" key for parameters the surface rejects
SceneWaterSurface makeSceneWater(const Scene& scene);

}  // namespace buoyancy::cli
