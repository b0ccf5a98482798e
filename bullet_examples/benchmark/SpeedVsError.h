#pragma once
/// @file SpeedVsError.h
/// The speed-against-error table: every method × texture size × shape × pose in flat water, with the errors
/// against the exact polyhedral clip of the same mesh (tests/oracles/PolyhedralOracle) and the time of one
/// body-substep with drag on, one thread; and the wave rows: the wave methods × the wave shapes × the seas × poses
/// near the local surface, with the errors against the divergence-theorem reference (tests/oracles/WaveOracle), the
/// time of the hydrostatics alone and of the body-substep with drag on.

#include "benchmark/BenchSeas.h"
#include "benchmark/BenchShapes.h"
#include "benchmark/BodyTiming.h"

#include <limits>

#include <iosfwd>
#include <string>
#include <vector>

namespace buoyancy::bench {

/// One row of docs/benchmarks/speed_vs_error.csv.
struct SpeedErrorRow {
    std::string shape;          ///< shape id
    std::size_t triangles = 0;  ///< triangles of the mesh
    std::string method;         ///< default, texel-centre, exact-coverage, exact-mesh, sub-texel, lod, probes, downward-faces, tangent-plane, fitted-plane
    int texture = 0;            ///< N of N×N (0 for mesh and probe methods; the resolved N for default)
    std::string variant;        ///< default: what it resolved to; lod: budget-X%:resolved; probes: hull-N / grid-N; else empty
    std::size_t samples = 0;    ///< elements summed per substep: samples, probes or triangles
    std::string pose;           ///< pose id (BenchPose::id)
    double volume_error_pct = 0; ///< |V − V_exact| / V_body, %
    double cob_error_pct = 0;    ///< |C_B − C_B,exact| / bounding-box diagonal, %
    double torque_error_pct = 0; ///< |τ − τ_exact| about the COM / (ρ g V_body × diagonal), %
    double ns_per_body_substep = 0; ///< one btActionInterface::updateAction with drag, one thread, ns
    std::string water = "flat";  ///< the water: flat (y = 0), swell or chop (BenchSeas.h)
    /// One updateAction with drag off (the hydrostatics and their impulses alone), one thread, ns; NaN (an empty
    /// cell) where not measured (the flat rows)
    double ns_hydrostatics = std::numeric_limits<double>::quiet_NaN();
    /// The reference submerged volume / the body's volume (0..1): with cob_error_pct it gives the error of the
    /// centre of buoyancy's first moment, |ΔC_B| V_sub / (V · diagonal)
    double submerged_fraction = 0;
};

/// What to run.
struct SpeedErrorOptions {
    std::vector<int> textures{32, 64, 128, 256, 512, 1024};   ///< N for the sampled methods
    std::vector<double> drafts{0.1, 0.3, 0.5, 0.7, 0.9};      ///< draft fractions
    std::vector<double> heels{0, 20, 45};                      ///< heel angles, degrees
    std::vector<int> hullProbes{32, 128};                      ///< hull probe counts
    std::vector<int> gridProbes{64, 512};                      ///< grid probe counts
    std::vector<double> budgets{1.0, 0.1, 0.01};               ///< error budgets (%) for the `lod` rows
    TimingOptions timing;                                      ///< timer settings
    ///@name Wave rows (waveBenchPoses: times × offsets, heels in turn)
    std::vector<double> waveTimes{0.8, 2.4, 4.0, 5.6, 7.2};   ///< water times of the poses, s
    std::vector<double> waveOffsets{-0.25, 0.0, 0.25};        ///< body centre above the local water, fraction of its height
    std::vector<double> waveHeels{0, 15, 30};                 ///< heel angles taken in turn, degrees
    std::vector<int> waveHullProbes{32};                      ///< hull probe counts in waves
    std::vector<int> waveGridProbes{64};                      ///< grid probe counts in waves
    int oracleWaterlineLevels = 5;                            ///< WaveOracleOptions::waterlineLevels of the reference
    ///@}
};

/// Measure every configuration on every shape and pose. Configurations that cannot be built (an atlas that
/// does not fit a small texture) are reported in `log` and left out.
std::vector<SpeedErrorRow> runSpeedVsError(const std::vector<BenchShape>& shapes, const SpeedErrorOptions& options,
                                           std::ostream& log);

/// The wave rows: on every shape (waveBenchShapes) in every sea (benchSeas) at options.waveTimes × waveOffsets poses,
/// the methods default and exact-mesh (errors: what the btBuoyancyAction computed at the pose; times: the action with
/// drag on, and with drag off for ns_hydrostatics), tangent-plane and fitted-plane (PlaneClipMethods.h; hydrostatics
/// alone, and with the library's drag path), probes and downward-faces (ComparisonMethods.h, with and without their
/// drag). Errors against tests/oracles/WaveOracle with maxEdge = max(shortest wavelength / 40, 1 % of the bounding-box
/// diagonal) and waterMax = the surface's heightBounds over the body's footprint; torques about the body's centre of
/// mass. Progress and per-configuration worst errors go to `log`.
std::vector<SpeedErrorRow> runSpeedVsErrorWaves(const std::vector<BenchShape>& shapes, const std::vector<BenchSea>& seas,
                                                const SpeedErrorOptions& options, std::ostream& log);

/// Write the rows with the header
/// shape,triangles,method,texture,variant,samples,pose,volume_error_pct,cob_error_pct,torque_error_pct,ns_per_body_substep,
/// water,ns_hydrostatics,submerged_fraction (the last three added for the wave rows; ns_hydrostatics empty where NaN).
/// @throws std::runtime_error when the file cannot be written
void writeSpeedVsErrorCsv(const std::string& path, const std::vector<SpeedErrorRow>& rows);

}  // namespace buoyancy::bench
