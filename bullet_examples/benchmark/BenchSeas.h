#pragma once
/// @file BenchSeas.h
/// The seas of the wave rows of the speed-against-error table (docs/benchmarks/README.md, "Wave rows"): `swell` is
/// the 4-wave Gerstner sea of the scaling rows (p3Sea, Scaling.h: the same definition, not a copy), `chop` a short,
/// steep sea defined here once.

#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <string>
#include <vector>

namespace buoyancy::bench {

/// The chop sea: four Gerstner waves of wavelengths 10, 7, 5.5 and 4 m (amplitudes 0.30, 0.22, 0.16, 0.12 m;
/// steepness Q 0.6, 0.65, 0.7, 0.7; directions (1, 0), (0.6, 0.8), (−0.5, 0.866), (0.8, −0.6) in x–z; phases 0.3,
/// 1.7, 4.0, 2.6 rad), Σ Q·A·k = 0.501 (each wave's A·k ≈ 0.18–0.20).
std::vector<btGerstnerWave> chopSea();

/// One named sea of the wave rows.
struct BenchSea {
    std::string name;                  ///< the `water` column: "swell" or "chop"
    std::vector<btGerstnerWave> waves; ///< the Gerstner waves (mean level 0, g = 9.81 m/s²)
};

/// The wave rows' seas, in CSV order: swell (p3Sea()), chop (chopSea()).
std::vector<BenchSea> benchSeas();

}  // namespace buoyancy::bench
