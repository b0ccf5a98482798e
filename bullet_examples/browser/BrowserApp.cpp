#include "browser/BrowserApp.h"

#include "example_scenes/ExampleEntries.h"
#include "example_scenes/SceneFileExample.h"
#include "render/GlApi.h"
#include "render/PngWriter.h"
#include "render/SceneRenderer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace buoyancy::browser {

namespace {

/// Draws example frames into the window with the shared renderer (Bullet: the GUI helper).
class WindowGuiHelper : public examples::ExampleGuiHelper {
public:
    render::SceneRenderer* renderer = nullptr;
    int width = 1, height = 1;
    void render(const render::RenderFrame& frame) override {
        if (renderer) renderer->draw(frame, width, height);
    }
};

/// The browser's state: the current example and what the panels edit.
struct Browser {
    WindowGuiHelper helper;
    examples::ExampleOptions exampleOptions;
    std::unique_ptr<examples::ExampleScene> example;
    examples::SceneFileExample* sceneExample = nullptr;  ///< `example` when it is scene-file based
    int entry = -1;
    bool paused = false;
    float speed = 1.f;
    int selectedBody = 0;
    int textureChoice = 0;  // index into kTextures
    std::string error;
    render::SceneRenderer* renderer = nullptr;

    /// Make and start entry i. @return false (with `error` set) when its scene cannot be built
    bool open(int i) {
        const examples::ExampleEntry& e = examples::exampleEntry(i);
        if (!e.createFunc) return false;
        if (renderer) renderer->clearMeshCache();
        example.reset();
        sceneExample = nullptr;
        entry = i;
        selectedBody = 0;
        textureChoice = 0;
        error.clear();
        try {
            exampleOptions.option = e.option;
            example.reset(e.createFunc(exampleOptions));
            example->initPhysics();
            sceneExample = dynamic_cast<examples::SceneFileExample*>(example.get());
        } catch (const std::exception& ex) {
            error = std::string(e.name) + ": " + ex.what();
            example.reset();
            sceneExample = nullptr;
            return false;
        }
        return true;
    }

    /// Rebuild the world from the (edited) scene; on failure re-read the file and say why.
    void rebuild() {
        if (!sceneExample) return;
        if (renderer) renderer->clearMeshCache();
        try {
            sceneExample->initPhysics();
            error.clear();
        } catch (const std::exception& ex) {
            error = ex.what();
            sceneExample->reloadScene();
            try {
                sceneExample->initPhysics();
            } catch (const std::exception&) {
            }
        }
    }
};

const int kTextures[] = {0, 32, 64, 128, 256, 512};
/// Width of the panel's plots and sliders, pixels: the panel takes what its contents need and no more.
constexpr float kPanelContentWidth = 250.f;
const char* kTextureNames[] = {"default (exact mesh)", "32", "64", "128", "256", "512"};

/// Slider that reports true once the user let go after a change (rebuild only then).
bool committed() { return ImGui::IsItemDeactivatedAfterEdit(); }

/// The scenes as one drop-down (grouped under their headings): one line of the panel, not a screenful.
void sceneList(Browser& b) {
    const char* current = b.entry >= 0 ? examples::exampleEntry(b.entry).name : "(none)";
    ImGui::SetNextItemWidth(kPanelContentWidth);
    if (!ImGui::BeginCombo("##scene", current, ImGuiComboFlags_HeightLarge)) {
        if (b.entry >= 0 && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", examples::exampleEntry(b.entry).description);
        return;
    }
    for (int i = 0; i < examples::exampleEntryCount(); ++i) {
        const examples::ExampleEntry& e = examples::exampleEntry(i);
        if (e.menuLevel == 0) {
            ImGui::TextDisabled("%s", e.name);
            continue;
        }
        if (ImGui::Selectable(e.name, b.entry == i)) b.open(i);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", e.description);
    }
    ImGui::EndCombo();
}

void controls(Browser& b) {
    if (ImGui::Button(b.paused ? "Run" : "Pause")) b.paused = !b.paused;
    ImGui::SameLine();
    if (ImGui::Button("Step") && b.sceneExample) {
        b.paused = true;
        b.sceneExample->stepFrame();
    }
    ImGui::SameLine();
    if (ImGui::Button("Reset")) {
        if (b.sceneExample) b.rebuild();
        else if (b.example) b.example->initPhysics();
    }
    ImGui::SameLine();
    if (ImGui::Button("Camera") && b.example) b.example->resetCamera();
    // The value goes in the label, not inside the slider, so the grab never covers it.
    char speedLabel[32];
    std::snprintf(speedLabel, sizeof speedLabel, "speed %.2fx###speed", double(b.speed));
    ImGui::SliderFloat(speedLabel, &b.speed, 0.1f, 2.f, "");
    if (!b.sceneExample) return;
    render::SceneFrameOptions& fo = b.sceneExample->frameOptions();
    ImGui::Checkbox("force arrows", &fo.arrows);
    ImGui::SameLine();
    ImGui::Checkbox("samples", &fo.samples);
    ImGui::TextColored(ImVec4(0.95f, 0.35f, 0.35f, 1), "weight");
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.35f, 0.9f, 0.4f, 1), "buoyancy");
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.45f, 0.6f, 1.f, 1), "drag");
}

