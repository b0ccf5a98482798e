#pragma once
/// @file SceneFrame.h
/// Turn a running scene (cli::SceneWorld) into a RenderFrame: bodies at their mesh world transforms, the
/// water surface sampled from the scene's btWaterSurface on a grid, the ground plane, the force arrows
/// (weight red at the centre of mass, buoyancy green at the centre of buoyancy, drag blue at the centre of
/// mass) and, on request, the surface samples coloured wet (below the water height at their x, z) or dry.
/// A frame is expressed in the scene's water frame (btBuoyancyWorld::getWaterFrame): the renderer's y is the water's
/// up, so the picture, the orbit camera and the browser follow the up axis of a Z-up or oblique scene; the camera
/// block's target is given in world coordinates and mapped. For a +y-up scene these are the world's coordinates.

#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"
#include "render/RenderFrame.h"

namespace buoyancy::render {

/// What buildSceneFrame draws.
struct SceneFrameOptions {
    bool arrows = true;          ///< force arrows (weight red, buoyancy green, drag blue)
    int maxArrowBodies = 12;     ///< no arrows in scenes with more bodies than this (a fleet would be clutter)
    /// Arrow length per newton is body radius / weight: the weight arrow is as long as the body's bounding radius.
    double arrowScale = 1.0;
    bool samples = false;        ///< draw the drag samples as wet/dry points
    int waterResolution = 160;   ///< water grid samples along each side (≥ 2)
    double waterExtent = 0;      ///< half-size of the water grid, m; 0: from the camera distance (interactive
                                 ///< water always uses its own extent)
};

/// A camera that frames every body of the world at its current position (the pictures keep it fixed): it looks at
/// the centre of the bodies' bounding box (pulled towards the water level when the bodies are near it) and moves in
/// until their vertices fill about 60 % of a 16:9 picture's width or height. The scene's "camera" block overrides
/// each field it gives; a given yaw or pitch is used for the fit.
RenderCamera frameSceneCamera(const cli::Scene& scene, const cli::SceneWorld& world);

/// Fill `out` from the world's current state (out.camera is kept: set it with frameSceneCamera or a UI).
void buildSceneFrame(const cli::Scene& scene, const cli::SceneWorld& world, const SceneFrameOptions& options,
                     RenderFrame& out);

/// The dry colour of body number `index` (a fixed palette), linear RGB 0..1.
Eigen::Vector3f bodyColour(std::size_t index);

/// The colour of a body's wet surface: its dry colour darker and more saturated (the same hue, never the water's).
Eigen::Vector3f wetColourOf(const Eigen::Vector3f& dry);

}  // namespace buoyancy::render
