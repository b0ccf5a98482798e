#pragma once
/// @file RunCommand.h
/// `buoyancy run SCENE.json --out DIR [--duration T]`: the headless scene runner shared by users and
/// tests. Reads and validates the whole scene (SceneFile.h), builds a Bullet world with one
/// btBuoyancyAction per body, steps it with stepSimulation(dt·n, n, dt) per frame and writes
/// DIR/trajectory.csv (docs/scene-format.md). With `--png PNGDIR [--size W H]` it also renders a picture at
/// t = 0 and at every output time through the offscreen renderer (bullet_examples/render).

#include "scene/SceneFrameSink.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace buoyancy::cli {

/// Options of `buoyancy run`.
struct RunOptions {
    std::string scene;               ///< scene JSON file
    std::string out;                 ///< output folder (created when missing)
    std::optional<double> duration;  ///< overrides the scene's "duration", s (≥ 0)
    double import_timeout = 10.0;    ///< s, time limit of the child process that imports each mesh file
    std::string png;                 ///< `--png DIR`: one PNG per output interval ("" = none)
    std::vector<int> size{960, 540}; ///< `--size W H`: picture size, pixels (with --png)
    SceneFrameSinkFactory pngSink;   ///< the offscreen renderer (unset: this build has none, --png is refused)
    bool quiet = false;              ///< `--quiet`: no progress, level-of-detail lines or summary (errors still print)
};

/// Register the `run` subcommand on `app`, writing parsed values into `options`.
void addRunCommand(CLI::App& app, RunOptions& options);

/// Run a scene. @throws UsageError (exit 2) for bad input, InternalError (exit 3) for a non-finite state.
/// @return kExitOk
int runScene(const RunOptions& options);

/// Convenience for tests and embedding: runScene with the exceptions turned into exit codes (0 ok,
/// 2 bad input, 3 internal) and the message printed on stderr; quiet (no progress, no summary).
int runSceneCommand(const std::string& scenePath, const std::string& outDir, std::optional<double> duration);

}  // namespace buoyancy::cli
