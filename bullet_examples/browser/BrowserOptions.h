#pragma once
/// @file BrowserOptions.h
/// Command line of `buoyancy_browser`:
///   buoyancy_browser [--scene NAME] [--size W H] [--screenshot FILE --frames N] [--list]
/// --screenshot renders N frames at a fixed 1/60 s each (no wall clock: the same picture every run), saves the
/// window (3D view and panels) as a PNG and exits — how the tests and scripts/pictures.sh use it under Xvfb.

#include <string>

namespace buoyancy::browser {

/// Parsed options.
struct BrowserOptions {
    std::string scene = "Buoy in waves"; ///< entry name (ExampleEntries.cpp) or its row number
    int width = 1280, height = 720;      ///< window size, pixels
    std::string screenshot;              ///< PNG to write after `frames` frames, then exit ("" = interactive)
    int frames = 60;                     ///< frames before the screenshot
    bool list = false;                   ///< print the entry names and exit
};

/// Parse argv. @throws std::invalid_argument with a message naming the bad flag
BrowserOptions parseBrowserOptions(int argc, char** argv);

}  // namespace buoyancy::browser
