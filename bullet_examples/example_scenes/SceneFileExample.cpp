#include "example_scenes/SceneFileExample.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>

namespace buoyancy::examples {

void ExampleHistory::clear() {
    time.clear();
    submerged.clear();
    waterInside.clear();
}

void ExampleHistory::push(float t, float sub, float inside) {
    if (time.size() >= capacity) {  // drop the oldest half at once (amortised O(1))
        const std::size_t half = capacity / 2;
        time.erase(time.begin(), time.begin() + std::ptrdiff_t(half));
        submerged.erase(submerged.begin(), submerged.begin() + std::ptrdiff_t(half));
        waterInside.erase(waterInside.begin(), waterInside.begin() + std::ptrdiff_t(half));
    }
    time.push_back(t);
    submerged.push_back(sub);
    waterInside.push_back(inside);
}

std::string defaultScenesDir() {
    if (const char* env = std::getenv("BUOYANCY_SCENES_DIR"); env && *env) return env;
#ifdef BUOYANCY_SCENES_DIR
    return BUOYANCY_SCENES_DIR;
#else
    return "bullet_examples/scenes";
#endif
}

SceneFileExample::SceneFileExample(ExampleOptions& options, std::string sceneFile) : m_options(options) {
    const std::string dir = options.scenesDir.empty() ? defaultScenesDir() : options.scenesDir;
    m_path = std::filesystem::path(sceneFile).is_absolute() ? sceneFile : (std::filesystem::path(dir) / sceneFile).string();
    reloadScene();
}

SceneFileExample::~SceneFileExample() { exitPhysics(); }

void SceneFileExample::reloadScene() { m_scene = cli::loadSceneFile(m_path); }

void SceneFileExample::initPhysics() {
    exitPhysics();
    m_world = cli::buildSceneWorld(m_scene, 10.0);
    m_history.clear();
    m_accumulator = 0;
    m_substepMicros = 0;
    if (!m_cameraSet) resetCamera();
}

void SceneFileExample::exitPhysics() { m_world.reset(); }

void SceneFileExample::resetCamera() {
    if (!m_world) return;
    m_frame.camera = render::frameSceneCamera(m_scene, *m_world);
    m_cameraSet = true;
}

void SceneFileExample::stepFrame() {
    if (!m_world) return;
    const auto start = std::chrono::steady_clock::now();
    cli::stepSceneFrame(m_scene, *m_world);
    const double micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() /
                          double(m_scene.substepsPerFrame);
    m_substepMicros = m_substepMicros > 0 ? 0.9 * m_substepMicros + 0.1 * micros : micros;
    double sub = 0, inside = 0;
    for (std::size_t i = 0; i < m_world->bodies.size(); ++i) {
        if (m_world->actions[i]) sub += m_world->actions[i]->getLastResult().submergedVolume;
        if (m_world->floods[i]) inside += m_world->floods[i]->getWaterVolume();
    }
    m_history.push(float(m_world->time()), float(sub), float(inside));
    afterFrame();
}

void SceneFileExample::stepSimulation(float deltaTime) {
    if (!m_world || !(deltaTime > 0)) return;
    const double frameTime = m_scene.dt * m_scene.substepsPerFrame;
    m_accumulator = std::min(m_accumulator + double(deltaTime), 8 * frameTime);  // never spiral when slow
    while (m_accumulator >= frameTime) {
        stepFrame();
        m_accumulator -= frameTime;
    }
}

void SceneFileExample::renderScene() {
    if (!m_world) return;
    render::buildSceneFrame(m_scene, *m_world, m_frameOptions, m_frame);
    if (m_options.guiHelper) m_options.guiHelper->render(m_frame);
}

void SceneFileExample::applyBuoyancySettings() {
    if (!m_world) return;
    for (std::size_t i = 0; i < m_world->actions.size() && i < m_scene.bodies.size(); ++i)
        if (m_world->actions[i]) m_world->actions[i]->setSettings(m_scene.bodies[i].buoyancy);
}

}  // namespace buoyancy::examples
