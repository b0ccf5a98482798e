#pragma once
/// @file OffscreenContext.h
/// An OpenGL 3.3 core context without a display: Mesa's EGL on the surfaceless platform (llvmpipe in software
/// when there is no GPU), rendering into a 4× multisampled framebuffer object that is resolved and read back.

#include <cstdint>
#include <memory>
#include <vector>

namespace buoyancy::render {

/// Owns an EGL display, context and framebuffer of a fixed size; current on the creating thread.
class OffscreenContext {
public:
    /// @param width,height  framebuffer size, pixels (16..8192)
    /// @throws std::runtime_error naming the failing step ("no EGL surfaceless display", "no OpenGL 3.3 core
    ///         context", "framebuffer incomplete")
    OffscreenContext(int width, int height);
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;

    /// Bind the multisampled framebuffer (draw here).
    void bind();
    /// Resolve and read the picture: width·height·4 bytes RGBA, top row first.
    void readPixels(std::vector<std::uint8_t>& rgba);

    int width() const { return m_width; }
    int height() const { return m_height; }
    /// GL_RENDERER of the context (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
    const char* rendererName() const;

private:
    void release();  ///< free the framebuffers, context and display (idempotent)
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    int m_width, m_height;
};

}  // namespace buoyancy::render
