#pragma once
/// @file BuoyancyBulletExample.h
/// The adapter between our example scenes (bullet_examples/example_scenes: a scene file, its world built by
/// cli::buildSceneWorld) and Bullet's ExampleBrowser (examples/CommonInterfaces/CommonRigidBodyBase.h). The scene
/// owns the Bullet world; the adapter only shows it with Bullet's GUI helper: every body as a graphics shape made
/// from its own triangle mesh (our palette colours; the balloon's deformed surface re-uploaded each frame), the
/// ground plane, the water surface as a translucent mesh, and the force arrows (weight red, buoyancy green, drag
/// blue) drawn through the world's btIDebugDraw. The camera and the up axis come from the scene. Mouse picking is
/// Bullet's own (it drags bodies of our world).

#include "CommonInterfaces/CommonRigidBodyBase.h"
#include "example_scenes/ExampleInterface.h"

#include <memory>
#include <vector>

namespace buoyancy::examples {
class SceneFileExample;
}

/// One of our scenes inside Bullet's ExampleBrowser.
class BuoyancyBulletExample : public CommonRigidBodyBase {
public:
    /// @param options     the browser's options (its GUI helper draws everything)
    /// @param createScene one of our create functions (bullet_examples/example_scenes/ExampleEntries.h); the scene
    ///                    must be a SceneFileExample (all of ours are)
    BuoyancyBulletExample(CommonExampleOptions& options, buoyancy::examples::ExampleScene::CreateFunc createScene);
    ~BuoyancyBulletExample() override;

    /// Build the scene's world and its graphics. A scene file that fails to load or build is reported on stderr
    /// and leaves an empty example (the browser keeps running).
    void initPhysics() override;
    /// Forget the graphics' link to the world, then destroy the world (the scene owns it, not the base class).
    void exitPhysics() override;
    /// Advance whole fixed frames of the scene (dt · substeps_per_frame), as `buoyancy run` does.
    void stepSimulation(float deltaTime) override;
    /// Bodies through the GUI helper, then the water surface and the force arrows.
    void renderScene() override;
    /// Bullet's wireframe view: the base class's debug drawing (actions draw their buoyancy and drag forces).
    void physicsDebugDraw(int debugFlags) override;
    /// The scene's camera (its "camera" block, else framing the bodies) in Bullet's yaw/pitch convention.
    void resetCamera() override;

private:
    /// One graphics shape and instance per body, from its triangle mesh in the rigid body's frame; the ground plane.
    void createBodyGraphics();
    /// The water surface's mesh (the frame's height grid) and its translucent instance; none for air.
    void createWaterGraphics();
    /// Refill m_waterVertices from the frame's water heights (world coordinates, normals from the height field).
    void updateWaterGraphics();
    /// Re-upload the meshes whose RenderBody::meshVersion changed (the balloon).
    void updateDeformedBodies();
    /// The frame's force arrows as lines (with heads) through the world's debug drawer.
    void drawArrows();
    /// Unattended runs: BUOYANCY_EXAMPLE_FRAMES=N quits after N frames (printing a summary line),
    /// BUOYANCY_EXAMPLE_PNG=FILE saves the last one.
    void frameLoopHook();

    buoyancy::examples::ExampleOptions m_sceneOptions;
    std::unique_ptr<buoyancy::examples::SceneFileExample> m_scene;
    int m_upAxis = 1;                      ///< Bullet's up axis: 1 (y) or 2 (z), from the scene's gravity
    int m_waterShape = -1;                 ///< graphics shape of the water mesh, -1: none
    std::vector<float> m_waterVertices;    ///< GLInstanceVertex layout: xyzw, normal, uv (9 floats)
    std::vector<int> m_bodyShapes;         ///< graphics shape per body, -1: none
    std::vector<unsigned long long> m_bodyMeshVersions; ///< last uploaded mesh version per body
    long m_frames = 0;                     ///< frames rendered
};
