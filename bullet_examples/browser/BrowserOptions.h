#pragma once
/// @file BrowserOptions.h
/// Command line of `buoyancy_browser`:
///   buoyancy_browser [--scene NAME|NUMBER] [--size W H] [--screenshot FILE --frames N] [--list] [--help]
/// --screenshot renders N frames at a fixed 1/60 s each (no wall clock: the same picture every run), saves the
/// window (3D view and panels) as a PNG and exits — how the tests and scripts/pictures.sh use it under Xvfb.

#include <string>

namespace buoyancy::browser {

/// Parsed options.
struct BrowserOptions {
    std::string scene = "Buoy in waves"; ///< scene name (ExampleEntries.cpp) or its number 1..N (as --list prints)
    int width = 1280, height = 720;      ///< window size, pixels
    std::string screenshot;              ///< PNG to write after `frames` frames, then exit ("" = interactive)
    int frames = 60;                     ///< frames before the screenshot
    bool list = false;                   ///< print the scenes, numbered, and exit
    bool help = false;                   ///< print the usage and exit
};

/// The usage text of `--help` (several lines, ends with a newline).
const char* browserUsage();

/// Parse argv. @throws std::invalid_argument with a message naming the bad flag
BrowserOptions parseBrowserOptions(int argc, char** argv);

}  // namespace buoyancy::browser
