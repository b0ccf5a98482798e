#include "render/PngRecorder.h"

#include "scene/SceneErrors.h"
#include "render/FrameLabel.h"
#include "render/OffscreenContext.h"
#include "render/PngWriter.h"
#include "render/SceneFrame.h"
#include "render/SceneRenderer.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace buoyancy::render {

namespace {

/// Renders each frame into DIR/frame_NNNNN.png, its time stamped in the top-left corner.
class PngSink : public cli::SceneFrameSink {
public:
    PngSink(std::string dir, int width, int height) : m_dir(std::move(dir)), m_context(width, height), m_renderer() {}

    void frame(const cli::Scene& scene, const cli::SceneWorld& world, double t) override {
        if (m_index == 0) m_frame.camera = frameSceneCamera(scene, world);
        buildSceneFrame(scene, world, m_options, m_frame);
        m_context.bind();
        m_renderer.draw(m_frame, m_context.width(), m_context.height());
        m_context.readPixels(m_pixels);
        stampLabel(m_pixels, m_context.width(), m_context.height(), timeLabel(t), m_label);
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", m_index++);
        try {
            writePng((std::filesystem::path(m_dir) / name).string(), m_context.width(), m_context.height(), m_pixels);
        } catch (const std::exception& e) {
            throw cli::UsageError(std::string("--png: ") + e.what());
        }
    }

private:
    std::string m_dir;
    OffscreenContext m_context;  // first: the renderer needs its context current
    SceneRenderer m_renderer;
    SceneFrameOptions m_options;
    LabelStyle m_label;
    RenderFrame m_frame;
    std::vector<std::uint8_t> m_pixels;
    int m_index = 0;
};

}  // namespace

std::unique_ptr<cli::SceneFrameSink> makePngSink(const std::string& folder, int width, int height, const cli::Scene&) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (!std::filesystem::is_directory(folder)) throw cli::UsageError("--png: cannot create the folder " + folder);
    try {
        return std::make_unique<PngSink>(folder, width, height);
    } catch (const cli::UsageError&) {
        throw;
    } catch (const std::exception& e) {
        throw cli::UsageError(std::string("--png: ") + e.what());
    }
}

}  // namespace buoyancy::render
