#pragma once
/// @file PolyhedralOracle.h
/// Independent exact reference for tests (design.md 5): dry and submerged volume, centroid and second
/// moments of a closed triangle mesh, computed by signed tetrahedra and triangle clipping. Written without
/// the library's code or approach (the library integrates Eberly's per-face polynomials and the fields of
/// design.md 2.2); takes plain vectors so it depends on nothing in plugin/.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace buoyancy_test {

/// Exact integrals over a solid region.
struct OracleMoments {
    double volume = 0;                                  ///< ∫ 1 dv, m³
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); ///< ∫ r dv / V, m (zero when V = 0)
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();   ///< S = ∫ r rᵀ dv about the origin, m⁵
    /// Inertia tensor of unit density about the centroid: (tr S_c) E − S_c with S_c = S − V c cᵀ, m⁵.
    Eigen::Matrix3d inertiaAboutCentroid() const;
};

/// Dry integrals of a closed, outward triangle mesh: Σ over faces of the signed tetrahedron (ref, a, b, c),
/// with the closed-form tetrahedron covariance ∫ r rᵀ = V/20 (Σ v_i v_iᵀ + (Σ v_i)(Σ v_i)ᵀ).
/// @param[in] verts  #V positions, m   @param[in] tris  #T index triples (outward CCW)
OracleMoments oracleDryMoments(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris);

/// Part of the (already posed) closed mesh below the plane y = h: each triangle is clipped against the
/// plane (keeping y ≤ h) and the kept polygons are closed with signed tetrahedra whose apex lies ON the
/// plane, so the cap faces (in the plane) contribute zero and need not be built.
OracleMoments oracleSubmergedMoments(const std::vector<Eigen::Vector3d>& verts,
                                     const std::vector<Eigen::Vector3i>& tris, double h);

/// Area of the cut of the closed mesh by the plane y = h (the waterline/cap area), m², from the oriented
/// cut segments with the 2D shoelace formula (no use of face normals).
double oracleCapArea(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris, double h);

/// Total surface area, m².
double oracleSurfaceArea(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris);

/// Apply a rigid pose to every vertex.
std::vector<Eigen::Vector3d> oraclePose(const std::vector<Eigen::Vector3d>& verts, const Eigen::Isometry3d& pose);

/// @name Analytic helpers (design.md 5)
///@{
/// Volume of a ball of radius R, m³.
double sphereVolume(double R);
/// Volume of a spherical cap of height h (0 ≤ h ≤ 2R), m³: π h² (3R − h) / 3.
double sphereCapVolume(double R, double h);
/// Distance from the sphere centre to the centroid of a cap of height h: 3 (2R − h)² / (4 (3R − h)), m.
double sphereCapCentroidDistance(double R, double h);
/// Box a×b×c (x, y, z extents, centred at the origin, axis-aligned) in water y = h: submerged volume, m³.
double boxSubmergedVolume(double a, double b, double c, double h);
/// Height (y) of the centre of buoyancy of that box, m (meaningless when dry).
double boxCentreOfBuoyancyY(double a, double b, double c, double h);
/// Inertia of a solid box a×b×c of unit density about its centre (diagonal), m⁵.
Eigen::Matrix3d boxInertia(double a, double b, double c);
/// Inertia of a solid ball of radius R, unit density: (2/5) M R² on the diagonal, m⁵.
Eigen::Matrix3d sphereInertia(double R);
///@}

}  // namespace buoyancy_test
