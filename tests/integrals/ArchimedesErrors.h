#pragma once
/// @file ArchimedesErrors.h
/// Errors of a flat-water hydrostatic result against the exact polyhedral oracle and Archimedes' principle
/// (design.md 5): ρ g V_sub upward through the oracle's centre of buoyancy. Shared by the exact-mesh tests
/// (clip every triangle: HydrostaticsTest.cpp; moment tree: TreeHydrostaticsTest.cpp).

#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include "oracles/PolyhedralOracle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace buoyancy_test {

/// Relative errors of one result (see archimedesErrors).
struct ArchimedesErrors {
    double volume = 0;  ///< |V − V_oracle| / V_full
    double force = 0;   ///< |F − ρgV_oracle ŷ| / (ρ g V_full)
    double torque = 0;  ///< |τ − (c_oracle − ref) × F_oracle| / (ρ g V_full diag)
    double centre = 0;  ///< |C_B − c_oracle| / diag, 0 when under 1e-6 of the volume is wet (C_B undefined)

    /// Keep the larger of each error (a running worst case over many results).
    void takeWorst(const ArchimedesErrors& e) {
        volume = std::max(volume, e.volume);
        force = std::max(force, e.force);
        torque = std::max(torque, e.torque);
        centre = std::max(centre, e.centre);
    }
};

/// Compare `r` (computed about `ref` with density rho and gravity g) with the oracle's submerged moments `o`.
/// @param fullVolume the body's volume, m³   @param diag its bounding-box diagonal, m
inline ArchimedesErrors archimedesErrors(const buoyancy::HydrostaticsResult& r, const OracleMoments& o, double fullVolume,
                                         double diag, const Eigen::Vector3d& ref, double rho, double g) {
    ArchimedesErrors e;
    e.volume = std::abs(r.submerged_volume - o.volume) / fullVolume;
    const Eigen::Vector3d Fa(0, rho * g * o.volume, 0);
    e.force = (r.force - Fa).norm() / (rho * g * fullVolume);
    e.torque = (r.torque - (o.centroid - ref).cross(Fa)).norm() / (rho * g * fullVolume * diag);
    if (o.volume > 1e-6 * fullVolume) e.centre = (r.centre_of_buoyancy - o.centroid).norm() / diag;
    return e;
}

}  // namespace buoyancy_test
