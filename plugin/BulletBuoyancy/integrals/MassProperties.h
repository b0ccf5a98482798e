#pragma once
/// @file MassProperties.h
/// Volume, area, centre and inertia of a body from its surface samples (design.md 2.1, the paper's
/// eqs. 1–8 with the corrections listed there) or exactly from its triangles.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Core>
#include <vector>

namespace buoyancy {

/// Mass properties in the body (mesh) frame.
struct MassProperties {
    double mass = 0;                               ///< kg (for "unit density" results: = volume, m³)
    double volume = 0;                             ///< enclosed volume, m³
    double area = 0;                               ///< surface area, m²
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< centre of mass, m (body frame)
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero(); ///< inertia tensor about `centre`, body axes, kg·m²
};

/// Solid body of uniform density ρ from samples: V = Σ A^y y, first moments Σ A^x x²/2 …, second moments
/// Σ A^x x³/3 …, I = ρ[(tr S)E − S] shifted to the centre (parallel-axis theorem). Paper eqs. 4, 6–8 corrected.
MassProperties solidMassProperties(const SurfaceSamples& samples, double density);

/// Thin shell of uniform density ρ and thickness t (m): mass ρ Σ|A_i| t (the paper's eq. 5 uses A^y; wrong).
MassProperties shellMassProperties(const SurfaceSamples& samples, double density, double thickness);

/// Shell with per-sample areal density σ_i (kg/m²: density × thickness per sample), #S values.
MassProperties shellMassProperties(const SurfaceSamples& samples, const std::vector<double>& arealDensity);

/// Exact polyhedral mass properties of a closed mesh of uniform density (signed tetrahedra from the
/// origin; Mirtich 1996 / Eberly "Polyhedral mass properties"). Used by the exact-mesh method.
MassProperties polyhedronMassProperties(const TriangleMesh& mesh, double density);

/// Principal frame for Bullet: inertia = R · diag(principal) · Rᵀ, R a proper rotation (det +1).
struct PrincipalFrame {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); ///< columns: principal axes in body axes
    Eigen::Vector3d moments = Eigen::Vector3d::Zero();      ///< principal moments, kg·m²
};

/// Diagonalise a symmetric inertia tensor (Eigen::SelfAdjointEigenSolver), right-handed basis.
PrincipalFrame principalFrame(const Eigen::Matrix3d& inertia);

}  // namespace buoyancy
