#pragma once
/// @file CapsuleHydrostatics.h
/// A capsule in flat water without tessellation (design.md 2.5 "Capsules in flat water"): what a btCapsuleShape body
/// floats with, to rounding, in constant time.

#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <Eigen/Core>

namespace buoyancy {

/// Hydrostatics of the capsule of radius `radius` whose axis segment runs from centre − halfHeight·axis to
/// centre + halfHeight·axis (the points within `radius` of it; water frame, m) in flat water at height `waterHeight`
/// (m, along y). The capsule is sliced across its axis: each slice is a disc whose wet part is a circular segment in
/// closed form; slices wholly wet or dry integrate in closed form, the band of slices the waterline cuts by a
/// Gauss–Legendre rule in the angle that makes the segment's chord a polynomial, converged to rounding (relative
/// 1e-13 measured, tests/integrals/CapsuleHydrostaticsTest.cpp). F = ρ g V ŷ through the centre of buoyancy; the
/// waterline is the section of the capsule by the water plane, swept by the slices' chords.
/// @param axis unit vector (either sign)   @param halfHeight ≥ 0, m   @param radius > 0, m
/// @param fluidDensity ρ, kg/m³   @param gravity g, m/s²   @param torqueReference point the torque and the
///        waterplane moments are taken about, m
HydrostaticsResult capsuleHydrostatics(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double halfHeight,
                                       double radius, double waterHeight, double fluidDensity, double gravity,
                                       const Eigen::Vector3d& torqueReference);

}  // namespace buoyancy
