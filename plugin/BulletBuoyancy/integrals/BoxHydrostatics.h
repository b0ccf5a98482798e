#pragma once
/// @file BoxHydrostatics.h
/// A box in flat water, exactly (design.md 2.5 "Boxes in flat water"): what a btBoxShape body floats with, in
/// constant time, without the general mesh path's per-triangle work.

#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace buoyancy {

/// Hydrostatics of the box of half extents `halfExtents` (m, along its own axes) centred at the origin of `pose`
/// (box frame → water frame) in flat water at height `waterHeight` (m, along y): the part of the box below the
/// water, clipped face by face. Volume and centre of buoyancy from the divergence theorem with the apex on the water
/// plane (the waterline polygon then adds nothing); waterline area and waterplane moments from the waterline's
/// segments (Green's theorem); F = ρ g V ŷ through the centre of buoyancy; wetted area the clipped faces' area.
/// Exact to rounding at every attitude and depth.
/// @param fluidDensity ρ, kg/m³   @param gravity g, m/s²   @param torqueReference point the torque and the
///        waterplane moments are taken about, m
HydrostaticsResult boxHydrostatics(const Eigen::Isometry3d& pose, const Eigen::Vector3d& halfExtents,
                                   double waterHeight, double fluidDensity, double gravity,
                                   const Eigen::Vector3d& torqueReference);

}  // namespace buoyancy
