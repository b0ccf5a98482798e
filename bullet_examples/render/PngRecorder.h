#pragma once
/// @file PngRecorder.h
/// `buoyancy run SCENE --png DIR [--size W H]`: renders the running scene offscreen (OffscreenContext +
/// SceneRenderer) at t = 0 and at every output time and writes DIR/frame_00000.png, frame_00001.png, …
/// The camera frames the bodies at t = 0 and then stays fixed, so the pictures show the motion.

#include "cli/RunCommand.h"

namespace buoyancy::render {

/// The factory main.cpp puts into RunOptions::pngSink. @throws cli::UsageError when the folder cannot be made
/// or no offscreen OpenGL context can be created (the message says why)
std::unique_ptr<cli::SceneFrameSink> makePngSink(const cli::RunOptions& options, const cli::Scene& scene);

}  // namespace buoyancy::render
