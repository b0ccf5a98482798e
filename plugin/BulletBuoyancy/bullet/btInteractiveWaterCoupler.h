#pragma once
/// @file btInteractiveWaterCoupler.h
/// The two-way seam between btBuoyancyAction and btInteractiveWaterSurface: a btActionInterface added to
/// the dynamics world AFTER the bodies' buoyancy actions (Bullet calls actions in the order added, once
/// per substep). Each substep it reads every registered action's last displaced volume and moves that water
/// out of the body's old footprint and into its new one (addVolumeChange), then steps the grid by dt. The
/// footprint is the disc of the body's bounding sphere under its bounds centre: constant in size, and covering
/// every point where the body reads the water, so the raised ring is never under the body. The actions' hot path is untouched: they only
/// see a height field.
///
/// Usage:  btInteractiveWaterSurface water(20, 20, 128, 2.0, 0.1);  btBuoyancyWorld ctx(&water);
///         ... add bodies and their actions ...;  btInteractiveWaterCoupler coupler(&water, &ctx);
///         dynamicsWorld->addAction(&coupler);   // last

#include <BulletDynamics/Dynamics/btActionInterface.h>

#include <cstddef>
#include <unordered_map>
#include <vector>

class btInteractiveWaterSurface;
class btBuoyancyWorld;
class btBuoyancyAction;

/// Feeds bodies' displaced volumes into an interactive water grid and steps it once per substep.
class btInteractiveWaterCoupler : public btActionInterface {
public:
    /// @param water  the grid (not owned); should be the surface of `world`
    /// @param world  the buoyancy context whose registered actions disturb the water (not owned)
    /// @throws std::invalid_argument for a null argument
    /// @param coupling  fraction κ of each change of displaced volume that pushes the grid, (0, 1]. The body
    ///                  reads the surface it depresses, a loop of gain ≈ κ per substep: κ = 1 is marginal
    ///                  and unstable for footprints of a few cells; 0.25 (default) keeps it damped.
    btInteractiveWaterCoupler(btInteractiveWaterSurface* water, const btBuoyancyWorld* world, double coupling = 0.25);

    /// Once per substep: push the water by each body's change of displaced volume, then step the grid by dt.
    void updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) override;
    void debugDraw(btIDebugDraw*) override {}

    /// Total volume the bodies currently displace (as last fed to the grid), m³.
    double displacedVolume() const;

    ///@name Save and restore (btBuoyancyState.h, docs/integration.md "Save and restore")
    /// The interactive water's state as a versioned blob of bytes: the grid's elevations (m), velocities (m/s), level
    /// offset and height range, and each body's footprint last fed to it (centre, m; displaced volume, m³; radius, m),
    /// its action named by its index in the world's getActions(). Call between stepSimulation calls.
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote into this coupler and its grid (the same ones, or ones built the same way with
    /// the actions registered in the same order). Read and checked whole before anything changes.
    /// @param data, size  the blob (size in bytes)
    /// @throws std::invalid_argument naming the problem, the coupler and the grid unchanged: not a state blob, another
    ///         format version or precision, another kind of blob, truncated or corrupted, a grid of other cell counts,
    ///         or a footprint of an action index the world does not have
    void restoreState(const unsigned char* data, std::size_t size);
    /// restoreState of a whole vector. @throws std::invalid_argument (see above)
    void restoreState(const std::vector<unsigned char>& blob) { restoreState(blob.data(), blob.size()); }
    ///@}

private:
    struct Footprint {
        double x = 0, z = 0, volume = 0, radius = 0;
    };
    btInteractiveWaterSurface* m_water;
    const btBuoyancyWorld* m_world;
    double m_coupling;
    std::unordered_map<const btBuoyancyAction*, Footprint> m_last;
};