void sliders(Browser& b) {
    if (!b.sceneExample) return;
    cli::Scene& s = b.sceneExample->scene();
    if (!ImGui::CollapsingHeader("Parameters")) return;
    bool rebuild = false;

    // Bodies: density or mass of one body (a fleet has many).
    if (!s.bodies.empty()) {
        const int n = int(s.bodies.size());
        if (n > 1) ImGui::SliderInt("body", &b.selectedBody, 0, n - 1);
        b.selectedBody = std::clamp(b.selectedBody, 0, n - 1);
        cli::SceneBody& body = s.bodies[std::size_t(b.selectedBody)];
        ImGui::Text("%s (%s)", body.name.c_str(), body.shape.type.c_str());
        if (!body.body.fixed) {
            if (body.body.mass > 0) {
                float m = float(body.body.mass);
                ImGui::SliderFloat("mass kg", &m, float(body.body.mass) * 0.25f + 1e-3f, float(body.body.mass) * 4.f, "%.3f",
                                   ImGuiSliderFlags_Logarithmic);
                if (m > 0) body.body.mass = m;
            } else {
                float d = float(body.body.density);
                ImGui::SliderFloat("density kg/m3", &d, 10.f, 3000.f, "%.0f", ImGuiSliderFlags_Logarithmic);
                body.body.density = d;
            }
            rebuild |= committed();
        }
    }
    float fluid = float(s.waterDensity);
    ImGui::SliderFloat("fluid density", &fluid, 1.f, 1100.f, "%.1f", ImGuiSliderFlags_Logarithmic);
    s.waterDensity = fluid;
    rebuild |= committed();

    // Texture size of the sampled methods (all bodies).
    if (ImGui::Combo("texture", &b.textureChoice, kTextureNames, int(sizeof kTextures / sizeof kTextures[0]))) {
        for (cli::SceneBody& body : s.bodies) {
            body.buoyancy.textureSize = kTextures[b.textureChoice];
            body.buoyancy.method = b.textureChoice == 0 ? btBuoyancyMethod::Auto : btBuoyancyMethod::ExactCoverage;
        }
        rebuild = true;
    }

    // Drag: applied live to every body.
    if (!s.bodies.empty()) {
        btBuoyancySettings& first = s.bodies.front().buoyancy;
        float cd = float(first.dragCoefficient), damping = float(first.linearDamping), cf = float(first.skinFriction);
        bool live = ImGui::SliderFloat("drag Cd", &cd, 0.f, 3.f, "%.2f");
        live |= ImGui::SliderFloat("linear damping", &damping, 0.f, 2.f, "%.2f m/s");
        live |= ImGui::SliderFloat("skin friction", &cf, 0.f, 0.1f, "%.3f");
        if (live) {
            for (cli::SceneBody& body : s.bodies) {
                body.buoyancy.dragCoefficient = cd;
                body.buoyancy.linearDamping = damping;
                body.buoyancy.skinFriction = cf;
            }
            b.sceneExample->applyBuoyancySettings();
        }
    }

    // Waves.
    if (s.water.type == "gerstner") {
        for (std::size_t i = 0; i < s.water.waves.size(); ++i) {
            btGerstnerWave& w = s.water.waves[i];
            ImGui::PushID(int(i));
            float a = float(w.amplitude), l = float(w.wavelength), q = float(w.steepness);
            ImGui::SliderFloat("amplitude m", &a, 0.f, 2.f, "%.2f");
            rebuild |= committed();
            ImGui::SliderFloat("wavelength m", &l, 1.f, 100.f, "%.1f");
            rebuild |= committed();
            ImGui::SliderFloat("steepness Q", &q, 0.f, 1.f, "%.2f");
            rebuild |= committed();
            w.amplitude = a;
            w.wavelength = l;
            w.steepness = q;
            ImGui::PopID();
        }
    } else if (s.water.type == "fft") {
        float u = float(s.water.fft.windSpeed), c = float(s.water.fft.choppiness);
        ImGui::SliderFloat("wind m/s", &u, 1.f, 30.f, "%.1f");
        rebuild |= committed();
        ImGui::SliderFloat("choppiness", &c, 0.f, 2.f, "%.2f");
        rebuild |= committed();
        s.water.fft.windSpeed = u;
        s.water.fft.choppiness = c;
    } else if (s.water.type == "interactive") {
        float c = float(s.water.waveSpeed), g = float(s.water.damping);
        ImGui::SliderFloat("wave speed m/s", &c, 0.5f, 6.f, "%.2f");
        rebuild |= committed();
        ImGui::SliderFloat("wave damping 1/s", &g, 0.f, 2.f, "%.2f");
        rebuild |= committed();
        s.water.waveSpeed = c;
        s.water.damping = g;
    }

    // Permeability of the holes (bodies with a water graph).
    for (cli::SceneBody& body : s.bodies) {
        for (std::size_t r = 0; r < body.flooding.regions.size(); ++r) {
            float v = float(body.flooding.regions[r].value);
            const std::string label = body.name + " hole " + std::to_string(r);
            ImGui::SliderFloat(label.c_str(), &v, 0.f, 1.f, "%.3f", ImGuiSliderFlags_Logarithmic);
            rebuild |= committed();
            body.flooding.regions[r].value = v;
        }
    }
    if (ImGui::Button("Reload file")) {
        b.sceneExample->reloadScene();
        rebuild = true;
    }
    if (rebuild) b.rebuild();
}

