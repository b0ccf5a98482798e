#pragma once
/// @file SphereHydrostatics.h
/// A sphere in flat water, in closed form (design.md 2.5 "Spheres in flat water"): what a btSphereShape body floats
/// with, exactly and in constant time, instead of the tessellation its mesh is.

#include <BulletBuoyancy/integrals/Hydrostatics.h>

#include <Eigen/Core>

namespace buoyancy {

/// Hydrostatics of the sphere of radius `radius` centred at `centre` (water frame, m) in flat water at height
/// `waterHeight` (m, along y): the spherical cap below the water. With s = waterHeight − centre.y and cap height
/// h = clamp(radius + s, 0, 2 radius): V = π h² (3R − h) / 3; the cap's centroid lies 3 (2R − h)² / (4 (3R − h))
/// below the centre; F = ρ g V ŷ through it; waterline a disc of radius² R² − s²; wetted area 2π R h.
/// @param fluidDensity ρ, kg/m³   @param gravity g, m/s²   @param torqueReference point the torque and the
///        waterplane moments are taken about, m
HydrostaticsResult sphereHydrostatics(const Eigen::Vector3d& centre, double radius, double waterHeight,
                                      double fluidDensity, double gravity, const Eigen::Vector3d& torqueReference);

}  // namespace buoyancy
