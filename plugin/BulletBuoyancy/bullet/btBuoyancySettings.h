#pragma once
/// @file btBuoyancySettings.h
/// Tuning of the buoyancy of one body (Bullet's btRaycastVehicle::btVehicleTuning / Jolt's
/// *Settings style): public members with documented defaults, validated once when a shape or an action
/// is built.

#include <BulletBuoyancy/integrals/BuoyancyMethod.h>

#include <cstddef>
#include <string>

/// How the buoyancy integrals are evaluated (design.md 1.1, 2.4, 8.2): the Bullet-style name of the library's one
/// method enumeration, buoyancy::BuoyancyMethod (integrals/BuoyancyMethod.h):
///   Auto           the library default: ExactMesh for small meshes, else ExactCoverage (btBuoyancyResolveMethod);
///   TexelCentre    the paper's texel-centre baking (erratic convergence, Σ A ≠ 0; for comparison);
///   ExactCoverage  surface samples baked by exact texel coverage (Σ A = 0, O(h²) waterline error);
///   ExactMesh      every triangle clipped against the water each substep (exact in flat water).
/// What each method prepares and evaluates: buoyancy::integrationMethod (integrals/IntegrationMethod.h).
using btBuoyancyMethod = buoyancy::BuoyancyMethod;

/// Name used in scene files and on the command line: "default", "texel-centre", "exact-coverage", "exact-mesh"
/// (buoyancy::buoyancyMethodName; Auto is "default").
const char* btBuoyancyMethodName(btBuoyancyMethod method);
/// Parse a name of btBuoyancyMethodName ("auto" is accepted for "default"). @throws std::invalid_argument naming the unknown value
btBuoyancyMethod btBuoyancyMethodFromName(const std::string& name);

/// How the water's own acceleration Du/Dt acts on a body's linear motion (btBuoyancySettings::waterAcceleration,
/// design.md 2.7, "The water's acceleration"). Du/Dt is taken at the centre of buoyancy: both terms are meant for
/// bodies small against the wavelength (Morison's regime); over a body as long as the waves they are one point's.
enum class btWaterAccelerationForce {
    /// Not at all: the added mass acts on the body's absolute acceleration, (m + m_a) a = F − m g (no query).
    None,
    /// The added mass acts on the acceleration relative to the water: (m + m_a) a = F − m g + m_a Du/Dt, N. Nothing
    /// without btBuoyancySettings::addedMass.
    AddedMass,
    /// AddedMass, and the pressure force's part beyond the buoyancy ρ g V_sub (the hydrostatic pressure below the
    /// local surface, whose wave force does not decay with depth and has no vertical part on a submerged body) is
    /// replaced by linear wave theory's Froude–Krylov force ρ V_sub Du/Dt, N: a small body then rides the waves
    /// (it follows the orbital motion of the water around it). Not for bodies comparable with the wavelength; not
    /// applied while a body straddles water bodies or with buoyancyEnabled off. btBuoyancyResult::buoyancyForce stays
    /// the integrated pressure force; linearImpulse holds what was applied.
    AddedMassAndFroudeKrylov,
};

/// Per-body buoyancy settings. Fluid density, gravity and the water surface belong to btBuoyancyWorld.
struct btBuoyancySettings {
    ///@name Integration method and level of detail
    btBuoyancyMethod method = btBuoyancyMethod::Auto; ///< see btBuoyancyMethod
    /// N of the N×N sample texture (sampled methods), 1..16384, typical 64–512; 0 = the library default for
    /// the resolved method (buoyancy::IntegrationMethod::defaultTextureSize; 512 when Auto picks exact-coverage).
    int textureSize = 0;
    bool preferModelUvs = true;         ///< sampled methods: use the model's UVs when they are a valid layout
    /// Automatic level of detail: the worst submerged-volume error allowed, % of the body's volume
    /// (e.g. 0.1). When > 0 and `method` is Auto, the method and texture size are picked as the cheapest
    /// configuration whose measured worst error (docs/benchmarks, × 2 margin) fits
    /// (btBuoyancyPickLevelOfDetail says which); with ExactCoverage or TexelCentre only N is picked. An explicit
    /// textureSize > 0 still wins. 0 (default) = no budget: the library default rule (exact-mesh up to 131072
    /// triangles, else exact-coverage 512²).
    double errorBudget = 0.0;

