#pragma once
/// @file btBuoyancySettings.h
/// Tuning of the buoyancy of one body (Bullet's btRaycastVehicle::btVehicleTuning / Jolt's
/// *Settings style): public members with documented defaults, validated once when a shape or an action
/// is built.

#include <cstddef>
#include <string>

/// How the buoyancy integrals are evaluated (DESIGN-NOTES 1.1, 2.4).
enum class btBuoyancyMethod {
    Auto,          ///< the library default: ExactMesh for small meshes, else ExactCoverage (btBuoyancyResolveMethod)
    TexelCentre,   ///< the paper's texel-centre baking (erratic convergence, Σ A ≠ 0; for comparison)
    ExactCoverage, ///< surface samples baked by exact texel coverage (Σ A = 0, O(h²) waterline error)
    ExactMesh,     ///< every triangle clipped against the water each substep (exact in flat water)
};

/// Name used in scene files and on the command line: "default", "texel-centre", "exact-coverage", "exact-mesh"
/// (buoyancy::buoyancyMethodName; Auto is "default").
const char* btBuoyancyMethodName(btBuoyancyMethod method);
/// Parse a name of btBuoyancyMethodName ("auto" is accepted for "default"). @throws std::invalid_argument naming the unknown value
btBuoyancyMethod btBuoyancyMethodFromName(const std::string& name);

/// Per-body buoyancy settings. Fluid density, gravity and the water surface belong to btBuoyancyWorld.
struct btBuoyancySettings {
    ///@name Integration method and level of detail
    btBuoyancyMethod method = btBuoyancyMethod::Auto; ///< see btBuoyancyMethod
    /// N of the N×N sample texture (sampled methods), 1..16384, typical 64–512; 0 = the library default for
    /// the resolved method (buoyancy::defaultTextureSize; 512 when Auto picks exact-coverage).
    int textureSize = 0;
    bool preferModelUvs = true;         ///< sampled methods: use the model's UVs when they are a valid layout

    ///@name Drag (DESIGN-NOTES 2.6, paper eq. 12)
    /// Pressure-drag coefficient C_d per front-facing wetted sample, dimensionless, ≥ 0; 0 turns pressure drag
    /// off. The per-sample model gives a convex body ½ρ C_d A_silhouette |v|²: real values lie between a
    /// sphere (≈ 0.47) and a flat plate (≈ 1.2); 1.0 is a middle that damps bobbing convincingly.
    double dragCoefficient = 1.0;
    /// Skin-friction coefficient C_f on the tangential relative velocity, dimensionless, ≥ 0; typical
    /// 0.003–0.01 for a hull; 0 (default) turns it off.
    double skinFriction = 0.0;
    /// Linear pressure damping b, m/s, ≥ 0: per wetted sample F_i = −ρ b (A_i·v_i) Â_i. Stands for what
    /// quadratic drag misses at low speed (wave radiation, which is what really brings a bobbing body to
    /// rest; viscous damping). Not in the paper. For a box heaving with waterplane area A and mass m it gives
    /// a damping ratio ζ = b sqrt(ρ A) / (2 sqrt(g m)): 0.3 gives ζ ≈ 0.1 for a 2×0.4×1 m plank at s = 0.75,
    /// ≈ 0.2 for a 10 cm cube at s = 0.5. 0 turns it off (then a small bobbing decays only like 1/t).
    double linearDamping = 0.3;

    ///@name Added mass (DESIGN-NOTES 2.7)
    /// Apply added mass m_a = C_a ρ_w V_sub to the linear motion (one scalar, Stonefish-style; rotation has
    /// none). Keeps light bodies (density ratio ≪ 1) stable at game time steps.
    bool addedMass = true;
    double addedMassCoefficient = 0.5; ///< C_a, dimensionless, ≥ 0; 0.5 is exact for a fully submerged sphere

    ///@name Features
    bool buoyancyEnabled = true; ///< pressure force and torque (DESIGN-NOTES 2.3); off leaves only drag

    /// Check every field. @throws std::invalid_argument whose message names the field and the value
    void validate() const;
};

/// The concrete method Auto stands for, given the mesh's triangle count (delegates to
/// buoyancy::resolveMethod, the one place that decides the library default); others are returned unchanged.
btBuoyancyMethod btBuoyancyResolveMethod(const btBuoyancySettings& settings, std::size_t triangleCount);

/// The texture size used for a resolved sampled method: settings.textureSize, or the library default when 0.
int btBuoyancyResolveTextureSize(const btBuoyancySettings& settings, btBuoyancyMethod resolved);
