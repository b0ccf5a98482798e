#pragma once
/// @file SceneFileExample.h
/// An example scene made from a scene JSON file (docs/scene-format.md): the world is the one `buoyancy run`
/// builds (cli::buildSceneWorld), so the browser, the pictures and the headless runner show the same physics.
/// Keeps the history the browser plots (submerged volume, water inside) and the measured cost per substep.

#include "example_scenes/ExampleInterface.h"

#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"
#include "render/SceneFrame.h"

#include <memory>
#include <string>
#include <vector>

namespace buoyancy::examples {

/// Time series recorded once per scene frame (the browser's live plot).
struct ExampleHistory {
    std::vector<float> time;          ///< s
    std::vector<float> submerged;     ///< Σ submerged volume over the bodies, m³
    std::vector<float> waterInside;   ///< Σ water inside the bodies (water graphs), m³
    std::size_t capacity = 4000;      ///< oldest samples are dropped beyond this many
    void clear();
    void push(float t, float sub, float inside);
};

/// A scene file wrapped as an example.
class SceneFileExample : public ExampleScene {
public:
    /// @param sceneFile  file name inside options.scenesDir (or an absolute path)
    SceneFileExample(ExampleOptions& options, std::string sceneFile);
    ~SceneFileExample() override;

    void initPhysics() override;
    void exitPhysics() override;
    void stepSimulation(float deltaTime) override;
    void renderScene() override;
    void resetCamera() override;

    /// Advance exactly one frame of the scene (dt · substeps_per_frame); the browser's "step" button.
    virtual void stepFrame();

    /// The scene as read from the file; edit it, then exitPhysics() + initPhysics() rebuild from it (sliders).
    cli::Scene& scene() { return m_scene; }
    /// Re-read the file (undo slider edits); takes effect at the next initPhysics().
    void reloadScene();
    /// Push every body's current "buoyancy" block (drag, damping, ...) into the running actions (no rebuild).
    void applyBuoyancySettings();

    /// The running world (null before initPhysics).
    const cli::SceneWorld* world() const { return m_world.get(); }
    cli::SceneWorld* world() { return m_world.get(); }
    /// Simulated time, s.
    double time() const { return m_world ? m_world->time() : 0.0; }
    /// Recorded series.
    const ExampleHistory& history() const { return m_history; }
    /// Wall-clock cost of one physics substep (Bullet + buoyancy + water), averaged, µs.
    double substepMicroseconds() const { return m_substepMicros; }
    /// The frame renderScene() draws (camera editable by the UI).
    render::RenderFrame& frame() { return m_frame; }
    /// What renderScene() draws.
    render::SceneFrameOptions& frameOptions() { return m_frameOptions; }
    /// Path of the scene file.
    const std::string& scenePath() const { return m_path; }

protected:
    /// Hook after every frame (subclasses animate things here).
    virtual void afterFrame() {}

    ExampleOptions m_options;
    std::string m_path;
    cli::Scene m_scene;
    std::unique_ptr<cli::SceneWorld> m_world;
    ExampleHistory m_history;
    double m_substepMicros = 0;
    double m_accumulator = 0;
    render::RenderFrame m_frame;
    render::SceneFrameOptions m_frameOptions;
    bool m_cameraSet = false;
};

/// The folder of the bundled scenes: $BUOYANCY_SCENES_DIR when set, else the source tree's
/// bullet_examples/scenes (compiled in).
std::string defaultScenesDir();

}  // namespace buoyancy::examples
