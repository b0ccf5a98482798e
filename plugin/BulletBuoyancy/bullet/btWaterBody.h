#pragma once
/// @file btWaterBody.h
/// A bounded water body of a btBuoyancyWorld: a water surface (any btWaterSurface) inside an axis-aligned box of the
/// world, with its own fluid density (a pool, a lake, a lock chamber). A world holds either one unbounded water
/// (btBuoyancyWorld's constructor, the default) or several water bodies whose boxes do not overlap
/// (btBuoyancyWorld::addWaterBody; docs/integration.md, design.md 2.9).
///
/// The water of a body fills its box from the box's bottom up to the surface: the box's sides and bottom bound it,
/// its top should be at or above the surface's highest point (the surface is not cut off at the top). Heights are
/// measured along the world's water frame's up (btWaterFrame), as for the unbounded water.

#include <LinearMath/btVector3.h>

#include <Eigen/Core>

#include <string>

class btWaterSurface;

/// What a water body is made of (btBuoyancyWorld::addWaterBody copies it).
struct btWaterBodyInfo {
    /// Name used in messages, e.g. "pool" (empty: "water body <index>").
    std::string name;
    /// The water surface inside the region; not owned, must outlive the world. Its velocities (btFlatWaterSurface's
    /// uniform current, btRiverSurface's current along its channel, waves' orbital velocities) are the water's velocity
    /// in the region.
    const btWaterSurface* surface = nullptr;
    /// ρ_w, kg/m³ (fresh water 1000, sea water 1025), finite and > 0.
    double fluidDensity = 1000.0;
    /// Lower corner of the region's axis-aligned box, world, m; each coordinate finite and < regionMax's.
    btVector3 regionMin = btVector3(0, 0, 0);
    /// Upper corner of the region's axis-aligned box, world, m.
    btVector3 regionMax = btVector3(0, 0, 0);
};

/// A water body as the world holds it (the region in double precision).
struct btWaterBody {
    std::string name;                          ///< as given, or "water body <index>"
    const btWaterSurface* surface = nullptr;   ///< not owned
    double fluidDensity = 1000.0;              ///< kg/m³
    Eigen::Vector3d regionMin = Eigen::Vector3d::Zero();  ///< lower box corner, world, m
    Eigen::Vector3d regionMax = Eigen::Vector3d::Zero();  ///< upper box corner, world, m

    /// Distance from `point` (world, m) to the region's box, m (0 inside or on it).
    double distanceTo(const Eigen::Vector3d& point) const {
        const Eigen::Vector3d outside = (regionMin - point).cwiseMax(point - regionMax).cwiseMax(0.0);
        return outside.norm();
    }
};