    ///@name Drag (design.md 2.6, paper eq. 12)
    /// Pressure-drag coefficient C_d per front-facing wetted sample, dimensionless, ≥ 0; 0 turns pressure drag
    /// off. The per-sample model gives a convex body ½ρ C_d A_silhouette |v|²: real values lie between a
    /// sphere (≈ 0.47) and a flat plate (≈ 1.2); 1.0 is a middle that damps bobbing convincingly.
    double dragCoefficient = 1.0;
    /// Skin-friction coefficient C_f on the tangential relative velocity, dimensionless, ≥ 0; typical
    /// 0.003–0.01 for a hull; 0 (default) turns it off.
    double skinFriction = 0.0;
    /// Wave-radiation damping β, dimensionless, 0..10; 0 turns it off. A body moving at the free surface makes waves
    /// that carry its energy away: this is what brings a bobbing body to rest. Applied as a linear pressure damping
    /// per wetted sample, F_i = −ρ b (A_i·v_i) Â_i, with a coefficient that scales with the body and fades with depth
    /// like the energy of the waves it makes (design.md 2.6, "Radiation damping"):
    ///   b = β g / ω_n · e^(−2 k d) · (1 − d / (3 D))²   for d < 3 D, else 0,
    /// ω_n² = ρ g A_ref / (m + m_a) the body's heave frequency (A_ref its waterplane area, at least ½ V^(2/3)),
    /// k = ω_n² / g the wavenumber of the waves it makes at that frequency, d the depth of the top of its bounding
    /// sphere under the water (0 while it pierces the surface), D that sphere's diameter. Geometrically similar
    /// bodies get the same damping ratio: ζ = β/3 in heave for a half-immersed sphere, β/2 for a wall-sided box.
    /// Default 0.3: ζ = 0.10 for the half-immersed sphere, against Hulme (1982)'s 0.08–0.13 at resonance
    /// (docs/accuracy.md); a body deeper than three of its sizes gets none (its terminal velocity is the drag law's).
    double radiationDamping = 0.3;
    /// Depth-independent linear (viscous) damping b_v, m/s, 0..100, added to the radiation damping's b at every depth:
    /// per wetted sample F_i = −ρ b_v (A_i·v_i) Â_i. For a box heaving with waterplane area A and mass m it gives a
    /// damping ratio ζ = b_v sqrt(ρ A) / (2 sqrt(g m)); for a body sinking at speed v it lowers the terminal velocity
    /// by about b_v / v (a sphere: (2/3) b_v / (½ C_d v)). Default 0 (off): deep terminal velocities are the drag law's.
    double linearDamping = 0.0;

