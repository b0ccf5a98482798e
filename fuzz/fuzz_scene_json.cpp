/// @file fuzz_scene_json.cpp
/// libFuzzer target: the scene-file parser and validator of `buoyancy run` (scene/SceneFile.cpp) on
/// arbitrary text, without running anything. Contract checked: bad input ends as cli::UsageError naming
/// the file; an accepted scene has settings the library itself accepts (btBuoyancySettings::validate,
/// btBuoyantBodySettings::validate), finite numbers, dt > 0 and a unit rotation axis.
#include "FuzzContract.h"

#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

using buoyancy::fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    buoyancy::cli::Scene scene;
    try {
        // Mesh paths resolve against a folder that does not exist: "no such file" errors, no disk reads.
        scene = buoyancy::cli::parseScene(text, "fuzz.json", "/nonexistent-fuzz-dir");
    } catch (const buoyancy::cli::UsageError& e) {
        if (std::string(e.what()).rfind("fuzz.json: ", 0) != 0) violated("error does not name the file");
        return 0;
    }
    if (!(scene.dt > 0) || !std::isfinite(scene.dt)) violated("dt");
    if (scene.substepsPerFrame < 1) violated("substeps_per_frame");
    if (!std::isfinite(scene.duration) || !std::isfinite(scene.outputInterval) || !(scene.outputInterval > 0))
        violated("duration / output_interval");
    if (!scene.gravity.allFinite() || !std::isfinite(scene.waterHeight) || !(scene.waterDensity > 0))
        violated("gravity / water");
    for (const auto& b : scene.bodies) {
        try {
            b.body.validate();
            b.buoyancy.validate();
        } catch (const std::invalid_argument& e) {
            std::fprintf(stderr, "%s\n", e.what());
            violated("the parser accepted settings the library rejects");
        }
        if (!b.position.allFinite() || !b.linearVelocity.allFinite() || !b.angularVelocity.allFinite() ||
            !std::isfinite(b.degrees))
            violated("non-finite pose or velocity");
        if (!(std::abs(b.axis.norm() - 1.0) < 1e-9)) violated("rotation axis not unit");
    }
    return 0;
}
