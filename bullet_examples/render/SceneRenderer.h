#pragma once
/// @file SceneRenderer.h
/// OpenGL 3.3 core renderer of a RenderFrame: bodies lit with flat shading and coloured wet/dry per pixel
/// (a point is wet when it lies below the water height at its x, z — the same rule as the samples, evaluated
/// from the water grid uploaded as a height texture), the water surface as a translucent mesh, a checkered
/// ground plane, force arrows drawn on top, optional sample points. Shared by `buoyancy run --png` (offscreen)
/// and the scene browser (a window).

#include "render/RenderFrame.h"

#include <cstddef>
#include <memory>

namespace buoyancy::render {

/// Draws RenderFrames into the currently bound framebuffer. Needs a current OpenGL ≥ 3.3 core context for its
/// whole life (construct, draw and destroy it with the same context current).
class SceneRenderer {
public:
    /// Compile the shaders and make the static meshes. @throws std::runtime_error when a shader does not build
    SceneRenderer();
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    /// Clear and draw `frame` over a viewport of width × height pixels.
    void draw(const RenderFrame& frame, int width, int height);

    /// Forget the uploaded body meshes (call when the meshes a frame points to are destroyed, e.g. on reset).
    void clearMeshCache();

    /// Number of body meshes currently uploaded.
    std::size_t meshCacheSize() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace buoyancy::render