void plots(Browser& b) {
    if (!b.sceneExample) return;
    const examples::ExampleHistory& h = b.sceneExample->history();
    ImGui::Text("t = %.2f s   bodies %zu", b.sceneExample->time(), b.sceneExample->scene().bodies.size());
    ImGui::Text("cost per substep: %.1f us", b.sceneExample->substepMicroseconds());
    const int n = int(h.time.size());
    const int shown = std::min(n, 600);
    if (shown > 0) {
        const float* sub = h.submerged.data() + (n - shown);
        const float* in = h.waterInside.data() + (n - shown);
        const ImVec2 size(kPanelContentWidth, 46.f);
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "submerged %.4f m3", double(sub[shown - 1]));
        ImGui::PlotLines("##sub", sub, shown, 0, overlay, FLT_MAX, FLT_MAX, size);
        std::snprintf(overlay, sizeof overlay, "water inside %.4f m3", double(in[shown - 1]));
        ImGui::PlotLines("##in", in, shown, 0, overlay, FLT_MAX, FLT_MAX, size);
    }
}

/// Orbit with the left mouse button, pan with the right one, zoom with the wheel (when ImGui does not use them).
void cameraInput(Browser& b, GLFWwindow* window) {
    if (!b.sceneExample) return;
    ImGuiIO& io = ImGui::GetIO();
    if (io.WantCaptureMouse) return;
    render::RenderCamera& cam = b.sceneExample->frame().camera;
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
        cam.yawDeg -= io.MouseDelta.x * 0.3f;
        cam.pitchDeg = std::clamp(cam.pitchDeg + io.MouseDelta.y * 0.3f, -85.f, 85.f);
    }
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
        const float k = cam.distance * 0.0015f, yaw = cam.yawDeg * 3.14159265f / 180.f;
        cam.target.x() -= k * (io.MouseDelta.x * std::cos(yaw) - io.MouseDelta.y * std::sin(yaw));
        cam.target.z() -= k * (-io.MouseDelta.x * std::sin(yaw) - io.MouseDelta.y * std::cos(yaw));
    }
    if (io.MouseWheel != 0) cam.distance = std::clamp(cam.distance * std::pow(0.9f, io.MouseWheel), 0.5f, 500.f);
    (void)window;
}

}  // namespace