    ///@name Level of detail (design.md 2.5: doing less work)
    /// Drag level of detail: at most this many drag samples per body, made by merging the shape's fine drag
    /// samples (face sub-samples or texture samples) into clusters of nearby samples facing about the same way
    /// (buoyancy::clusterDragSamples). One water query per cluster instead of per fine sample. 0 = no merging
    /// (every fine sample). Each cluster is evaluated at two points along its spread, so a rotating face keeps its
    /// damping torque. Typical 64–1024; default 256 (64 left a rolling log and a light floating cylinder
    /// under-damped in tests/bullet; the drag error against the fine sum is in docs/benchmarks/drag_lod.csv — drag
    /// coefficients are uncertain to ±20 % anyway). 0..1000000.
    int dragClusters = 256;
    /// Water-velocity probes for drag on a non-flat or moving surface: the water velocity is queried at this
    /// many points (the drag clusters merged again) and each cluster uses its nearest probe's velocity
    /// (buoyancy::assignVelocityProbes). 0 = one query per cluster. Default 32. 0..1000000.
    int waterVelocityProbes = 32;
    /// Wave queries: on a Gerstner surface (whose query is a Newton inversion; grid, FFT and interactive surfaces
    /// answer by a cheaper lookup and are always queried exactly) the water height under the body is queried on a waterPatchNodes ×
    /// waterPatchNodes grid over its footprint and interpolated (buoyancy::WaterPatch, bicubic) instead of
    /// queried at every vertex / sample. 0 = query every point exactly. 5..64 otherwise; default 8, the fewest nodes
    /// a patch gets (see waterPatchNodesPerWavelength; the error it adds is measured in docs/benchmarks). Flat water
    /// is never affected.
    int waterPatchNodes = 8;
    /// Patch resolution against the waves: the grid spacing is at most (shortest wavelength of the surface) / this,
    /// so a large body in short waves gets more nodes (btBuoyancyWaterPatchNodes; up to 64 per side). The patch's
    /// error falls like the fourth power of the spacing (its measured error per setting: docs/benchmarks/waves_lod.csv).
    /// 0 = the fixed waterPatchNodes. Default 16, finite, ≥ 0.
    /// A patch with at least as many nodes as the points it would stand for (the mesh's vertices or the samples, plus
    /// the drag clusters) is not built: those points are then queried exactly (cheaper, and exact).
    double waterPatchNodesPerWavelength = 16.0;
    /// Temporal level of detail (buoyancy::TemporalLevelOfDetail): evaluate the hydrostatics and drag exactly
    /// every K-th substep and predict them in between by extrapolating the last four exact evaluations in time
    /// (a cubic), moved to the body's actual pose through the linear hydrostatic stiffness (heave through the
    /// waterline area; roll and pitch through the waterplane's moments, which the exact-mesh methods compute:
    /// hydrostaticStiffnessCorrection), so that only what the waves drive is extrapolated and a bobbing or rolling
    /// body keeps its energy. A body predicts only while its pose and velocity stay within hydrostaticsReuseTolerance
    /// of the ones extrapolated the same way (a contact or a teleport makes it evaluate exactly), while its submerged
    /// volume is not about to saturate (a wave overrunning it), while its heave is slow against the interval
    /// (ω K dt ≤ 0.3, ω² = ρ g A_waterline / m_eff), and while the last check of the predictor against an exact
    /// evaluation passed. Three misses in four checks halve the body's own interval (down to 2); passes double it
    /// back. Bodies of one world take turns (staggered by registration order), so the cost per substep stays even;
    /// results are deterministic. getLastResult().predicted says which substeps were predicted. Ignored (exact every
    /// substep) for deformable bodies and on a device backend.
    /// 0 (default) = automatic: an exact evaluation at least every 1/30 s (btBuoyancyAutomaticInterval: every
    /// substep up to 30 substeps/s, every 2nd at 60/s, every 4th at 120/s, every 8th at 240/s), longer when
    /// errorBudget allows it (btBuoyancyEvaluationPeriod: up to 1/15 s). 1 = exact every substep. 2..16: that K.
    /// Measured on the benchmark's 3,400-triangle boat in its 4-wave sea at 240 substeps/s against exact wave queries
    /// (docs/benchmarks/temporal_lod.csv): the default predicts ≈ 84 % of the substeps and leaves the force error's
    /// mean and 99th percentile where exact evaluation has them (the wave patch's). Energy: an undamped bobbing box
    /// and sphere and a rolling box keep theirs within 0.14 % a minute (tests/bullet/TemporalLodTest.cpp,
    /// DynamicsTest.cpp).
    int hydrostaticsInterval = 0;
    /// Largest prediction error accepted by hydrostaticsInterval's checks, as a fraction of the body's full
    /// buoyancy ρ g V (force; a force error of x is a submerged-volume error of x·V) and of ρ g V × its bounding
    /// diameter (torque); the pose check allows the draft change that would change the force by this fraction
    /// (HydrostaticsHistory::poseDeviation, correctedPoseDeviation). A failed check makes the body evaluate exactly
    /// for the next interval. Default 1e-4 (0.01 %: the accuracy asked of the submerged volume); with an errorBudget
    /// and an automatic interval the tolerance used is at least errorBudget / 2 (btBuoyancyResolveReuseTolerance).
    /// Finite, > 0, ≤ 1.
    double hydrostaticsReuseTolerance = 1e-4;

    ///@name Added mass (design.md 2.7)
    /// Apply added mass to the linear motion (rotation has none): C_a ρ_w V_sub across the water's up, and along it
    /// (heave) the larger of that and the waterplane's c_wp ρ_w A_waterline^(3/2). Keeps light bodies (density
    /// ratio ≪ 1) stable at game time steps and gives flat floating bodies their heave period.
    bool addedMass = true;
    double addedMassCoefficient = 0.5; ///< C_a, dimensionless, ≥ 0; 0.5 is exact for a fully submerged sphere
    /// c_wp, dimensionless, ≥ 0 (0: C_a ρ_w V_sub along up too). The default 0.2 gives a floating square plate 0.88
    /// of its high-frequency heave added mass (DNV-RP-H103: 0.227 ρ_w A^(3/2)) and a half-immersed sphere 0.53 of
    /// its displaced mass (Hulme: 0.43–0.83 over the frequencies of its heave); see design.md 2.7.
    double addedMassWaterplaneCoefficient = 0.2;
    /// How the water's own acceleration Du/Dt (btWaterSurface::accelerations at the centre of buoyancy, one query per
    /// body and substep, only under water that changes over time) acts on the linear motion (design.md 2.7, "The
    /// water's acceleration"). Default None (no query): the terms take Du/Dt at one point, right for bodies small
    /// against the wavelength (a buoy, an ROV, debris) and not for a hull as long as the waves; turn them on for such
    /// bodies (AddedMassAndFroudeKrylov makes a small body ride the waves' orbits).
    btWaterAccelerationForce waterAcceleration = btWaterAccelerationForce::None;

    ///@name Features
    bool buoyancyEnabled = true; ///< pressure force and torque (design.md 2.3); off leaves only drag

