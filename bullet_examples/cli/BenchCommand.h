#pragma once
/// @file BenchCommand.h
/// `buoyancy bench [--quick] [--out DIR] [--parts LIST]`: the benchmark. Writes into DIR
///   speed_vs_error.csv   every method × texture × shape × pose in flat water (part speed): errors against the exact
///                        clip and ns per body-substep (drag on, one thread); and the wave rows (part waves): the wave
///                        methods × box, cylinder, hull × the swell and chop seas × poses near the local surface,
///                        errors against the wave reference, ns per body-substep and ns of the hydrostatics alone,
///   fig9_sphere_volume.csv  the paper's Fig. 9 (sphere R = 0.5, volume against depth),
///   scaling.csv          1…1000 bodies in Gerstner waves, 1 and 2 threads (and "no-lod" rows),
///   waves_lod.csv, drag_lod.csv  the error the level of detail adds and the time it saves (part lod),
///   summary.md           the headline table and goals P1–P3 as measured (also printed).
/// --quick runs a reduced set (3 shapes, 2 textures, 4 poses, 4 wave poses, ≤ 100 bodies) in well under 30 s; plots are
/// made from the CSVs by scripts/bench_plots.py (scripts/bench.sh runs both).

#include <CLI/CLI.hpp>

#include <string>

namespace buoyancy::cli {

/// Options of `buoyancy bench`.
struct BenchOptions {
    bool quick = false;            ///< the reduced, fast set (smoke test)
    std::string out = "bench-results"; ///< output folder (created when missing)
    /// which parts to run, comma-separated: speed (flat water), waves (the wave rows), fig9, scaling, lod, primitives
    /// (Bullet primitives in flat water; also: opencl)
    std::string parts = "speed,waves,fig9,scaling,lod,primitives";
    /// body counts of the opencl part, comma-separated, each 1 to 100,000 (empty: 1,10,100,1000; --quick: 1,10)
    std::string openclBodies;
    /// body counts of the scaling part, comma-separated, each 1 to 100,000 (empty: the full set; set: only the public-API
    /// rows of the default settings at these counts, 3 windows each)
    std::string scalingBodies;
    /// thread counts of the scaling part, comma-separated, each 1 to 1,024 (empty: 1,2)
    std::string scalingThreads;
};

/// Register the `bench` subcommand on `app`.
void addBenchCommand(CLI::App& app, BenchOptions& options);

/// Run the benchmark. @throws UsageError for bad options or an unwritable folder. @return kExitOk
int runBench(const BenchOptions& options);

}  // namespace buoyancy::cli
