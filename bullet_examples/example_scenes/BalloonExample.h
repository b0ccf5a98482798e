#pragma once
/// @file BalloonExample.h
/// Paper Fig. 17: a light balloon rising in air (the scene's fluid is air, 1.2 kg/m³, with its "surface" far
/// above). The balloon is deformable: it inflates over the first seconds and stretches along its motion, and its
/// surface samples are re-baked from the animated vertices every frame (btBuoyancyDeformable), so the
/// lift follows the changing volume.

#include "example_scenes/SceneFileExample.h"

#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>

#include <memory>

namespace buoyancy::examples {

/// The balloon scene (balloon_air.json) with the deformation.
class BalloonExample : public SceneFileExample {
public:
    explicit BalloonExample(ExampleOptions& options);
    void initPhysics() override;
    void renderScene() override;

    /// Inflation factor (radius / rest radius) at time t, s: 0.8 at t = 0 rising smoothly to 1 at t = 3 s.
    static double inflation(double t);
    /// The deformable samples (null when the scene has no balloon).
    const btBuoyancyDeformable* deformable() const { return m_skin.get(); }
    /// Volume enclosed by the current (deformed) samples, m³.
    double currentVolume() const { return m_skin ? m_skin->getVolume() : 0.0; }

protected:
    void afterFrame() override;

private:
    void deform();
    std::shared_ptr<btBuoyancyDeformable> m_skin;
    TriangleMesh m_mesh;          ///< the deformed mesh drawn
    std::uint64_t m_version = 0;
};

}  // namespace buoyancy::examples
