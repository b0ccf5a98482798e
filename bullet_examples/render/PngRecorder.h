#pragma once
/// @file PngRecorder.h
/// `buoyancy run SCENE --png DIR [--size W H]`: renders the running scene offscreen (OffscreenContext +
/// SceneRenderer) at t = 0 and at every output time and writes DIR/frame_00000.png, frame_00001.png, …
/// The camera frames the bodies at t = 0 and then stays fixed, so the pictures show the motion. Each picture
/// carries its time ("t = 2.5 s", FrameLabel.h) in its top-left corner.

#include "scene/SceneFrameSink.h"

namespace buoyancy::render {

/// The factory main.cpp puts into RunOptions::pngSink: pictures of `width` × `height` pixels into `folder`.
/// @throws cli::UsageError when the folder cannot be made or no offscreen OpenGL context can be created (the
/// message says why)
std::unique_ptr<cli::SceneFrameSink> makePngSink(const std::string& folder, int width, int height, const cli::Scene& scene);

}  // namespace buoyancy::render
