#pragma once
/// @file BrowserApp.h
/// The scene browser: a GLFW window with the shared SceneRenderer in the background and Dear ImGui panels —
/// the scene list (ExampleEntries), pause / step / reset, sliders (densities, texture size, drag, wave
/// parameters, permeability), view toggles (force arrows, wet/dry samples, water), a live plot of the submerged
/// volume and the water inside, and the measured cost per physics substep.

#include "browser/BrowserOptions.h"

#include <memory>

namespace buoyancy::browser {

/// Run the browser until the window closes (or the screenshot is written).
/// @return process exit code: 0 ok, 2 bad option or scene, 3 no window / OpenGL context
int runBrowser(const BrowserOptions& options);

}  // namespace buoyancy::browser
