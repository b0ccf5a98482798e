#pragma once
/// @file WaterMassProperties.h
/// Mass properties of the water in a graph (paper eqs. 15–17) and their composition with the dry body
/// (paper section 4.4, corrected: design.md 4).
///
/// Eq. 15: M_G = ρ Σ v_n; eq. 16: C_G = Σ m_n r_n / M_G; eq. 17: point-mass inertia. Improvement: r_n is
/// the centre of node n's water at the current pose (it lies at the bottom of the node in world down),
/// not the node position, so the centre moves as the body heels (the free-surface effect). The paper's
/// "I + I_G" holds only about a common point: the composition shifts both tensors to the common centre
/// of mass with the parallel-axis theorem.

#include <BulletBuoyancy/graph/WaterGraphState.h>
#include <BulletBuoyancy/integrals/MassProperties.h>

namespace buoyancy {

/// Water of the graph, body frame: mass (kg), volume (m³), centre (m) and inertia about that centre (kg·m²).
/// Each node's water sits at its free-surface centroid; its inertia is a point mass there (paper eq. 17,
/// WaterInertiaModel::PointMass) or, by default, the rigid inertia of its shape (sphere cap / clipped box)
/// about that centroid plus the parallel-axis term. All zero when the graph is dry.
/// @param fluidDensity ρ, kg/m³
MassProperties waterMassProperties(const WaterGraphState& state, double fluidDensity);

/// Parallel-axis term M (|d|² E − d dᵀ) (Steiner), kg·m².
Eigen::Matrix3d parallelAxisTerm(double mass, const Eigen::Vector3d& d);

/// Two bodies as one: M = M_a + M_b, C = (M_a C_a + M_b C_b)/M, I = I_a + M_a S(C_a − C) + I_b + M_b S(C_b − C)
/// with each I about its own centre. Volumes and areas add. A zero-mass part is ignored.
MassProperties composeMassProperties(const MassProperties& a, const MassProperties& b);

}  // namespace buoyancy
