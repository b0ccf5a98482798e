#pragma once
/// @file SpeedVsError.h
/// The speed-against-error table: every method × texture size × shape × pose, with the errors
/// against the exact polyhedral clip of the same mesh (tests/oracles/PolyhedralOracle) and the time of one
/// body-substep with drag on, one thread.

#include "benchmark/BenchShapes.h"
#include "benchmark/BodyTiming.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace buoyancy::bench {

/// One row of docs/benchmarks/speed_vs_error.csv.
struct SpeedErrorRow {
    std::string shape;          ///< shape id
    std::size_t triangles = 0;  ///< triangles of the mesh
    std::string method;         ///< default, texel-centre, exact-coverage, exact-mesh, sub-texel, lod, probes, downward-faces
    int texture = 0;            ///< N of N×N (0 for mesh and probe methods; the resolved N for default)
    std::string variant;        ///< default: what it resolved to; lod: budget-X%:resolved; probes: hull-N / grid-N; else empty
    std::size_t samples = 0;    ///< elements summed per substep: samples, probes or triangles
    std::string pose;           ///< pose id (BenchPose::id)
    double volume_error_pct = 0; ///< |V − V_exact| / V_body, %
    double cob_error_pct = 0;    ///< |C_B − C_B,exact| / bounding-box diagonal, %
    double torque_error_pct = 0; ///< |τ − τ_exact| about the COM / (ρ g V_body × diagonal), %
    double ns_per_body_substep = 0; ///< one btActionInterface::updateAction with drag, one thread, ns
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
};

/// Measure every configuration on every shape and pose. Configurations that cannot be built (an atlas that
/// does not fit a small texture) are reported in `log` and left out.
std::vector<SpeedErrorRow> runSpeedVsError(const std::vector<BenchShape>& shapes, const SpeedErrorOptions& options,
                                           std::ostream& log);

/// Write the rows with the header
/// shape,triangles,method,texture,variant,samples,pose,volume_error_pct,cob_error_pct,torque_error_pct,ns_per_body_substep.
/// @throws std::runtime_error when the file cannot be written
void writeSpeedVsErrorCsv(const std::string& path, const std::vector<SpeedErrorRow>& rows);

}  // namespace buoyancy::bench
