#pragma once
/// @file SceneRenderer.h
/// OpenGL 3.3 core renderer of a RenderFrame: bodies lit with flat shading and coloured wet/dry per pixel
/// (a point is wet when it lies below the water height at its x, z — the same rule as the samples, evaluated
/// from the water grid uploaded as a height texture) with the waterline drawn where they cut the surface; the
/// water surface translucent looking down and opaque at a grazing angle, crests lighter and troughs darker;
/// submerged things fading to the deep-water colour with depth; a plain sandy ground; force arrows drawn on top
/// of everything; optional sample points. Shared by `buoyancy run --png` (offscreen) and the scene browser.

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
