#pragma once
/// @file LodStudy.h
/// What the level-of-detail approximations of design.md 2.5 cost in accuracy and buy in time:
///  - waves_lod.csv: exact-mesh hydrostatics in the scaling run's Gerstner sea with the water heights interpolated from a
///    per-body grid of M×M queries (btBuoyancySettings::waterPatchNodes) against the same clipping with one exact
///    query per vertex, at the same wave field (several poses and times);
///  - drag_lod.csv: the drag force and torque of btBuoyancyAction with the drag samples merged into at most K
///    clusters (btBuoyancySettings::dragClusters) against every fine sample (K = 0), flat water, fixed velocity.

#include "benchmark/BenchShapes.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace buoyancy::bench {

/// Run both studies on `shapes` (the wave study only on the shapes named in `waveShapes`), write the two CSVs
/// into `outDir`, and return Markdown lines summarising the worst errors and the speed-ups.
std::string runLodStudy(const std::vector<BenchShape>& shapes, const std::vector<std::string>& waveShapes,
                        const std::string& outDir, bool quick, std::ostream& log);

}  // namespace buoyancy::bench
