#pragma once
/// @file NodeLevel.h
/// The water level of one water-graph node (design.md 4): the water of a partly filled node sits at
/// the bottom of its level model in the world's "down" direction. Heights are measured from the node's
/// centre along world up (expressed in body axes), so the functions are independent of the body's
/// position; add the node centre's world y to get a world level.
///
/// Sphere model: a sphere of the node's capacity, R = (3C/4π)^(1/3); a cap of height k holds
/// π k² (3R − k)/3 and its centroid lies 3(2R − k)² / (4(3R − k)) from the centre (textbook spherical cap).
/// Box model: the node's box (extents `size`, body axes) cut by the horizontal plane, exact polyhedral
/// volume and centroid of the part below; volumes are scaled by capacity / (size.x·size.y·size.z).

#include <BulletBuoyancy/graph/WaterGraph.h>

#include <Eigen/Core>

namespace buoyancy {

/// Half height of the node's level model along `up`: levels range over [−H, H] from the centre, m.
/// @param up  world up in body axes (unit)
double nodeHalfHeight(const WaterNode& node, const Eigen::Vector3d& up);

/// Water volume the node holds when its level is `h` above its centre (clamped to [−H, H]), m³.
double nodeVolumeBelow(const WaterNode& node, const Eigen::Vector3d& up, double h);

/// Level h (m above the centre, along up) at which the node holds `volume` (clamped to [0, capacity]).
/// Sphere: closed-form root of the cap cubic plus a Newton polish; box: bisection to 1e-12 of H.
double nodeLevelForVolume(const WaterNode& node, const Eigen::Vector3d& up, double volume);

/// Centre of the node's water when it holds `volume`, body frame, m (the node position when full or empty).
Eigen::Vector3d nodeWaterCentroid(const WaterNode& node, const Eigen::Vector3d& up, double volume);

/// Inertia of the node's water about its own centroid, body axes, for a density of 1 kg/m³ (kg·m² per kg/m³):
/// the rigid inertia of the water's shape (sphere model: the bottom spherical cap, closed form; box model: the
/// box clipped by the level plane, exact polyhedral second moments), scaled to `volume`. Zero when empty.
/// Multiply by ρ; add the parallel-axis term for another point (WaterMassProperties).
Eigen::Matrix3d nodeWaterInertia(const WaterNode& node, const Eigen::Vector3d& up, double volume);

/// Exact volume and first moment of the part of an axis-aligned box (centred at the origin, half extents
/// `half`) below the plane x·up = h (up unit). Signed tetrahedra from a point of the plane, so the cap
/// face contributes nothing (divergence theorem). @param[out] moment ∫x dV, m⁴
double boxVolumeBelowPlane(const Eigen::Vector3d& half, const Eigen::Vector3d& up, double h, Eigen::Vector3d& moment);

}  // namespace buoyancy
