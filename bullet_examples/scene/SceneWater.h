#pragma once
/// @file SceneWater.h
/// Build the water surface a scene's "water" block describes (docs/scene-format.md).

#include "scene/SceneFile.h"

#include <cstddef>
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

/// The surface of the scene's water body `index` (Scene::waters; interactive water is refused by the loader).
/// @throws UsageError naming "waters[index]" for parameters the surface rejects
std::unique_ptr<btWaterSurface> makeSceneWaterBody(const Scene& scene, std::size_t index);

}  // namespace buoyancy::cli