int runBrowser(const BrowserOptions& options) {
    if (options.list) {
        int number = 0;
        for (int i = 0; i < examples::exampleEntryCount(); ++i)
            if (examples::exampleEntry(i).createFunc) std::cout << ++number << '\t' << examples::exampleEntry(i).name << '\n';
        return 0;
    }
    std::string sceneError;
    const int first = examples::findExampleScene(options.scene, sceneError);
    if (first < 0) {
        std::cerr << "error: --scene: " << sceneError << '\n';
        return 2;
    }
    if (!glfwInit()) {
        std::cerr << "error: cannot initialise GLFW (no display? try xvfb-run -a buoyancy_browser ...)\n";
        return 3;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, 4);
    GLFWwindow* window = glfwCreateWindow(options.width, options.height, "BulletBuoyancy scene browser", nullptr, nullptr);
    if (!window) {
        std::cerr << "error: cannot open an OpenGL 3.3 core window\n";
        glfwTerminate();
        return 3;
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(options.screenshot.empty() ? 1 : 0);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    int rc = 0;
    {
        render::SceneRenderer renderer;
        Browser b;
        b.renderer = &renderer;
        b.helper.renderer = &renderer;
        b.exampleOptions.guiHelper = &b.helper;
        if (!b.open(first) && !options.screenshot.empty()) {
            std::cerr << "error: " << b.error << '\n';
            rc = 2;
        }
        const bool capture = !options.screenshot.empty();
        double last = glfwGetTime();
        for (int frame = 0; rc == 0 && !glfwWindowShouldClose(window); ++frame) {
            glfwPollEvents();
            const double now = glfwGetTime();
            const float dt = capture ? 1.f / 60.f : float(std::min(now - last, 0.1));
            last = now;
            if (b.example && !b.paused) b.example->stepSimulation(dt * b.speed);

            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            // The panel: as large as its contents (collapse it with the arrow of its title bar; "Parameters"
            // opens the sliders).
            ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Once);
            ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(FLT_MAX, float(options.height) - 16));
            ImGui::Begin("BulletBuoyancy", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
            ImGui::PushItemWidth(kPanelContentWidth * 0.62f);
            sceneList(b);
            controls(b);
            plots(b);
            sliders(b);
            if (!b.error.empty()) {
                ImGui::PushTextWrapPos(kPanelContentWidth);
                ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", b.error.c_str());
                ImGui::PopTextWrapPos();
            }
            ImGui::PopItemWidth();
            ImGui::End();
            cameraInput(b, window);
            ImGui::Render();

            glfwGetFramebufferSize(window, &b.helper.width, &b.helper.height);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            if (b.example) {
                b.example->renderScene();
            } else {
                glViewport(0, 0, b.helper.width, b.helper.height);
                glClearColor(0.2f, 0.2f, 0.25f, 1.f);
                glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            }
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

            if (capture && frame + 1 >= options.frames) {
                const int w = b.helper.width, h = b.helper.height;
                std::vector<std::uint8_t> bottomUp(std::size_t(w) * h * 4), rgba(bottomUp.size());
                glPixelStorei(GL_PACK_ALIGNMENT, 1);
                glReadBuffer(GL_BACK);
                glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
                const std::size_t row = std::size_t(w) * 4;
                for (int y = 0; y < h; ++y)
                    std::memcpy(&rgba[std::size_t(y) * row], &bottomUp[std::size_t(h - 1 - y) * row], row);
                try {
                    render::writePng(options.screenshot, w, h, rgba);
                    std::cout << "wrote " << options.screenshot << " (" << w << "x" << h << ", " << options.frames
                              << " frames, t = " << (b.sceneExample ? b.sceneExample->time() : 0.0) << " s)\n";
                } catch (const std::exception& e) {
                    std::cerr << "error: --screenshot: " << e.what() << '\n';
                    rc = 2;
                }
                break;
            }
            glfwSwapBuffers(window);
        }
        renderer.clearMeshCache();
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return rc;
}

}  // namespace buoyancy::browser