    ///@name Bullet collision shapes (btBuoyancyShape::fromCollisionShape)
    /// The largest relative volume error allowed when a curved collision shape (sphere, capsule, cylinder, cone)
    /// is tessellated (an inscribed polyhedron, refined until its volume is this close to the shape's), in
    /// (0, 0.1]. Default 1e-3 (0.1 %); design.md 8.3 has the triangle counts it gives.
    double curvedShapeTolerance = 1e-3;

    /// Check every field. @throws std::invalid_argument whose message names the field and the value
    void validate() const;
};

/// The interval hydrostaticsInterval = 0 stands for at a substep of dt seconds: the largest K ≤ 16 with
/// K·dt ≤ periodSeconds (at least 1). The default period is the library's: an exact evaluation every 1/30 s.
int btBuoyancyAutomaticInterval(double dt, double periodSeconds = 1.0 / 30.0);

/// Temporal level of detail with hydrostaticsInterval = 0: the longest time between exact evaluations, s.
/// Without an error budget 1/30 s. With settings.errorBudget > 0, the longest period of the measured temporal
/// error model whose worst force error × kLodSafetyFactor (2) fits the budget (a force error of x % of ρ g V is a
/// submerged-volume error of x % of V), never below 1/30 s. The model (docs/benchmarks/temporal_lod.csv: the
/// 3,400-triangle boat in the scaling sea at 240 substeps/s, tolerance 0.2 %; other bodies and seas can differ):
/// 33 ms 0.21 %, 50 ms 0.24 %, 67 ms 0.28 %.
/// @param[out] modelErrorPct  optional: the model's worst force error at that period, % of ρ g V (0 at the default)
double btBuoyancyEvaluationPeriod(const btBuoyancySettings& settings, double* modelErrorPct = nullptr);

/// settings.hydrostaticsInterval resolved at a substep of dt seconds: itself when > 0, else
/// btBuoyancyAutomaticInterval(dt, btBuoyancyEvaluationPeriod(settings)).
int btBuoyancyResolveInterval(const btBuoyancySettings& settings, double dt);

/// The prediction tolerance used (fraction of ρ g V): settings.hydrostaticsReuseTolerance, raised to
/// errorBudget / 200 (the budget in %, halved) when the interval is automatic and a budget is set.
double btBuoyancyResolveReuseTolerance(const btBuoyancySettings& settings);

/// The concrete method Auto stands for, given the mesh's triangle count (delegates to
/// buoyancy::resolveMethod, the one place that decides the library default); others are returned unchanged.
btBuoyancyMethod btBuoyancyResolveMethod(const btBuoyancySettings& settings, std::size_t triangleCount);

/// The texture size used for a resolved sampled method: settings.textureSize, or the budget's pick
/// (errorBudget > 0), or the library default when 0.
int btBuoyancyResolveTextureSize(const btBuoyancySettings& settings, btBuoyancyMethod resolved);

/// Nodes per side of a body's wave patch (btBuoyancyAction; design.md 2.5): 0 when settings.waterPatchNodes is 0
/// (exact queries), else max(waterPatchNodes, ⌈2 r · waterPatchNodesPerWavelength / λ_min⌉ + 4) capped at 64 — the
/// patch's interior spans 2r with spacing 2r / (nodes − 4) (buoyancy::WaterPatch).
/// @param footprintRadius     r, half the side of the body's footprint, m (its bounding-sphere radius)
/// @param shortestWavelength  λ_min of the surface, m (btWaterSurface::shortestWavelength; 0 = unknown: the fixed count)
int btBuoyancyWaterPatchNodes(const btBuoyancySettings& settings, double footprintRadius, double shortestWavelength);

/// What the automatic level of detail picked for a mesh.
struct btBuoyancyLevelOfDetail {
    btBuoyancyMethod method = btBuoyancyMethod::ExactMesh; ///< concrete method
    int textureSize = 0;                ///< N (0 for exact-mesh)
    double modelVolumeErrorPct = 0;     ///< the error model's worst volume error for it, % of the volume
    double budgetPct = 0;               ///< settings.errorBudget (0: no budget, the library default rule)
    bool withinBudget = true;           ///< false when no configuration fits (the most accurate one is used)
    /// Temporal level of detail (hydrostaticsInterval 0): longest time between exact evaluations, s
    /// (btBuoyancyEvaluationPeriod); 0 when the settings fix the interval.
    double evaluationPeriod = 0;
    std::string description;            ///< one line for logs and the CLI, e.g. "exact-coverage 128 (…)"
};

/// The method and texture size `settings` resolve to for a mesh of `triangleCount` triangles, and why
/// (the same decision btBuoyancyShape::create makes). @throws std::invalid_argument for bad settings
btBuoyancyLevelOfDetail btBuoyancyPickLevelOfDetail(const btBuoyancySettings& settings, std::size_t triangleCount);
