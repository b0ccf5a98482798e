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

/// One configuration on one shape, reduced over poses.
struct ConfigStats {
    std::string shape, method, variant;
    std::size_t triangles = 0, samples = 0;
    int texture = 0;
    double worstVolumePct = 0, worstCobPct = 0, worstTorquePct = 0; ///< max over poses, %
    double meanNs = 0;                                              ///< mean over poses, ns
};

/// Group rows by (shape, method, texture, variant), in first-seen order.
std::vector<ConfigStats> reduceConfigs(const std::vector<SpeedErrorRow>& rows);

/// The Markdown summary: headline table (default, texel-centre 1024, exact-coverage 128, exact-mesh per
/// shape), the speed goals (accuracy and cost from the table, 1,000 bodies in real time from the scaling rows), each with the numbers behind it.
std::string summaryMarkdown(const std::vector<SpeedErrorRow>& rows, const std::vector<ScalingRow>& scaling);

}  // namespace buoyancy::bench
