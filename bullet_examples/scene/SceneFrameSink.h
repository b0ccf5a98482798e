#pragma once
/// @file SceneFrameSink.h
/// What receives a running scene's frames (the `--png` pictures of `buoyancy run`), so that the scene runner and
/// the offscreen renderer know this interface and not each other.

#include <functional>
#include <memory>
#include <string>

namespace buoyancy::cli {

struct Scene;
struct SceneWorld;

/// Receives the running world at t = 0 and at every output time (the `--png` pictures).
class SceneFrameSink {
public:
    virtual ~SceneFrameSink() = default;
    /// Called after the trajectory rows of time t (s) were written.
    virtual void frame(const Scene& scene, const SceneWorld& world, double t) = 0;
};

/// Makes a picture sink writing into `folder` at `width` × `height` pixels; set by an executable built with the
/// offscreen renderer (empty otherwise).
/// @throws UsageError when the renderer cannot start (e.g. no EGL display) or the folder cannot be made
using SceneFrameSinkFactory =
    std::function<std::unique_ptr<SceneFrameSink>(const std::string& folder, int width, int height, const Scene&)>;

}  // namespace buoyancy::cli
