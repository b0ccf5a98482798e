#pragma once
/// @file ExampleInterface.h
/// The example-scene interface, shaped like Bullet's example browser (examples/CommonInterfaces/
/// CommonExampleInterface.h: initPhysics / stepSimulation / renderScene / exitPhysics, a create function per
/// example and a table of ExampleEntry) so that each scene can be dropped into Bullet's own ExampleBrowser
/// (docs/example-browser.md). Used by the scene browser app and by the headless tests.

#include "render/RenderFrame.h"

#include <string>

namespace buoyancy::examples {

/// Where renderScene() draws (Bullet: GUIHelperInterface). The browser draws into its window; headless runs
/// pass none (renderScene then only builds the frame).
class ExampleGuiHelper {
public:
    virtual ~ExampleGuiHelper() = default;
    /// Draw one frame of the scene.
    virtual void render(const render::RenderFrame& frame) = 0;
};

/// What a create function gets (Bullet: CommonExampleOptions).
struct ExampleOptions {
    ExampleGuiHelper* guiHelper = nullptr; ///< may be null (headless)
    int option = 0;                        ///< the entry's option value
    std::string scenesDir;                 ///< folder of the scene JSON files; empty: examples::defaultScenesDir()
};

/// One example (Bullet: CommonExampleInterface).
class ExampleScene {
public:
    /// Bullet: CommonExampleInterface::CreateFunc.
    using CreateFunc = ExampleScene* (*)(ExampleOptions& options);

    virtual ~ExampleScene() = default;
    /// Build the world (again, after exitPhysics: that is "reset"). @throws std::runtime_error for bad input
    virtual void initPhysics() = 0;
    /// Destroy the world.
    virtual void exitPhysics() = 0;
    /// Advance the simulation by deltaTime seconds of wall-clock time (whole fixed frames of the scene).
    virtual void stepSimulation(float deltaTime) = 0;
    /// Draw the current state through the options' gui helper.
    virtual void renderScene() = 0;
    /// Put the camera back to the scene's default view.
    virtual void resetCamera() {}
    /// Bullet's input hooks (unused by our scenes; kept for the shape of the interface).
    virtual bool mouseMoveCallback(float x, float y) {
        (void)x;
        (void)y;
        return false;
    }
    virtual bool mouseButtonCallback(int button, int state, float x, float y) {
        (void)button;
        (void)state;
        (void)x;
        (void)y;
        return false;
    }
    virtual bool keyboardCallback(int key, int state) {
        (void)key;
        (void)state;
        return false;
    }
};

/// One row of the example table (Bullet: ExampleEntry in examples/ExampleBrowser/ExampleEntries.cpp).
struct ExampleEntry {
    int menuLevel;                      ///< 0: a heading, 1: an example
    const char* name;                   ///< shown in the list
    const char* description;            ///< one or two sentences (what to look at)
    ExampleScene::CreateFunc createFunc; ///< null for headings
    int option;                         ///< passed in ExampleOptions::option
};

}  // namespace buoyancy::examples
