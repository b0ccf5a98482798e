#pragma once
/// @file WaveOracle.h
/// Independent reference for hydrostatics in a curved height-field water y = η(x, z) (design.md 5): submerged
/// volume, its first moments, the pressure force and torque of a closed triangle mesh, by the divergence theorem.
/// Written without the library's code or approach (the library clips each triangle against a model of the water
/// over it); takes plain vectors and a height function so it depends on nothing in plugin/.
///
/// With D = min(y − η, 0) and M = (min(y, η)² − η²) / 2 (both 0 above the water), the vertical fields
/// (0, D, 0), (0, x·D, 0), (0, M, 0), (0, z·D, 0) have divergence 1, x, y, z below the water and 0 above, so
///   V = ∮ D n_y dS,  ∫x dV = ∮ x D n_y dS,  ∫y dV = ∮ M n_y dS,  ∫z dV = ∮ z D n_y dS.
/// The hydrostatic pressure P = ρ g (η − y) has −∇P = ρ g (−η_x, 1, −η_z), so the force on the body is
/// F = ρ g ∫_{V_sub} (−η_x, 1, −η_z) dV and the torque about r is ρ g ∫ (p − r) × (−η_x, 1, −η_z) dV: each
/// component is a(x, z) + y·b(x, z), the surface integral ∮ (a D + b M) n_y dS.
/// Each triangle is cut into sub-triangles of edge ≤ maxEdge; sub-triangles the waterline crosses are split 1:4
/// again `waterlineLevels` times (the integrand has a kink there); each piece takes the 6-point degree-4 rule
/// (Dunavant 1985). Gradients of η by central differences (step gradientStep).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

namespace buoyancy_test {

/// Water height η(x, z) at a world point, m.
using WaveHeightFunction = std::function<double(double x, double z)>;

/// What the reference integrates.
struct WaveOracleOptions {
    double maxEdge = 0.1;         ///< longest sub-triangle edge, m (e.g. shortest wavelength / 40)
    int waterlineLevels = 5;      ///< extra 1:4 splits of the sub-triangles the waterline crosses
    bool forceAndTorque = true;   ///< also integrate the force and torque (needs the gradient of η: 4 more queries)
    double gradientStep = 1e-4;   ///< central-difference step of ∇η, m
    /// Triangles whose every corner is higher than this are skipped (dry): the water's highest point, m.
    double waterMax = 1e300;
    /// > 0: η has slope kinks on the vertical lines x = kinkOriginX + i·kinkSpacing and z = kinkOriginZ + j·kinkSpacing
    /// (a bilinear grid): every triangle is first clipped to each lattice cell, so no piece straddles a kink, m.
    double kinkSpacing = 0.0;
    double kinkOriginX = 0.0;  ///< x of one kink line, m
    double kinkOriginZ = 0.0;  ///< z of one kink line, m
};

/// The integrals (world frame).
struct WaveOracleResult {
    double volume = 0;                                  ///< submerged volume, m³
    Eigen::Vector3d firstMoment = Eigen::Vector3d::Zero(); ///< ∫ p dV over the submerged part, m⁴
    Eigen::Vector3d force = Eigen::Vector3d::Zero();    ///< pressure force / (ρ g), m³
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();   ///< pressure torque about the reference / (ρ g), m⁴
    /// Centre of buoyancy firstMoment / volume, m (zero when dry).
    Eigen::Vector3d centreOfBuoyancy() const {
        return volume > 0 ? Eigen::Vector3d(firstMoment / volume) : Eigen::Vector3d::Zero();
    }
};

/// Hydrostatics of the posed closed, outward-oriented mesh (world vertices) in the water η.
/// @param torqueReference  point the torque is taken about, world, m
WaveOracleResult waveOracle(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris,
                            const WaveHeightFunction& eta, const Eigen::Vector3d& torqueReference,
                            const WaveOracleOptions& options = WaveOracleOptions());

/// Submerged volume of the box [x0, x1] × [y_b, y_t] × [z0, z1] under water bilinear in every cell of the lattice
/// x = ox + i·s, z = oz + j·s, when its bottom is wet and its top dry everywhere: the sum over the rectangles where
/// the footprint meets a cell of their area × (η at their centre − y_b) (a bilinear function's mean over a rectangle
/// is its value at the centre), m³.
double bilinearBoxVolume(const WaveHeightFunction& eta, double ox, double oz, double s, double x0, double x1, double z0,
                         double z1, double yBottom);

/// Submerged volume of the box [x0, x1] × [y_b, y_t] × [z0, z1] under an Airy wave η = a cos(k x + φ) whose crests
/// run along z, when its bottom is wet and its top dry everywhere: V = L_z [(a/k)(sin(k x1 + φ) − sin(k x0 + φ))
/// − y_b (x1 − x0)], m³ (closed form: ∫ (η − y_b) dx dz).
double airyBoxVolume(double a, double k, double phase, double x0, double x1, double yBottom, double lengthZ);

}  // namespace buoyancy_test
