#pragma once
/// @file Summary.h
/// Reducing the speed-against-error rows to per-configuration figures (a configuration's error is
/// its worst volume and worst centre-of-buoyancy error over the poses, its time the mean) and checking the
/// the speed goals as measured, written as Markdown (docs/benchmarks/summary.md).

#include "benchmark/Scaling.h"
#include "benchmark/SpeedVsError.h"

#include <string>
#include <vector>

namespace buoyancy::bench {

/// One configuration on one shape in one water, reduced over poses.
struct ConfigStats {
    std::string shape, method, variant;
    std::string water = "flat"; ///< flat, swell or chop
    std::size_t triangles = 0, samples = 0;
    int texture = 0;
    double worstVolumePct = 0, worstCobPct = 0, worstTorquePct = 0; ///< max over poses, %
    /// Max over poses of the centre of buoyancy's first-moment error |ΔC_B| V_sub / (V · diagonal), a fraction
    /// (cob_error_pct / 100 × submerged_fraction).
    double worstCobMoment = 0;
    double meanNs = 0;                                              ///< mean over poses, ns
    /// Mean over poses of ns_hydrostatics, ns; NaN where not measured (the flat rows).
    double meanNsHydrostatics = 0;
    int poses = 0;                                                  ///< rows reduced
};

/// Group rows by (shape, water, method, texture, variant), in first-seen order.
std::vector<ConfigStats> reduceConfigs(const std::vector<SpeedErrorRow>& rows);

/// The accuracy bars the default is held to, per shape and water: worst submerged-volume error 0.1 % of the body's
/// volume, worst first-moment error of the centre of buoyancy |ΔC_B| V_sub / (V · diagonal) 1e-3.
constexpr double kVolumeBarPct = 0.1;
constexpr double kCobMomentBar = 1e-3; ///< see kVolumeBarPct

/// The Markdown summary: headline table (default, texel-centre 1024, exact-coverage 128, exact-mesh per
/// shape), the speed goals (accuracy and cost from the table, 1,000 bodies in real time from the scaling rows), each
/// with the numbers behind it; from the wave rows, a table per shape and sea, and per shape and water whether anything
/// measured is at least as accurate as the default and > 10 % faster, the default's worst errors against the bars, and
/// on the box in swell the default against tangent-plane (hydrostatics time and worst errors, same run).
std::string summaryMarkdown(const std::vector<SpeedErrorRow>& rows, const std::vector<ScalingRow>& scaling);

}  // namespace buoyancy::bench
