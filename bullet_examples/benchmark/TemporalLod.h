#pragma once
/// @file TemporalLod.h
/// The temporal level of detail (btBuoyancySettings::hydrostaticsInterval) measured: a small fleet of
/// the scaling model in the scaling sea at 240 substeps/s, for several intervals K, one thread. Per K: the time per
/// body-substep of stepSimulation (Bullet included) and, at every substep after a 2 s settling, the error of the
/// pressure force and torque the action applied against an exact evaluation (every triangle clipped, one exact
/// wave query per vertex) at the body's pose and the water time of that substep. The errors of K = 1 are the
/// default evaluation's own (the wave patch's); the difference is what prediction adds. Also per K: the energy an
/// undamped bobbing box (2 × 1 × 2 m, density ratio 0.5, released 0.1 m below equilibrium, flat water, drag off)
/// gains or loses over 60 s at 240 substeps/s, against its initial energy above rest (the oracle: kinetic +
/// gravity + the wall-sided buoyancy potential ρ g A d²/2); exact evaluation every substep keeps it to ≈ 0.01 %.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace buoyancy::bench {

/// What to run.
struct TemporalLodOptions {
    /// (hydrostaticsInterval, hydrostaticsReuseTolerance) pairs; interval 0 is the automatic default, tolerance 0 the
    /// library's default tolerance.
    std::vector<std::pair<int, double>> configurations{{1, 0.0}, {0, 0.0}, {4, 0.0}, {4, 0.002}, {8, 0.002},
                                                       {12, 0.002}, {16, 0.002}};
    int bodies = 5;              ///< boats, 17 m apart, varied headings
    /// A last row at the default settings with this many boats placed as in the scaling run (floating on the local
    /// water surface, four body lengths apart), settled for fleetSettleSeconds, errors over fleetSeconds: the rare
    /// worst substeps of a fleet (0: none).
    int fleetBodies = 200;
    double fleetSettleSeconds = 4.0;  ///< simulated before the fleet row's errors are taken, s
    double fleetSeconds = 5.0;        ///< simulated while the fleet row's errors are taken, s
    double settleSeconds = 2.0;  ///< simulated before errors are taken, s
    double seconds = 10.0;       ///< simulated while errors are taken, s
    double energySeconds = 60.0; ///< the undamped box's run, s
};

/// One row of temporal_lod.csv.
struct TemporalLodRow {
    std::string model;               ///< model id
    std::size_t triangles = 0;       ///< triangles of the model
    int interval = 0;                ///< hydrostaticsInterval asked for (0: automatic)
    double tolerance = 0;            ///< hydrostaticsReuseTolerance used, fraction of ρ g V
    int resolvedInterval = 0;        ///< the interval used at 240 substeps/s
    int bodies = 0;                  ///< bodies
    double predictedPct = 0;         ///< substeps whose hydrostatics were predicted, % of body-substeps
    double nsPerBodySubstep = 0;     ///< stepSimulation wall time / (bodies × substeps), ns, one thread
    double forceErrorMeanPct = 0;    ///< |F − F_exact| / (ρ g V), mean over body-substeps, %
    double forceErrorP99Pct = 0;     ///< 99th percentile, %
    double forceErrorMaxPct = 0;     ///< worst, %
    double torqueErrorMaxPct = 0;    ///< |τ − τ_exact| / (ρ g V × bounding diameter), worst, %
    double energyDriftPct = 0;       ///< undamped bobbing box: worst |E(t) − E(0)| over 60 s, % of E(0) above rest
    double sphereAmplitudeChangePct = 0; ///< undamped bobbing sphere: heave amplitude, last 5 s against first 5 s, %
};

/// Run every interval of `options` with `mesh` (density 500 kg/m³, the library's default settings otherwise).
std::vector<TemporalLodRow> runTemporalLod(const TriangleMesh& mesh, const std::string& model,
                                           const TemporalLodOptions& options, std::ostream& log);

/// Write temporal_lod.csv.
void writeTemporalLodCsv(const std::string& path, const std::vector<TemporalLodRow>& rows);

/// Markdown lines for the summary.
std::string temporalLodMarkdown(const std::vector<TemporalLodRow>& rows);

}  // namespace buoyancy::bench
