#include "render/OffscreenContext.h"

#include "render/GlApi.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace buoyancy::render {

struct OffscreenContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    GLuint msFbo = 0, msColour = 0, msDepth = 0;
    GLuint fbo = 0, colour = 0;
};

namespace {
std::string eglError(const char* what) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04x", unsigned(eglGetError()));
    return std::string("offscreen renderer: ") + what + " (EGL error " + buf + ")";
}
}  // namespace

OffscreenContext::OffscreenContext(int width, int height)
    : m_impl(std::make_unique<Impl>()), m_width(width), m_height(height) {
    if (width < 16 || height < 16 || width > 8192 || height > 8192)
        throw std::runtime_error("offscreen renderer: size must be in [16, 8192] pixels");
    Impl& r = *m_impl;
    // Surfaceless platform (EGL_MESA_platform_surfaceless): no X server, no GPU device needed.
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay) r.display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (r.display == EGL_NO_DISPLAY) throw std::runtime_error(eglError("no EGL surfaceless display (Mesa's libEGL needed)"));
    EGLint major = 0, minor = 0;
    if (!eglInitialize(r.display, &major, &minor)) {
        r.display = EGL_NO_DISPLAY;
        throw std::runtime_error(eglError("eglInitialize failed"));
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(r.display);
        throw std::runtime_error(eglError("no desktop OpenGL API in EGL"));
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    // EGL_KHR_no_config_context: no config needed without a surface.
    r.context = eglCreateContext(r.display, static_cast<EGLConfig>(nullptr), EGL_NO_CONTEXT, attribs);
    if (r.context == EGL_NO_CONTEXT || !eglMakeCurrent(r.display, EGL_NO_SURFACE, EGL_NO_SURFACE, r.context)) {
        const std::string msg = eglError("no OpenGL 3.3 core context");
        if (r.context != EGL_NO_CONTEXT) eglDestroyContext(r.display, r.context);
        eglTerminate(r.display);
        throw std::runtime_error(msg);
    }
    // 4× multisampled colour + depth, resolved into a plain colour renderbuffer.
    glGenFramebuffers(1, &r.msFbo);
    glGenRenderbuffers(1, &r.msColour);
    glGenRenderbuffers(1, &r.msDepth);
    glBindRenderbuffer(GL_RENDERBUFFER, r.msColour);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_RGBA8, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, r.msDepth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, 4, GL_DEPTH_COMPONENT24, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, r.msFbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r.msColour);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r.msDepth);
    const bool msOk = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glGenFramebuffers(1, &r.fbo);
    glGenRenderbuffers(1, &r.colour);
    glBindRenderbuffer(GL_RENDERBUFFER, r.colour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, r.fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r.colour);
    const bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (!msOk || !ok) {
        release();
        throw std::runtime_error("offscreen renderer: framebuffer incomplete");
    }
    bind();
}

OffscreenContext::~OffscreenContext() { release(); }

void OffscreenContext::release() {
    if (!m_impl) return;
    Impl& r = *m_impl;
    if (r.context != EGL_NO_CONTEXT) {
        eglMakeCurrent(r.display, EGL_NO_SURFACE, EGL_NO_SURFACE, r.context);
        if (r.msFbo) glDeleteFramebuffers(1, &r.msFbo);
        if (r.fbo) glDeleteFramebuffers(1, &r.fbo);
        if (r.msColour) glDeleteRenderbuffers(1, &r.msColour);
        if (r.msDepth) glDeleteRenderbuffers(1, &r.msDepth);
        if (r.colour) glDeleteRenderbuffers(1, &r.colour);
        r.msFbo = r.fbo = r.msColour = r.msDepth = r.colour = 0;
        eglMakeCurrent(r.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(r.display, r.context);
        r.context = EGL_NO_CONTEXT;
    }
    if (r.display != EGL_NO_DISPLAY) {
        eglTerminate(r.display);
        r.display = EGL_NO_DISPLAY;
    }
}

void OffscreenContext::bind() { glBindFramebuffer(GL_FRAMEBUFFER, m_impl->msFbo); }

void OffscreenContext::readPixels(std::vector<std::uint8_t>& rgba) {
    Impl& r = *m_impl;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r.msFbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r.fbo);
    glBlitFramebuffer(0, 0, m_width, m_height, 0, 0, m_width, m_height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r.fbo);
    const std::size_t row = std::size_t(m_width) * 4;
    std::vector<std::uint8_t> bottomUp(row * std::size_t(m_height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, m_width, m_height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    rgba.resize(bottomUp.size());
    for (int y = 0; y < m_height; ++y)  // OpenGL's rows are bottom-up
        std::memcpy(&rgba[std::size_t(y) * row], &bottomUp[std::size_t(m_height - 1 - y) * row], row);
    bind();
}

const char* OffscreenContext::rendererName() const {
    return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

}  // namespace buoyancy::render
