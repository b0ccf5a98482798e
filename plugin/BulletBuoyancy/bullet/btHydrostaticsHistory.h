#pragma once
/// @file btHydrostaticsHistory.h
/// The Bullet layer's names of the temporal level of detail's records, kept for existing code: the classes live in
/// the Bullet-free core, temporal/HydrostaticsHistory.h (design.md 2.5 "Fewer evaluations in time"). New code uses
/// buoyancy::HydrostaticsHistory, buoyancy::HydrostaticsSnapshot and buoyancy::hydrostaticStiffnessCorrection.

#include <BulletBuoyancy/temporal/HydrostaticsHistory.h>

#include <Eigen/Geometry>

/// buoyancy::HydrostaticsSnapshot: what one substep's evaluation of a body gives and where the body was.
using btHydrostaticsSnapshot = buoyancy::HydrostaticsSnapshot;
/// buoyancy::HydrostaticsHistory: the last exact evaluations of one body and their cubic extrapolation.
using btHydrostaticsHistory = buoyancy::HydrostaticsHistory;

/// buoyancy::hydrostaticStiffnessCorrection: move a pressure force, torque (about the COM) and submerged volume
/// evaluated at one pose to a nearby pose (COM `com`, m; `rotation` body → world) through the linear hydrostatic
/// stiffness. @param rhoG  ρ g, N/m³
inline void btHydrostaticStiffnessCorrection(btHydrostaticsSnapshot& predicted, const Eigen::Vector3d& com,
                                             const Eigen::Matrix3d& rotation, double rhoG) {
    buoyancy::hydrostaticStiffnessCorrection(predicted, com, rotation, rhoG);
}
